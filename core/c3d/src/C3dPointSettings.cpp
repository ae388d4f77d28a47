// What the header and the POINT group both say about the points: count, scale, rate and units.

#include <algorithm>
#include <cmath>

#include "C3dTakeLayout.h"
#include "boneless/Text.h"

namespace boneless {

std::optional<double> c3dUnitToMm(std::string_view units) {
    std::string u;
    for (char c : units)
        if (isAsciiAlpha(c)) u.push_back(asciiLower(c));
    if (u == "mm") return 1.0;
    if (u == "cm") return 10.0;
    if (u == "dm") return 100.0;
    if (u == "m") return 1000.0;
    if (u == "in") return 25.4;
    if (u == "ft") return 304.8;
    // Writers truncate the string to the space they allotted ("mete", "millim"): accept any
    // prefix of at least three letters of a spelled-out unit.
    static const std::pair<const char*, double> spelled[] = {
        {"millimeters", 1.0},  {"millimetres", 1.0},  {"centimeters", 10.0}, {"centimetres", 10.0},
        {"decimeters", 100.0}, {"decimetres", 100.0}, {"meters", 1000.0},    {"metres", 1000.0},
        {"inches", 25.4},      {"feet", 304.8},       {"foot", 304.8}};
    if (u.size() >= 3)
        for (const auto& [word, mm] : spelled)
            if (std::string_view(word).substr(0, u.size()) == u) return mm;
    return std::nullopt;
}

namespace c3d_detail {

std::optional<double> paramNumber(const C3dParameters& ps, const char* group, const char* name,
                                  bool unsignedInt16) {
    const C3dParameter* p = ps.find(group, name);
    return p ? p->number(0, unsignedInt16) : std::nullopt;
}

std::size_t countOr(std::vector<std::string>& warn, double v, double max, const std::string& what,
                    std::size_t fallback) {
    if (std::isfinite(v) && v >= 0 && v <= max && v == std::floor(v))
        return static_cast<std::size_t>(v);
    warn.push_back(what + " is " + shortNumber(v) + ", not a count; using the header's " +
                   std::to_string(fallback));
    return fallback;
}

std::size_t pointCount(const C3dParameters& ps, const HeaderWords& h,
                       std::vector<std::string>& warn) {
    // Trust the parameters, say so when the header disagrees.
    std::size_t points = h.pointCount;
    if (auto u = paramNumber(ps, "POINT", "USED")) {
        points = countOr(warn, *u, 65535, "POINT:USED", h.pointCount);
        if (points != h.pointCount)
            warn.push_back("header says " + std::to_string(h.pointCount) +
                           " points, POINT:USED says " + std::to_string(points) +
                           "; using POINT:USED");
    }
    return points;
}

double pointScale(const C3dParameters& ps, const HeaderWords& h, std::vector<std::string>& warn) {
    double scale = h.scale;
    // Signed: a writer storing the scale as int16 writes -1 for float storage, not 65535.
    if (auto s = paramNumber(ps, "POINT", "SCALE", false)) {
        if (std::isfinite(*s) && *s != 0.0) {
            // Opposite signs are a disagreement on the storage, which reconcileStorage names.
            if (std::isfinite(h.scale) && h.scale != 0.0f && (h.scale < 0) == (*s < 0) &&
                std::fabs(*s - h.scale) > 1e-4 * std::fabs(*s))
                warn.push_back("header scale " + shortNumber(h.scale) +
                               " differs from POINT:SCALE " + shortNumber(*s) +
                               "; using POINT:SCALE");
            scale = *s;
        } else {
            warn.push_back("POINT:SCALE is " + shortNumber(*s) + "; using the header's scale " +
                           shortNumber(h.scale));
        }
    }
    return scale;
}

double frameRate(const C3dParameters& ps, const HeaderWords& h, std::vector<std::string>& warn) {
    double rate = h.rate;
    if (auto r = paramNumber(ps, "POINT", "RATE")) {
        if (!(std::isfinite(*r) && *r > 0.0)) {
            warn.push_back("POINT:RATE is " + shortNumber(*r) + "; using the header's " +
                           shortNumber(h.rate) + " Hz");
        } else {
            if (std::isfinite(h.rate) && std::fabs(*r - h.rate) > 1e-3 * std::fabs(*r))
                warn.push_back("header rate " + shortNumber(h.rate) +
                               " Hz differs from POINT:RATE " + shortNumber(*r) +
                               " Hz; using POINT:RATE");
            rate = *r;
        }
    }
    if (!std::isfinite(rate) || rate <= 0.0) {
        warn.push_back("frame rate is " + shortNumber(rate) + "; reported as 0");
        rate = 0.0;
    }
    return rate;
}

void readUnits(const C3dParameters& ps, C3dTake& take, bool& latin1) {
    if (const C3dParameter* u = ps.find("POINT", "UNITS")) {
        take.units = textFromC3d(u->string(), latin1);
        if (auto mm = c3dUnitToMm(take.units)) take.unitToMm = *mm;
    }
    if (const std::string w = fileUnitsWarning(take); !w.empty()) take.warnings.push_back(w);
}

std::string fileUnitsWarning(const C3dTake& take) {
    if (!take.parameters.find("POINT", "UNITS")) return "no POINT:UNITS; assuming millimetres";
    const std::string units = c3dFileUnits(take);
    if (c3dUnitToMm(units)) return "";
    return "unknown POINT:UNITS \"" + units + "\"; assuming millimetres";
}

}  // namespace c3d_detail
const std::vector<std::string>& c3dUnitSymbols() {
    static const std::vector<std::string> symbols = {"mm", "cm", "dm", "m", "in", "ft"};
    return symbols;
}

std::string c3dFileUnits(const C3dTake& take) {
    const C3dParameter* u = take.parameters.find("POINT", "UNITS");
    bool latin1 = false;
    return u ? c3d_detail::textFromC3d(u->string(), latin1) : std::string();
}

void setTakeUnits(C3dTake& take, const std::string& units, const std::string& from) {
    const bool file = units == "file";
    if (file && take.unitsFrom.empty()) return;  // read in them already, its warnings in order
    const std::optional<double> mm = file ? c3dUnitToMm(c3dFileUnits(take)) : c3dUnitToMm(units);
    if (!file && std::find(c3dUnitSymbols().begin(), c3dUnitSymbols().end(), units) ==
                     c3dUnitSymbols().end())
        throw C3dError(take.file, C3dError::kNoOffset,
                       "units \"" + units + "\" are none of file, " + joined(c3dUnitSymbols()));
    auto& warnings = take.warnings;
    const auto drop = [&](const std::string& w) {
        if (!w.empty())
            warnings.erase(std::remove(warnings.begin(), warnings.end(), w), warnings.end());
    };
    drop(take.markerSpan.doubt);
    drop(c3d_detail::fileUnitsWarning(take));
    if (file) {
        const bool stated = take.parameters.find("POINT", "UNITS") != nullptr;
        take.units = stated ? c3dFileUnits(take) : std::string("mm");
        take.unitsFrom.clear();
        // What the reader said of the file's units is true again.
        if (const std::string w = c3d_detail::fileUnitsWarning(take); !w.empty())
            warnings.insert(warnings.begin(), w);
    } else {
        take.units = units;
        take.unitsFrom = from;
    }
    take.unitToMm = mm.value_or(1.0);
    take.markerSpan = c3d_detail::judgeMarkerSpan(take, take.markerSpan.stored);
    if (!take.markerSpan.doubt.empty()) warnings.push_back(take.markerSpan.doubt);
}

}  // namespace boneless
