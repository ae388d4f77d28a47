// Which POINTs are markers. Vicon and other modelling software store model outputs (joint
// angles, forces, moments, powers, scalars) and virtual points (segment axes, centre of mass) in
// the POINT data; the app must list markers only.

#include <array>
#include <map>
#include <set>

#include "C3dDetail.h"

namespace boneless::c3d_detail {

namespace {

std::string upper(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
    return out;
}

bool startsWithNoCase(std::string_view s, std::string_view prefix) {
    return s.size() >= prefix.size() && c3dNameEquals(s.substr(0, prefix.size()), prefix);
}

std::optional<C3dPointKind> kindFromTypeName(std::string_view t) {
    const std::string u = upper(t);
    if (u == "ANGLE" || u == "ANGLES") return C3dPointKind::Angle;
    if (u == "FORCE" || u == "FORCES" || u == "REACTION" || u == "REACTIONS")
        return C3dPointKind::Force;
    if (u == "MOMENT" || u == "MOMENTS") return C3dPointKind::Moment;
    if (u == "POWER" || u == "POWERS") return C3dPointKind::Power;
    if (u == "SCALAR" || u == "SCALARS") return C3dPointKind::Scalar;
    if (u == "VIRTUAL" || u == "VIRTUALS") return C3dPointKind::Virtual;
    return std::nullopt;
}

// Plug-in Gait and similar models emit each segment's axes as four points sharing a 3-letter
// stem: origin (O), anterior (A), lateral (L) and proximal (P), e.g. PELO PELA PELL PELP. A
// marker set containing all four of one stem would be a remarkable coincidence.
std::set<std::string> segmentAxisNames(const std::vector<C3dPoint>& points) {
    std::map<std::string, std::array<bool, 4>> stems;
    for (const auto& p : points) {
        if (p.name.size() != 4) continue;
        const std::string u = upper(p.name);
        const std::string suffixes = "OALP";
        const std::size_t k = suffixes.find(u[3]);
        if (k == std::string::npos) continue;
        stems[p.subject + ":" + u.substr(0, 3)][k] = true;
    }
    std::set<std::string> out;
    for (const auto& [stem, seen] : stems)
        if (seen[0] && seen[1] && seen[2] && seen[3])
            for (char s : std::string("OALP")) out.insert(stem + s);
    return out;
}

}  // namespace

void classifyPoints(const C3dParameters& params, std::vector<C3dPoint>& points) {
    for (auto& p : points) splitC3dLabel(p.label, p.subject, p.name);

    // POINT:TYPE_GROUPS pairs a list parameter with its type (ANGLES -> ANGLE, ...); without it
    // the usual list names apply.
    std::vector<std::pair<std::string, C3dPointKind>> lists = {
        {"ANGLES", C3dPointKind::Angle},   {"FORCES", C3dPointKind::Force},
        {"MOMENTS", C3dPointKind::Moment}, {"POWERS", C3dPointKind::Power},
        {"SCALARS", C3dPointKind::Scalar}, {"REACTIONS", C3dPointKind::Force}};
    if (const C3dParameter* tg = params.find("POINT", "TYPE_GROUPS")) {
        const auto s = tg->strings();
        for (std::size_t i = 0; i + 1 < s.size(); i += 2)
            if (auto kind = kindFromTypeName(s[i + 1])) lists.emplace_back(s[i], *kind);
    }
    std::map<std::string, C3dPointKind> byLabel;
    for (const auto& [list, kind] : lists)
        for (const auto& label : params.continuedStrings("POINT", list))
            if (!label.empty()) {
                bool latin1 = false;  // the reader has said so already, for the labels
                byLabel.emplace(upper(textFromC3d(label, latin1)), kind);
            }

    const std::set<std::string> axes = segmentAxisNames(points);
    for (auto& p : points) {
        p.kind = C3dPointKind::Marker;
        if (!byLabel.empty()) {
            auto it = byLabel.find(upper(p.label));
            if (it == byLabel.end()) it = byLabel.find(upper(p.name));
            if (it != byLabel.end()) {
                p.kind = it->second;
                continue;
            }
        }
        if (startsWithNoCase(p.name, "CentreOfMass") || startsWithNoCase(p.name, "CenterOfMass") ||
            (p.name.size() == 4 && !axes.empty() && axes.count(p.subject + ":" + upper(p.name))))
            p.kind = C3dPointKind::Virtual;
    }
}

}  // namespace boneless::c3d_detail
