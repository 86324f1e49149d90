#include "amr/field_units.h"

#include <cmath>
#include <cstdio>

namespace amrvk::amr {

namespace {

bool endsWith(std::string_view s, std::string_view tail) {
    return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}

std::string codeUnitsOf(double perCodeUnit, const char* unit) {
    if (!(perCodeUnit > 0) || !std::isfinite(perCodeUnit)) return "";
    char buf[64];
    std::snprintf(buf, sizeof(buf), "code units (1 = %.5g %s)", perCodeUnit, unit);
    return buf;
}

}  // namespace

Quantity enzoQuantity(std::string_view field) {
    if (field == "Density" || (endsWith(field, "_Density") && field != "Electron_Density")) return Quantity::Density;
    if (field == "x-velocity" || field == "y-velocity" || field == "z-velocity") return Quantity::Velocity;
    if (field == "TotalEnergy" || field == "GasEnergy" || field == "InternalEnergy") return Quantity::SpecificEnergy;
    if (field == "Temperature" || field == "Dust_Temperature") return Quantity::Temperature;
    return Quantity::Unknown;
}

Quantity ramsesQuantity(std::string_view field) {
    if (field == "density") return Quantity::Density;
    if (field == "velocity_x" || field == "velocity_y" || field == "velocity_z") return Quantity::Velocity;
    if (field == "pressure") return Quantity::Pressure;
    return Quantity::Unknown;
}

std::string fieldUnits(Quantity q, const CodeUnits& u) {
    switch (q) {
        case Quantity::Density:
            return codeUnitsOf(u.density, "g/cm^3");
        case Quantity::Velocity:
            return codeUnitsOf(u.velocity, "cm/s");
        case Quantity::SpecificEnergy:
            return codeUnitsOf(u.velocity * u.velocity, "erg/g");
        case Quantity::Pressure:
            return codeUnitsOf(u.density * u.velocity * u.velocity, "dyn/cm^2");
        case Quantity::Temperature:
            return "K";
        case Quantity::Unknown:
            break;
    }
    return "";
}

}  // namespace amrvk::amr
