#include "boneless/MarkerSuggestion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "SuggestionSides.h"
#include "boneless/ActorCalibration.h"
#include "boneless/C3dTake.h"
#include "boneless/Error.h"
#include "boneless/TakeSolver.h"

namespace boneless {

namespace {

// Frames scanned for the fits that explain the unmapped markers best. Measured on CMU 85_02
// from 6 picks (docs/markers.md): the rigid alignment's frame alone 11 of 35 within 30 mm.
constexpr int kScannedFrames = 40;
// Fits kept: the best, and those whose median marker distance is at most kKeptQuality times its
// (CMU from the second pick set of docs/markers.md: 10 of 35 at 1.3, 13 at 1.5, 11 at 1.7).
constexpr int kKeptFrames = 8;
constexpr double kKeptQuality = 1.5;
// Markers sit about this far off the skin: each vertex is scored lifted along its normal.
constexpr double kLiftMm = 10.0;
// When a proposal needs review: its marker is farther than farMm from it on the best fit; no
// pick keeps its distance to it within heldMm over the take (from the 10th to the 90th
// percentile: no pick holds its part of the body); the kept fits' own nearest vertices lie
// spreadMm from it (RMS, on the rest mesh); or another part of the body (farther than
// otherPartMm on the rest mesh) costs at most ambiguity times its cost plus ambiguityMm. An
// entry within mirrorMm of its picked partner's mirror image is exempt from the last three.
// On CMU 85_02 from five sets of six picks (docs/markers.md), correct entries lie up to 125 mm
// from the best fit, and the review flags catch 84 of the 98 misses and 37 of the 77 hits,
// where a 45 mm bound on the fit alone flagged 38 and 37.
struct ReviewThresholds {
    double farMm = 100.0;
    double heldMm = 25.0;
    double spreadMm = 30.0;
    double mirrorMm = 30.0;
    double otherPartMm = 150.0;
    double ambiguity = 1.5;
    double ambiguityMm = 10.0;
};
constexpr ReviewThresholds kReview;

Positions vertexNormals(const Faces& F, const Positions& V) {
    Positions N = Positions::Zero(V.rows(), 3);
    for (int f = 0; f < F.rows(); ++f) {
        const Vec3 a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
        const Vec3 n = (b - a).cross(c - a);
        for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n.transpose();
    }
    for (int v = 0; v < V.rows(); ++v)
        if (N.row(v).norm() > 0) N.row(v).normalize();
    return N;
}

// One fitted frame: the mesh posed by the picks, each vertex lifted off the skin.
struct Fit {
    int frame = -1;
    double quality = 0;  // median distance of the unmapped markers to the fit, mesh units
    Positions posed, lifted;
};

// The median distance from the frame's unmapped markers to the posed mesh (infinite if none).
double fitQuality(const C3dTake& take, const Similarity& s, const std::vector<std::size_t>& wanted,
                  int frame, const Positions& V) {
    std::vector<double> nearest;
    for (std::size_t p : wanted)
        if (const auto x = take.samples.position(frame, p))
            nearest.push_back((V.rowwise() - s.apply(*x).transpose()).rowwise().norm().minCoeff());
    if (nearest.empty()) return std::numeric_limits<double>::infinity();
    std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
    return nearest[nearest.size() / 2];
}

// Where the mirror image of the marker's picked partner's vertex lies on the rest mesh, if the
// mesh is mirrored and the partner (LFWT for RFWT) is picked.
std::optional<Vec3> mirrorOfPartner(const TriMesh& rest, const C3dTake& take,
                                    const Correspondence& known, std::size_t point,
                                    const MirrorPlane& mirror) {
    if (!mirror.known()) return std::nullopt;
    const auto partner = take.findPoint(SideCheck::partner(take.points[point].label));
    for (const MarkerMapping& k : known.markers)
        if (partner && take.findPoint(k.label) == partner && SideCheck::side(k.label))
            return mirror.reflect(rest.V.row(k.vertex).transpose());
    return std::nullopt;
}

// Marker sets are mirrored (LFWT and RFWT), and so are most bodies: on a mirrored rest mesh, an
// unmapped marker whose partner is picked costs more the farther it lands from the mirror image
// of the partner's vertex, a metre of asymmetry as much as a metre of distance to its marker over
// the fits (CMU 85_02, the two pick sets of docs/markers.md: 20 to 21 and 15 to 16 of 35). Pairs
// that are both unmapped are left to the take: tied together they lost as many as they gained,
// since actors wear limb markers unevenly and the fit does not know which side is right.
std::vector<Eigen::VectorXd> withMirror(const TriMesh& rest, const C3dTake& take,
                                        const Correspondence& known,
                                        const std::vector<std::size_t>& wanted,
                                        const MirrorPlane& mirror,
                                        const std::vector<Eigen::VectorXd>& cost) {
    std::vector<Eigen::VectorXd> out = cost;
    for (std::size_t w = 0; w < wanted.size(); ++w) {
        const auto target = mirrorOfPartner(rest, take, known, wanted[w], mirror);
        if (!target) continue;
        const Eigen::VectorXd d2 = (rest.V.rowwise() - target->transpose()).rowwise().squaredNorm();
        out[w] = (cost[w].cwiseAbs2() + d2).cwiseSqrt();
    }
    return out;
}

// One unmapped marker's proposal.
struct Draft {
    std::size_t point = 0;
    int vertex = -1;
    double cost = 0;        // RMS distance to the lifted vertex over the kept fits, mesh units
    double other = 0;       // the least such cost on another part of the body
    double fitMm = 0;       // marker to the vertex on the best fit
    double spreadMm = 0;    // RMS rest distance from the vertex to each kept fit's nearest
    bool seen = true;       // the marker is seen on the best fit's frame
    bool mirrored = false;  // it lies at its picked partner's mirror image
    std::string heldBy;     // the pick whose distance to the marker varies least over the take
    double heldMm = 0;      // how much it varies, 10th to 90th percentile
};

// How much the distance between two markers varies over the take, from its 10th to its 90th
// percentile, in mm: a few mm for two markers on one bone, tens across a joint. Infinite when
// fewer than 10 frames show both.
double distanceSpreadMm(const C3dTake& take, std::size_t a, std::size_t b) {
    std::vector<double> d;
    for (std::size_t f = 0; f < take.frameCount(); ++f) {
        const auto x = take.samples.position(f, a), y = take.samples.position(f, b);
        if (x && y) d.push_back((*x - *y).norm() * take.unitToMm);
    }
    if (d.size() < 10) return std::numeric_limits<double>::infinity();
    std::sort(d.begin(), d.end());
    return d[d.size() * 9 / 10] - d[d.size() / 10];
}

// Poses the mesh by the `known` markers at frames spread over the take (a rigid alignment cannot
// bring a T-posed mesh onto an actor whose arms are down), keeps the fits that come nearest the
// `wanted` markers, and gives each of those the free vertex that follows it best over the kept
// fits (the right vertex stays near its marker however the actor moves, where one fit's nearest
// may be a neighbour): surest first, so that a vertex two markers want goes to the nearer one.
// A marker no vertex comes within kUnreachableMm of over the fits, or that lies farther than that
// from its vertex on the best fit, is not on the body (a prop, another actor, a limb the picks
// leave unposed): it gets no vertex, and goes to `offBody` instead.
std::vector<Draft> draft(const TriMesh& rest, const C3dTake& take, const Correspondence& known,
                         const std::vector<std::size_t>& wanted, const MirrorPlane& mirror,
                         const std::optional<Vec3>& meshUp, const std::atomic<bool>* stop,
                         Calibration& calibration, int& fittedFrame,
                         std::vector<std::size_t>& offBody) {
    // The rest is first fitted to the actor at the alignment's frame, as solve does: the limbs
    // between the picks then take the actor's lengths (CMU 85_02, six picks: 17 to 20 of 35).
    TakeSolveOptions options;
    options.meshUp = meshUp;  // solved level as solve does, so the fits are the ones it makes
    TakeSolver solver(rest, take, known, options);
    calibration = solver.calibration();
    const Similarity& s = calibration.takeToMesh;
    const double unitsPerMm = s.scale / take.unitToMm;
    const int n = static_cast<int>(take.frameCount());
    std::vector<int> frames{calibration.frame};
    for (int i = 0; i < kScannedFrames && i < n; ++i)
        frames.push_back(static_cast<int>((i + 0.5) * n / std::min(n, kScannedFrames)));
    std::sort(frames.begin(), frames.end());
    frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
    std::vector<std::pair<double, int>> ranked;
    FrameReport report;
    // A fit takes up to a second on a 100K-face mesh, and there are some 50 of them.
    const auto stopped = [&] { return stop && stop->load(); };
    for (int f : frames) {
        if (stopped()) return {};
        const Positions V = solver.solve(f, report, stop);
        if (report.stopped) return {};
        ranked.push_back({fitQuality(take, s, wanted, f, V), f});
    }
    std::sort(ranked.begin(), ranked.end());
    std::vector<Fit> fits;
    for (const auto& [quality, f] : ranked) {
        if (fits.size() == kKeptFrames || !std::isfinite(quality) ||
            quality > kKeptQuality * ranked.front().first)
            break;
        if (stopped()) return {};
        const Positions V = solver.solve(f, report, stop);
        if (report.stopped) return {};
        fits.push_back({f, quality, V, V + kLiftMm * unitsPerMm * vertexNormals(rest.F, V)});
    }
    if (fits.empty()) return {};  // no scanned frame shows an unmapped marker: nothing to place
    fittedFrame = fits.front().frame;

    std::vector<Eigen::VectorXd> cost;
    std::map<int, Positions> liftedAt;  // the fits solved for markers no kept fit shows
    for (std::size_t p : wanted) {
        Eigen::VectorXd sum = Eigen::VectorXd::Zero(rest.vertexCount());
        int seen = 0;
        for (const Fit& fit : fits)
            if (const auto x = take.samples.position(fit.frame, p)) {
                sum += (fit.lifted.rowwise() - s.apply(*x).transpose())
                           .rowwise()
                           .squaredNorm()
                           .transpose();
                ++seen;
            }
        if (!seen) {
            // Hidden in every kept fit, seen elsewhere (a gap over the stance): placed by the
            // best-rated scanned fit that shows it, where it was left out without a word. Its
            // entry is marked for review: it is not seen on the best fit's frame.
            for (const auto& [quality, f] : ranked) {
                const auto x = take.samples.position(f, p);
                if (!std::isfinite(quality) || !x) continue;
                auto fit = liftedAt.find(f);  // markers hidden alike share the frame's fit
                if (fit == liftedAt.end()) {
                    if (stopped()) return {};
                    const Positions V = solver.solve(f, report, stop);
                    if (report.stopped) return {};
                    fit = liftedAt.emplace(f, V + kLiftMm * unitsPerMm * vertexNormals(rest.F, V))
                              .first;
                }
                const Positions& lifted = fit->second;
                sum = (lifted.rowwise() - s.apply(*x).transpose())
                          .rowwise()
                          .squaredNorm()
                          .transpose();
                seen = 1;
                break;
            }
        }
        cost.push_back(seen ? Eigen::VectorXd((sum / seen).cwiseSqrt())
                            : Eigen::VectorXd::Constant(rest.vertexCount(),
                                                        std::numeric_limits<double>::infinity()));
    }
    const std::vector<Eigen::VectorXd> choice = withMirror(rest, take, known, wanted, mirror, cost);
    std::vector<std::size_t> order;
    for (std::size_t w = 0; w < wanted.size(); ++w) {
        const double best = cost[w].minCoeff();
        if (!std::isfinite(best)) continue;  // never seen: no proposal
        if (best > kUnreachableMm * unitsPerMm)
            offBody.push_back(wanted[w]);
        else
            order.push_back(w);
    }
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return choice[a].minCoeff() < choice[b].minCoeff();
    });
    std::set<int> taken;
    for (const auto& m : known.markers) taken.insert(weldedVertex(rest, m.vertex));
    std::vector<Draft> drafts;
    for (std::size_t w : order) {
        Draft d;
        d.point = wanted[w];
        for (int v = 0; v < rest.vertexCount(); ++v)
            // Only a welded vertex's first copy: the one the faces, and the app's picks, use.
            if (weldedVertex(rest, v) == v && !taken.count(v) &&
                (d.vertex < 0 || choice[w][v] < choice[w][d.vertex]))
                d.vertex = v;
        if (d.vertex < 0) break;
        taken.insert(d.vertex);
        d.cost = cost[w][d.vertex] / unitsPerMm;
        d.other = std::numeric_limits<double>::infinity();
        const Vec3 home = rest.V.row(d.vertex).transpose();
        for (int v = 0; v < rest.vertexCount(); ++v)
            if (cost[w][v] < d.other &&
                (rest.V.row(v).transpose() - home).norm() > kReview.otherPartMm * unitsPerMm)
                d.other = cost[w][v];
        d.other /= unitsPerMm;
        double spread = 0;
        int spreadFits = 0;
        for (const Fit& fit : fits)
            if (const auto x = take.samples.position(fit.frame, d.point)) {
                Eigen::Index nearest = 0;
                (fit.lifted.rowwise() - s.apply(*x).transpose())
                    .rowwise()
                    .squaredNorm()
                    .minCoeff(&nearest);
                spread += (rest.V.row(nearest).transpose() - home).squaredNorm();
                ++spreadFits;
            }
        d.spreadMm = spreadFits ? std::sqrt(spread / spreadFits) / unitsPerMm : 0.0;
        const auto image = mirrorOfPartner(rest, take, known, d.point, mirror);
        d.mirrored = image && (*image - home).norm() <= kReview.mirrorMm * unitsPerMm;
        const auto x = take.samples.position(fits.front().frame, d.point);
        d.seen = x.has_value();
        if (x)
            d.fitMm =
                (fits.front().posed.row(d.vertex).transpose() - s.apply(*x)).norm() / unitsPerMm;
        // The bound holds on the distance the review reason gives, not only on the RMS over the
        // kept fits: from four picks on CMU 85_02, RFIN was written "336 mm from the fitted mesh".
        if (d.fitMm > kUnreachableMm) {
            taken.erase(d.vertex);
            offBody.push_back(d.point);
            continue;
        }
        drafts.push_back(d);
    }
    std::sort(offBody.begin(), offBody.end());  // in the take's order, as wanted lists them
    return drafts;
}

