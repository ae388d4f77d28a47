#include "boneless/MarkerSuggestion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>

#include "boneless/C3dTake.h"
#include "boneless/Error.h"
#include "boneless/Reconstruction.h"

namespace boneless {

namespace {

// A proposal is sure when its marker lies at most this far from it on the best-fitted frame
// (markers sit 10 to 20 mm off the skin)…
constexpr double kFarMm = 40.0;
// …and no vertex more than kOtherPartMm away from it on the rest mesh (another limb, the other
// side) follows the marker within kAmbiguity times its RMS distance plus kAmbiguityMm.
constexpr double kOtherPartMm = 150.0;
constexpr double kAmbiguity = 1.5;
constexpr double kAmbiguityMm = 10.0;
// Frames the fit is scored on. Measured on CMU 85_02 from 6 picks (shoulders, wrists, ankles):
// 11 of 35 land within 3 cm from the calibration frame alone, 14 from 9 frames, 14 to 15 from
// 25; refitting with the sure proposals added pulled the others onto their errors (9 of 35).
constexpr int kScoredFrames = 25;

struct Proposal {
    int vertex = -1;
    double distance = 0;       // RMS distance to its marker over the scored frames, mesh units
    double otherDistance = 0;  // the same for the best vertex on another part, mesh units
    double atFrame = 0;        // to its marker at the best-fitted frame, mesh units
};

// The free vertex of least cost (mean squared distance to the marker), and the least cost found
// on another part of the body (farther than otherPart from it on the rest mesh).
Proposal propose(const TriMesh& rest, const Eigen::VectorXd& cost, const std::set<int>& taken,
                 double otherPart) {
    Proposal best;
    double least = std::numeric_limits<double>::infinity();
    for (int v = 0; v < rest.vertexCount(); ++v)
        if (cost[v] < least && !taken.count(v)) least = cost[v], best.vertex = v;
    if (best.vertex < 0) return best;
    best.distance = std::sqrt(least);
    double other = std::numeric_limits<double>::infinity();
    const Vec3 home = rest.V.row(best.vertex).transpose();
    for (int v = 0; v < rest.vertexCount(); ++v)
        if (cost[v] < other && (rest.V.row(v).transpose() - home).norm() > otherPart)
            other = cost[v];
    best.otherDistance = std::sqrt(other);
    return best;
}

// The calibration frame and frames spread over the take: poses that tell body parts apart.
std::vector<int> scoringFrames(const C3dTake& take, int frame) {
    std::vector<int> frames{frame};
    const int n = static_cast<int>(take.frameCount());
    for (int i = 0; i < kScoredFrames - 1; ++i)
        frames.push_back(std::min(n - 1, static_cast<int>((i + 0.5) * n / (kScoredFrames - 1))));
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    return frames;
}

}  // namespace

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
    const double meshUnitsPerMm = s.scale / take.unitToMm;
    const int frame = out.calibration.frame;

    // Every unmapped marker; one occluded at the best-fitted frame needs review.
    struct Wanted {
        std::size_t point;
    };
    std::vector<Wanted> wanted;
    const std::set<std::size_t> mappedPoints(mapped.begin(), mapped.end());
    for (std::size_t p : take.markerIndices())
        if (!mappedPoints.count(p)) wanted.push_back({p});
    auto aligned = [&](int f, std::size_t point) {
        const auto x = take.samples.position(f, point);
        return x ? s.apply(*x) : Vec3::Constant(std::nan(""));
    };

