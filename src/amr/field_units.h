#pragma once
// The units of a field's values as a reader knows them (amr::Field::units): the text `amrvk info`,
// the legend's default units line and Python's Volume.units show.
//
// Values stay what the file holds (code units for Enzo and RAMSES): transfer functions, --range,
// thresholds and sessions are all written in those numbers, so converting them would silently
// change every existing session. The text says what one code unit is instead:
// "code units (1 = 2.4967e-29 g/cm^3)", so a label never names a unit the numbers are not in.
// A field that is already physical (Enzo's Temperature, in K) gets its unit itself; a field
// whose quantity a reader cannot tell, or a data set without unit scales, gets "".
#include <string>
#include <string_view>

namespace amrvk::amr {

// cgs per code unit, from a data set's metadata; 0 = not known.
struct CodeUnits {
    double density = 0;   // g/cm^3 per code density unit
    double velocity = 0;  // cm/s per code velocity unit (code length / code time)
};

// What a field measures, as far as its name tells.
enum class Quantity { Unknown, Density, Velocity, SpecificEnergy, Pressure, Temperature };

// Enzo's field names: Density and every X_Density but Electron_Density (Enzo scales that one by
// m_e/m_p) are densities; x-, y-, z-velocity; TotalEnergy, GasEnergy and InternalEnergy are
// specific energies (code velocity^2); Temperature and Dust_Temperature are written in K.
Quantity enzoQuantity(std::string_view field);
// RAMSES's (ramses_reader: density, velocity_x/y/z, pressure; scalar_NN unknown).
Quantity ramsesQuantity(std::string_view field);

// The units text of a field measuring `q` under `units`: "code units (1 = X unit)" with X to 5
// significant digits (unit g/cm^3, cm/s, erg/g or dyn/cm^2), "K" for a temperature, "" when
// the quantity or its scale is unknown.
std::string fieldUnits(Quantity q, const CodeUnits& units);

}  // namespace amrvk::amr
