#include "boneless/MarkerSuggestion.h"

#include <limits>
#include <set>

#include "boneless/C3dTake.h"
#include "boneless/Error.h"

namespace boneless {

Suggestion suggestMappings(const TriMesh& rest, const C3dTake& take,
                           const Correspondence& partial) {
    if (partial.markers.size() < 4)
        throw Error(
            "suggesting correspondences needs at least 4 mapped markers to align the "
            "take, the map has " +
            std::to_string(partial.markers.size()));
    partial.checkMesh(rest.vertexCount(), "the mesh");
    const std::vector<std::size_t> mapped = partial.resolve(take);
    Positions restPositions(mapped.size(), 3);
    for (size_t k = 0; k < mapped.size(); ++k)
        restPositions.row(k) = rest.V.row(partial.markers[k].vertex);

    Suggestion out;
    out.calibration = calibrate(take, mapped, restPositions);
    out.map = partial;
    const Similarity& s = out.calibration.takeToMesh;
    std::set<int> taken;
    for (const auto& m : partial.markers) taken.insert(m.vertex);
    std::set<std::size_t> mappedPoints(mapped.begin(), mapped.end());

    // Markers occluded at the calibration frame are placed from the first frame that shows them.
    for (std::size_t p : take.markerIndices()) {
        if (mappedPoints.count(p)) continue;
        std::optional<Eigen::Vector3d> seen = take.samples.position(out.calibration.frame, p);
        for (std::size_t f = 0; !seen && f < take.frameCount(); ++f)
            seen = take.samples.position(f, p);
        if (!seen) continue;  // never visible: nothing to suggest
        const Vec3 x = s.apply(*seen);
        int best = -1;
        double bestDistance = std::numeric_limits<double>::infinity();
        for (int v = 0; v < rest.vertexCount(); ++v) {
            if (taken.count(v)) continue;
            const double d = (rest.V.row(v).transpose() - x).squaredNorm();
            if (d < bestDistance) best = v, bestDistance = d;
        }
        if (best < 0) break;
        taken.insert(best);
        MarkerMapping m;
        m.label = take.points[p].name.empty() ? take.points[p].label : take.points[p].name;
        m.vertex = best;
        // Mesh units back to the take's, then to millimetres.
        m.offsetMm = std::sqrt(bestDistance) / s.scale * take.unitToMm;
        m.extraJson = R"({"suggested": true})";
        out.map.markers.push_back(m);
        ++out.suggested;
    }
    return out;
}

}  // namespace boneless