    // The pull: the mapped markers, as a take pulls them.
    std::vector<int> vertices;
    SolverOptions options;
    options.constraints = SolverOptions::Constraints::Soft;
    for (size_t k = 0; k < mapped.size(); ++k) {
        vertices.push_back(partial.markers[k].vertex);
        options.markerOffsets.push_back(partial.markers[k].offsetMm * meshUnitsPerMm);
    }
    Reconstruction solver;
    solver.prepare(rest, vertices, options);
    // The fit of each scored frame, and how near it comes to the unmapped markers (the median
    // of their distances to the nearest vertex): with a few picks, a crouch or a turn is fitted
    // worse than a stance.
    const std::vector<int> frames = scoringFrames(take, frame);
    std::vector<Positions> fits;
    std::vector<double> quality;
    for (int f : frames) {
        Positions T(mapped.size(), 3);
        for (size_t k = 0; k < mapped.size(); ++k) T.row(k) = aligned(f, mapped[k]).transpose();
        fits.push_back(solver.solve(T).V);
        std::vector<double> nearest;
        for (size_t w = 0; w < wanted.size() && fits.back().allFinite(); ++w) {
            const Vec3 x = aligned(f, wanted[w].point);
            if (x.allFinite())
                nearest.push_back(
                    (fits.back().rowwise() - x.transpose()).rowwise().norm().minCoeff());
        }
        std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
        quality.push_back(nearest.empty() ? std::numeric_limits<double>::infinity()
                                          : nearest[nearest.size() / 2]);
    }
    const size_t best = std::min_element(quality.begin(), quality.end()) - quality.begin();
    if (!std::isfinite(quality[best])) throw Error("the mapped markers give no fit of the mesh");
    out.fittedFrame = frames[best];
    out.fitted = fits[best];
    // Each marker's squared distance to each vertex over the scored frames, each frame weighted
    // by how well it is fitted: the right vertex stays near its marker however the actor moves,
    // where one frame's nearest may be a neighbour the fit slid under it.
    Eigen::MatrixXd cost = Eigen::MatrixXd::Zero(rest.vertexCount(), wanted.size());
    Eigen::VectorXd seen = Eigen::VectorXd::Zero(wanted.size());
    for (size_t i = 0; i < frames.size(); ++i) {
        if (!std::isfinite(quality[i])) continue;
        const double weight = std::pow(quality[best] / quality[i], 2);
        for (size_t w = 0; w < wanted.size(); ++w) {
            const Vec3 x = aligned(frames[i], wanted[w].point);
            if (!x.allFinite()) continue;
            cost.col(w) +=
                weight * (fits[i].rowwise() - x.transpose()).rowwise().squaredNorm().transpose();
            seen[w] += weight;
        }
    }
    std::vector<Proposal> proposals(wanted.size());
    std::vector<bool> sure(wanted.size(), false);
    std::set<int> taken(vertices.begin(), vertices.end());
    // Surest first, so that a vertex two markers want goes to the one closer to it.
    std::vector<std::pair<double, size_t>> order;
    for (size_t w = 0; w < wanted.size(); ++w)
        if (seen[w] > 0) order.push_back({cost.col(w).minCoeff() / seen[w], w});
    std::sort(order.begin(), order.end());
    for (const auto& [c, w] : order) {
        proposals[w] = propose(rest, cost.col(w) / seen[w], taken, kOtherPartMm * meshUnitsPerMm);
        if (proposals[w].vertex < 0) continue;
        taken.insert(proposals[w].vertex);
        Proposal& p = proposals[w];
        // The offset is the marker's height over its vertex where the mesh was fitted best.
        const Vec3 x = aligned(out.fittedFrame, wanted[w].point);
        p.atFrame = x.allFinite() ? (out.fitted.row(p.vertex).transpose() - x).norm() : 0.0;
        sure[w] = take.samples.valid(out.fittedFrame, wanted[w].point) &&
                  p.atFrame <= kFarMm * meshUnitsPerMm &&
                  p.otherDistance > kAmbiguity * p.distance + kAmbiguityMm * meshUnitsPerMm;
    }

    for (size_t w = 0; w < wanted.size(); ++w) {
        const Proposal& p = proposals[w];
        if (p.vertex < 0) continue;
        const C3dPoint& point = take.points[wanted[w].point];
        MarkerMapping m;
        m.label = point.name.empty() ? point.label : point.name;
        m.vertex = p.vertex;
        m.offsetMm = p.atFrame / meshUnitsPerMm;
        std::string reason;
        char text[120];
        if (!take.samples.valid(out.fittedFrame, wanted[w].point)) {
            reason = "not seen at the fitted frame";
        } else if (p.atFrame > kFarMm * meshUnitsPerMm) {
            std::snprintf(text, sizeof text, "%.0f mm from the fitted mesh", m.offsetMm);
            reason = text;
        } else if (!sure[w]) {
            std::snprintf(text, sizeof text,
                          "another part of the body follows it %.0f mm away, this one %.0f mm",
                          p.otherDistance / meshUnitsPerMm, p.distance / meshUnitsPerMm);
            reason = text;
        }
        m.extraJson = reason.empty() ? std::string(R"({"suggested": true})")
                                     : R"({"suggested": true, "needs_review": true, )"
                                       R"("review_reason": ")" +
                                           reason + "\"}";
        out.needsReview += reason.empty() ? 0 : 1;
        out.map.markers.push_back(m);
        ++out.suggested;
    }
    return out;
}

SuggestionCheck checkSuggestion(const TriMesh& rest, const C3dTake& take,
                                const Suggestion& suggestion, const Correspondence& reference,
                                double toleranceMm) {
    const double meshUnitsPerMm = suggestion.calibration.takeToMesh.scale / take.unitToMm;
    SuggestionCheck check;
    std::vector<double> mm;
    for (const auto& m : suggestion.map.markers) {
        if (m.extraJson.find("\"suggested\"") == std::string::npos) continue;
        const MarkerMapping* truth = reference.find(m.label);
        if (!truth || truth->vertex < 0 || truth->vertex >= rest.vertexCount()) continue;
        mm.push_back((rest.V.row(m.vertex) - rest.V.row(truth->vertex)).norm() / meshUnitsPerMm);
        check.within += mm.back() <= toleranceMm ? 1 : 0;
    }
    check.compared = static_cast<int>(mm.size());
    if (!mm.empty()) {
        std::sort(mm.begin(), mm.end());
        check.medianMm = mm[mm.size() / 2];
    }
    return check;
}

}  // namespace boneless
