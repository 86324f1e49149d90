#include "amr/step_time.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace amrvk::amr {

namespace {

std::optional<std::string> valueOf(const std::vector<std::pair<std::string, std::string>>& attributes,
                                   const std::string& key) {
    for (const auto& [k, v] : attributes)
        if (k == key) return v;
    return std::nullopt;
}

// The whole text as one finite number (Enzo writes "0.5", "3.5e+00"; trailing blanks allowed).
std::optional<double> number(const std::optional<std::string>& text) {
    if (!text) return std::nullopt;
    const char* begin = text->c_str();
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin) return std::nullopt;
    while (*end == ' ' || *end == '\t') ++end;
    if (*end != '\0' || !std::isfinite(v)) return std::nullopt;
    return v;
}

}  // namespace

std::optional<StepTime> stepTimeOf(const std::vector<std::pair<std::string, std::string>>& attributes) {
    const std::optional<double> comoving = number(valueOf(attributes, "ComovingCoordinates"));
    if (comoving && *comoving != 0)
        if (const std::optional<double> z = number(valueOf(attributes, "CosmologyCurrentRedshift")))
            return StepTime{StepTime::Kind::Redshift, *z};
    for (const char* key : {"time", "InitialTime"})
        if (const std::optional<double> t = number(valueOf(attributes, key))) return StepTime{StepTime::Kind::Time, *t};
    return std::nullopt;
}

std::string describe(const StepTime& t) {
    char text[64];
    std::snprintf(text, sizeof(text), "%s = %.6g", t.kind == StepTime::Kind::Redshift ? "z" : "t", t.value);
    return text;
}

}  // namespace amrvk::amr
