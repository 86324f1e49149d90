#pragma once
// When a data set is in its simulation, as its reader found it (Model::attributes): the redshift of
// a cosmological Enzo run (ComovingCoordinates 1 and CosmologyCurrentRedshift), else the time in
// code units (Enzo InitialTime; AMReX, RAMSES, Chombo and `amrvk gen --time`: "time"). What
// `amrvk info` prints and the viewer shows for each step of a series.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace amrvk::amr {

struct StepTime {
    enum class Kind { Time, Redshift } kind = Kind::Time;
    double value = 0;  // code units of time, or the redshift z
};

// nullopt where the source records neither (raw bricks, cell files without a time) or records a
// value that is not a finite number.
std::optional<StepTime> stepTimeOf(const std::vector<std::pair<std::string, std::string>>& attributes);

// "z = 3.5" or "t = 0.125" (code units).
std::string describe(const StepTime& t);

}  // namespace amrvk::amr