// Why a draft needs a person's eye, or empty.
std::string reviewReason(const Draft& d, const std::string& label, const SideCheck& sides,
                         const TriMesh& rest) {
    char reason[200];
    if (!d.seen) return "not seen in the frame the mesh was fitted best";
    if (d.fitMm > kReview.farMm) {
        std::snprintf(reason, sizeof reason, "%.0f mm from the fitted mesh", d.fitMm);
        return reason;
    }
    if (const std::string side = sides.mismatch(label, rest.V.row(d.vertex).transpose());
        !side.empty())
        return side;
    if (d.mirrored) return {};  // the user's pick of its partner shows where it goes
    if (std::isfinite(d.heldMm) && d.heldMm > kReview.heldMm) {  // infinite: too few frames
        std::snprintf(reason, sizeof reason,
                      "no pick moves with it (its distance to the steadiest, %s, varies by %.0f mm "
                      "over the take)",
                      d.heldBy.c_str(), d.heldMm);
        return reason;
    }
    if (d.spreadMm > kReview.spreadMm) {
        std::snprintf(reason, sizeof reason,
                      "the fits of different frames place it %.0f mm apart on the body",
                      d.spreadMm);
        return reason;
    }
    if (d.other <= kReview.ambiguity * d.cost + kReview.ambiguityMm) {
        std::snprintf(reason, sizeof reason,
                      "another part of the body fits it about as well (%.0f mm against %.0f)",
                      d.other, d.cost);
        return reason;
    }
    return {};
}

}  // namespace

