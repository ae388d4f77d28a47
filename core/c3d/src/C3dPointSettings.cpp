// What the header and the POINT group both say about the points: count, scale, rate and units.

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
    if (auto s = paramNumber(ps, "POINT", "SCALE")) {
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
        if (auto mm = c3dUnitToMm(take.units)) {
            take.unitToMm = *mm;
        } else {
            take.warnings.push_back("unknown POINT:UNITS \"" + take.units +
                                    "\"; assuming millimetres");
        }
    } else {
        take.warnings.push_back("no POINT:UNITS; assuming millimetres");
    }
}

}  // namespace c3d_detail
}  // namespace boneless
