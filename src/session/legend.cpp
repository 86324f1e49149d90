#include "session/legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/error.h"
#include "core/strings.h"

namespace amrvk::session {

namespace {

constexpr Named<LegendPlace> kPlaces[] = {{"side", LegendPlace::Side}, {"overlay", LegendPlace::Overlay}};

// m x 10^e, correctly rounded (10^-1 is not a double: divide by 10^1 instead of multiplying).
double scaled(double m, int e) { return e >= 0 ? m * std::pow(10.0, e) : m / std::pow(10.0, -e); }

// The exponent e of a step m x 10^e.
int stepExponent(double step) { return int(std::floor(std::log10(step) + 1e-9)); }

// "1.50e+07" -> "1.50e7", "2e-09" -> "2e-9".
std::string tidyExponent(std::string s) {
    const size_t e = s.find('e');
    if (e == std::string::npos) return s;
    std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
    const bool negative = !exponent.empty() && exponent[0] == '-';
    if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) exponent.erase(0, 1);
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    return mantissa + "e" + (negative ? "-" : "") + exponent;
}

// A value on its own (a degenerate range): six significant digits.
std::string shortNumber(double v) {
    if (v == 0) v = 0;  // -0 (e.g. ceil(-1e-9)) is "0"
    char text[48];
    std::snprintf(text, sizeof text, "%.6g", v);
    return tidyExponent(text);
}

void addMinor(std::vector<LegendTick>& ticks, double position) { ticks.push_back({position, false, "", ""}); }

// Nice ticks over [lo, hi] (lo < hi) of a value axis; `place` maps a value to its axis position.
template <typename Place>
void niceTicks(std::vector<LegendTick>& ticks, double lo, double hi, int maxMajor, Place place) {
    const double step = niceStep(hi - lo, maxMajor);
    const int e = stepExponent(step);
    const double m = std::round(scaled(step, -e));  // 1, 2, 5 (or 10)
    const int minorsPerStep = m == 2 ? 4 : 5;
    const double magnitude = std::max(std::fabs(lo), std::fabs(hi));
    // Minor ticks are multiples of step / minorsPerStep: index j counts them, every minorsPerStep-th is major.
    const double minorUnits = m / minorsPerStep;  // the minor step in units of 10^e
    const double first = std::ceil(scaled(lo, -e) / minorUnits - 1e-9);
    const double last = std::floor(scaled(hi, -e) / minorUnits + 1e-9);
    // Beyond double resolution (j + 1 == j) no tick is placed; the caller adds one at lo.
    if (!(last - first <= 4096) || first + 1 == first || last + 1 == last) return;
    const double lower = place(lo), upper = place(hi), slack = 1e-9 * (upper - lower);
    for (double j = first; j <= last; ++j) {
        const double value = scaled(j * minorUnits, e);
        const double exact = place(value);  // may round past an end by an ulp
        if (!(exact >= lower - slack && exact <= upper + slack)) continue;
        const double at = std::clamp(exact, lower, upper);
        if (std::fmod(j, minorsPerStep) == 0)
            ticks.push_back({at, true, tickLabel(value == 0 ? 0.0 : value, step, magnitude), ""});
        else
            addMinor(ticks, at);
    }
}

}  // namespace

LegendPlace parseLegendPlace(std::string_view text) { return parseNamed(kPlaces, text, "--legend-place"); }
const char* legendPlaceName(LegendPlace place) { return nameOf(kPlaces, place); }

double niceStep(double span, int maxTicks) {
    AMRVK_CHECK(span > 0 && std::isfinite(span) && maxTicks >= 1, "legend: no tick step for a span of ", span);
    const double raw = span / maxTicks;
    const int e = stepExponent(raw);
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (scaled(m, e) >= raw * (1 - 1e-12)) return scaled(m, e);
    return scaled(1.0, e + 1);
}

std::string tickLabel(double value, double step, double magnitude) {
    if (value == 0) return "0";
    const int e = stepExponent(step);
    char text[64];
    if (std::max(std::fabs(value), magnitude) < 1e5 && e >= -4) {
        std::snprintf(text, sizeof text, "%.*f", std::max(0, -e), value);
        return text;
    }
    const int ev = int(std::floor(std::log10(std::fabs(value))));
    std::snprintf(text, sizeof text, "%.*e", std::clamp(ev - e, 0, 16), value);
    return tidyExponent(text);
}