Suggestion suggestMappings(const TriMesh& rest, const C3dTake& take, const Correspondence& partial,
                           const std::optional<Vec3>& meshUp, const std::atomic<bool>* stop) {
    if (partial.markers.size() < 4)
        throw Error((partial.source().empty() ? "" : partial.source() + ": ") +
                    "suggesting correspondences needs at least 4 mapped markers to align the "
                    "take, the map has " +
                    std::to_string(partial.markers.size()));
    partial.checkMesh(rest.vertexCount(), "the mesh", &rest);
    const std::vector<std::size_t> mapped = partial.resolve(take);
    const std::set<std::size_t> mappedPoints(mapped.begin(), mapped.end());
    // A second actor's markers are not this body's: counted among the wanted, they would pick
    // the fits by how far another person stands.
    std::set<std::string> subjects;
    for (std::size_t p : mapped) subjects.insert(take.points[p].subject);
    std::vector<std::size_t> wanted;  // unmapped markers the take shows at least once
    std::vector<std::string> otherSubjects, sharedLabels;
    std::set<std::size_t> shared;
    for (const std::vector<std::size_t>& group : take.sharedLabels()) {
        sharedLabels.push_back(take.points[group.front()].label);
        shared.insert(group.begin(), group.end());
    }
    for (std::size_t p : take.markerIndices()) {
        if (mappedPoints.count(p) || shared.count(p) ||
            take.samples.missingFrames(p) == take.frameCount())
            continue;
        if (subjects.count(take.points[p].subject))
            wanted.push_back(p);
        else
            otherSubjects.push_back(take.points[p].label);
    }
    const SideCheck sides(rest, partial);
    // A proposal sits off the skin as the user's picks do: the distance to a fit is no offset,
    // since a fit from a few picks misses the body between them by centimetres (CMU 85_02: the
    // median proposal was 40 mm off, and solving with those offsets left 40 mm of residual).
    std::vector<double> picked;
    for (const auto& m : partial.markers) picked.push_back(m.offsetMm);
    std::nth_element(picked.begin(), picked.begin() + picked.size() / 2, picked.end());
    const double offsetMm = picked[picked.size() / 2];

    Suggestion out;
    out.map = partial;
    out.otherSubjects = otherSubjects;
    out.sharedLabels = sharedLabels;
    if (wanted.empty()) return out;  // every marker seen is mapped: nothing to fit the mesh for
    const MirrorPlane mirror(rest, sides);
    std::vector<std::size_t> offBody;
    std::vector<Draft> drafts = draft(rest, take, partial, wanted, mirror, meshUp, stop,
                                      out.calibration, out.fittedFrame, offBody);
    if (stop && stop->load()) {  // nothing half-done: the picks alone
        Suggestion stopped;
        stopped.map = partial;
        stopped.stopped = true;
        return stopped;
    }
    for (Draft& d : drafts) {
        d.heldMm = std::numeric_limits<double>::infinity();
        for (std::size_t pick : mapped)
            if (const double spread = distanceSpreadMm(take, d.point, pick); spread < d.heldMm) {
                d.heldMm = spread;
                d.heldBy = take.shortLabel(pick);
            }
        Proposal p;
        p.label = take.shortLabel(d.point);
        p.vertex = d.vertex;
        p.reviewReason = reviewReason(d, p.label, sides, rest);
        p.needsReview = !p.reviewReason.empty();
        MarkerMapping m;
        m.label = p.label;
        m.vertex = d.vertex;
        m.offsetMm = offsetMm;
        m.extraJson = p.needsReview
                          ? R"({"suggested": true, "needs_review": true, "review_reason": )" +
                                nlohmann::json(p.reviewReason).dump() + "}"
                          : std::string(R"({"suggested": true})");
        out.needsReview += p.needsReview ? 1 : 0;
        out.map.markers.push_back(m);
        out.proposals.push_back(p);
    }
    out.suggested = static_cast<int>(out.proposals.size());
    for (std::size_t p : offBody) out.offBody.push_back(take.points[p].label);
    return out;
}

SuggestionMark suggestionMark(const MarkerMapping& entry) {
    SuggestionMark mark;
    const auto extra = nlohmann::json::parse(entry.extraJson, nullptr, false);
    if (!extra.is_object()) return mark;
    const auto isTrue = [&](const char* key) { return extra.contains(key) && extra[key] == true; };
    mark.suggested = isTrue("suggested");
    mark.needsReview = isTrue("needs_review");
    if (mark.needsReview) {
        const auto reason = extra.find("review_reason");
        mark.reviewReason = reason != extra.end() && reason->is_string()
                                ? reason->get<std::string>()
                                : std::string("needs review");
    }
    return mark;
}

std::vector<std::string> labelsToReview(const Correspondence& map) {
    std::vector<std::string> labels;
    for (const MarkerMapping& m : map.markers)
        if (suggestionMark(m).needsReview) labels.push_back(m.label);
    return labels;
}

}  // namespace boneless
