// amr/field_units: which quantity a field's name tells, and the units text of each quantity.
#include "amr/field_units.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace amrvk::amr;

TEST(FieldUnits, EnzoNamesTellTheirQuantity) {
    EXPECT_EQ(enzoQuantity("Density"), Quantity::Density);
    EXPECT_EQ(enzoQuantity("Dark_Matter_Density"), Quantity::Density);
    EXPECT_EQ(enzoQuantity("HI_Density"), Quantity::Density);
    EXPECT_EQ(enzoQuantity("Electron_Density"), Quantity::Unknown);  // scaled by m_e/m_p in Enzo
    EXPECT_EQ(enzoQuantity("z-velocity"), Quantity::Velocity);
    EXPECT_EQ(enzoQuantity("TotalEnergy"), Quantity::SpecificEnergy);
    EXPECT_EQ(enzoQuantity("GasEnergy"), Quantity::SpecificEnergy);
    EXPECT_EQ(enzoQuantity("Temperature"), Quantity::Temperature);
    EXPECT_EQ(enzoQuantity("density"), Quantity::Unknown);  // Enzo's names are case-sensitive
    EXPECT_EQ(enzoQuantity("Density_Gradient"), Quantity::Unknown);
}

TEST(FieldUnits, RamsesNamesTellTheirQuantity) {
    EXPECT_EQ(ramsesQuantity("density"), Quantity::Density);
    EXPECT_EQ(ramsesQuantity("velocity_x"), Quantity::Velocity);
    EXPECT_EQ(ramsesQuantity("pressure"), Quantity::Pressure);
    EXPECT_EQ(ramsesQuantity("scalar_00"), Quantity::Unknown);
    EXPECT_EQ(ramsesQuantity("Density"), Quantity::Unknown);
}

TEST(FieldUnits, TextNamesOneCodeUnitInCgsOrNothing) {
    const CodeUnits u{.density = 1.66e-24, .velocity = 2e7};
    EXPECT_EQ(fieldUnits(Quantity::Density, u), "code units (1 = 1.66e-24 g/cm^3)");
    EXPECT_EQ(fieldUnits(Quantity::Velocity, u), "code units (1 = 2e+07 cm/s)");
    EXPECT_EQ(fieldUnits(Quantity::SpecificEnergy, u), "code units (1 = 4e+14 erg/g)");
    EXPECT_EQ(fieldUnits(Quantity::Pressure, u), "code units (1 = 6.64e-10 dyn/cm^2)");
    EXPECT_EQ(fieldUnits(Quantity::Temperature, u), "K");  // written in K: no code unit
    EXPECT_EQ(fieldUnits(Quantity::Unknown, u), "");
    // 5 significant digits.
    EXPECT_EQ(fieldUnits(Quantity::Density, {.density = 2.4967023e-29}), "code units (1 = 2.4967e-29 g/cm^3)");
    // A scale that is not known (0) or not a positive finite number names no unit.
    EXPECT_EQ(fieldUnits(Quantity::Density, {.velocity = 1}), "");
    EXPECT_EQ(fieldUnits(Quantity::Pressure, {.density = 1}), "");
    EXPECT_EQ(fieldUnits(Quantity::Velocity, {.velocity = -3}), "");
    EXPECT_EQ(fieldUnits(Quantity::Velocity, {.velocity = INFINITY}), "");
}
