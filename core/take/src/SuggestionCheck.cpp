#include "boneless/SuggestionCheck.h"

#include <algorithm>
#include <map>

#include "boneless/C3dTake.h"

namespace boneless {

namespace {

Vec3 restPoint(const TriMesh& rest, const MarkerMapping& m) {
    if (m.face < 0 || m.face >= rest.faceCount()) return rest.V.row(m.vertex).transpose();
    Vec3 x = Vec3::Zero();
    for (int c = 0; c < 3; ++c) x += m.barycentric[c] * rest.V.row(rest.F(m.face, c)).transpose();
    return x;
}

}  // namespace

SuggestionCheck checkSuggestion(const TriMesh& rest, const C3dTake& take,
                                const Suggestion& suggestion, const Correspondence& reference,
                                double toleranceMm) {
    const double mmPerMeshUnit = take.unitToMm / suggestion.calibration.takeToMesh.scale;
    // Entries match by the point of the take their labels name, as solve resolves them: a
    // reference written "walker:C7", or "c7", compared nothing with "C7" as text.
    std::map<std::size_t, const MarkerMapping*> referenceOf;
    for (const MarkerMapping& m : reference.markers)
        if (const std::vector<std::size_t> p = take.pointsNamed(m.label); p.size() == 1)
            referenceOf[p[0]] = &m;
    SuggestionCheck check;
    std::vector<double> mm;
    for (const auto& proposal : suggestion.proposals) {
        const std::vector<std::size_t> point = take.pointsNamed(proposal.label);
        const auto found = point.size() == 1 ? referenceOf.find(point[0]) : referenceOf.end();
        const MarkerMapping* truth = found == referenceOf.end() ? nullptr : found->second;
        const MarkerMapping* mine = suggestion.map.find(proposal.label);
        if (!truth || !mine || truth->vertex < 0 || truth->vertex >= rest.vertexCount()) continue;
        mm.push_back((restPoint(rest, *mine) - restPoint(rest, *truth)).norm() * mmPerMeshUnit);
        check.distancesMm.push_back({proposal.label, mm.back()});
        check.within += mm.back() <= toleranceMm ? 1 : 0;
    }
    check.compared = static_cast<int>(mm.size());
    if (!mm.empty()) {
        std::sort(mm.begin(), mm.end());
        const std::size_t h = mm.size() / 2;
        check.medianMm = mm.size() % 2 ? mm[h] : (mm[h - 1] + mm[h]) / 2;
    }
    return check;
}

}  // namespace boneless