std::vector<LegendTick> legendTicks(double lo, double hi, bool logScale, int maxMajor) {
    AMRVK_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo <= hi, "legend: the range [", lo, ", ", hi,
                "] is not a finite ascending range");
    AMRVK_CHECK(maxMajor >= 2, "legend: at least 2 labelled ticks (got ", maxMajor, ")");
    std::vector<LegendTick> ticks;
    const auto identity = [](double v) { return v; };
    if (lo == hi) {
        if (logScale && lo == std::round(lo))
            ticks.push_back({lo, true, "10", shortNumber(lo)});
        else if (logScale && std::isfinite(std::pow(10.0, lo)))
            ticks.push_back({lo, true, shortNumber(std::pow(10.0, lo)), ""});
        else if (logScale)
            ticks.push_back({lo, true, "10", shortNumber(lo)});
        else
            ticks.push_back({lo, true, shortNumber(lo), ""});
        return ticks;
    }
    if (!logScale) {
        niceTicks(ticks, lo, hi, maxMajor, identity);
    } else {
        const double kLo = std::ceil(lo - 1e-9), kHi = std::floor(hi + 1e-9);
        const double vLo = std::pow(10.0, lo), vHi = std::pow(10.0, hi);
        if (kHi - kLo >= 1) {
            // Two or more decades: 10^k, every s-th labelled.
            auto count = [&](double step) { return std::floor(kHi / step) - std::ceil(kLo / step) + 1; };
            double s = 1;  // the first of 1, 2, 5, 10, 20, ... with at most maxMajor multiples in range
            for (double base = 1; count(s) > maxMajor && base <= kHi - kLo; base *= 10)
                for (double m : {2.0, 5.0, 10.0})
                    if (count(s) > maxMajor && count(m * base) >= 1) s = m * base;
            for (double k = kLo; k <= kHi; ++k) {
                if (std::fmod(k, s) == 0)
                    ticks.push_back({k, true, "10", shortNumber(k)});
                else
                    addMinor(ticks, k);
            }
            if (s == 1)  // every decade labelled: m x 10^k between them
                for (double k = std::floor(lo); k <= kHi; ++k)
                    for (int m = 2; m <= 9; ++m)
                        if (const double at = k + std::log10(double(m)); at >= lo && at <= hi) addMinor(ticks, at);
        } else if (std::isfinite(vHi) && vLo > 0) {
            // Within two decades: 1, 2 and 5 x 10^k labelled as numbers, the other digits minor.
            std::vector<LegendTick> digits;
            for (double k = std::floor(lo); k <= kHi + 1; ++k)
                for (int m = 1; m <= 9; ++m) {
                    const double at = k + std::log10(double(m));
                    if (!(at >= lo && at <= hi)) continue;
                    if (m == 1 || m == 2 || m == 5)
                        digits.push_back({at, true, tickLabel(scaled(m, int(k)), scaled(1, int(k)), vHi), ""});
                    else
                        addMinor(digits, at);
                }
            const auto majors =
                std::count_if(digits.begin(), digits.end(), [](const LegendTick& t) { return t.major; });
            if (majors >= 2)
                ticks = std::move(digits);
            else
                niceTicks(ticks, vLo, vHi, maxMajor, [](double v) { return std::log10(v); });  // under a factor 2.5
        } else {
            // 10^lo or 10^hi is not a double: nice ticks of the exponent, labelled 10^x.
            niceTicks(ticks, lo, hi, maxMajor, identity);
            for (LegendTick& t : ticks)
                if (t.major) t.exponent = std::exchange(t.label, "10");
        }
    }
    if (std::none_of(ticks.begin(), ticks.end(), [](const LegendTick& t) { return t.major; }))
        ticks.push_back({lo, true, logScale ? shortNumber(std::pow(10.0, lo)) : shortNumber(lo), ""});
    std::sort(ticks.begin(), ticks.end(),
              [](const LegendTick& a, const LegendTick& b) { return a.position < b.position; });
    return ticks;
}

std::string legendTitle(const Legend& legend, const std::string& field, bool logScale) {
    std::string title = legend.title.empty() ? field : legend.title;
    if (logScale) title += title.empty() ? "log10 scale" : " (log10 scale)";
    return title;
}

std::string legendUnits(const Legend& legend, const std::string& fieldUnits) {
    return legend.units.empty() ? fieldUnits : legend.units;
}

std::string legendTextError(const std::string& text) {
    return text.size() <= kMaxLegendTextBytes ? "" : strCat(text.size(), " bytes (at most ", kMaxLegendTextBytes, ")");
}

void checkLegendText(const Legend& legend) {
    for (const auto& [text, option] :
         {std::pair{&legend.title, "--legend-title"}, std::pair{&legend.units, "--legend-units"}}) {
        const std::string why = legendTextError(*text);
        AMRVK_CHECK(why.empty(), option, ": ", why);
    }
}

}  // namespace amrvk::session
