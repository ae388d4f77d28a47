#include "boneless/ActorCalibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "boneless/Error.h"
#include "boneless/Text.h"

namespace boneless {

const char* calibrateModeName(CalibrateMode mode) {
    return mode == CalibrateMode::Shape ? "shape" : "none";
}

bool parseCalibrateMode(const std::string& name, CalibrateMode& mode) {
    for (auto m : {CalibrateMode::None, CalibrateMode::Shape})
        if (name == calibrateModeName(m)) {
            mode = m;
            return true;
        }
    return false;
}

EdgeStrain::EdgeStrain(const Faces& F, const Positions& rest) {
    for (int f = 0; f < F.rows(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int a = F(f, c), b = F(f, (c + 1) % 3);
            const double length = (rest.row(a) - rest.row(b)).norm();
            if (!(length > 0)) continue;
            ends_.insert(ends_.end(), {a, b});
            restLength_.push_back(length);
        }
}

std::vector<double> EdgeStrain::strains(const Positions& V) const {
    std::vector<double> strains(restLength_.size());
    for (size_t e = 0; e < strains.size(); ++e)
        strains[e] =
            std::abs((V.row(ends_[2 * e]) - V.row(ends_[2 * e + 1])).norm() / restLength_[e] - 1.0);
    return strains;
}

double rootMeanSquare(const std::vector<double>& values) {
    double sum = 0;
    for (double v : values) sum += v * v;
    return values.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(values.size()));
}

double quantile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    const auto rank = static_cast<std::size_t>(std::ceil(q * values.size()));
    const std::size_t i = std::min(values.size() - 1, rank == 0 ? 0 : rank - 1);
    std::nth_element(values.begin(), values.begin() + i, values.end());
    return values[i];
}

namespace {

// Each vertex's largest edge strain, V against rest.
std::vector<double> vertexStrain(const Faces& F, const Positions& V, const Positions& rest) {
    std::vector<double> worst(V.rows(), 0.0);
    for (int f = 0; f < F.rows(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int a = F(f, c), b = F(f, (c + 1) % 3);
            const double restLength = (rest.row(a) - rest.row(b)).norm();
            if (restLength <= 0) continue;
            const double s = std::abs((V.row(a) - V.row(b)).norm() / restLength - 1.0);
            worst[a] = std::max(worst[a], s);
            worst[b] = std::max(worst[b], s);
        }
    return worst;
}

Vec3 markerPoint(const Reconstruction& solver, std::size_t k, const Positions& V) {
    const int v = solver.markerVertices()[k];
    Vec3 x = V.row(v).transpose();
    const auto& offsets = solver.options().markerOffsets;
    if (k < offsets.size() && offsets[k] != 0 && solver.encoding().encoded(v))
        x += offsets[k] * solver.encoding().ringNormal(v, V);
    return x;
}

}  // namespace

Positions fitActorShape(Reconstruction& solver, const Positions& targets,
                        const std::vector<std::string>& labels, double mmPerMeshUnit) {
    const TriMesh& rest = solver.rest();
    SolveResult fit = solver.solve(targets);
    if (!fit.V.allFinite()) throw Error("the calibration frame's markers give no solution");
    // A marker that tears its neighbourhood is checked by solving without it: if the others put
    // its place far from where it is, it is not on this mesh (a wrong map, another actor's prop),
    // and a calibrated rest that follows it would be a spike, not a body.
    const std::vector<double> strain = vertexStrain(rest.F, fit.V, rest.V);
    std::vector<std::pair<double, std::string>> unreachable;  // mm, label
    const auto& markers = solver.markerVertices();
    for (std::size_t k = 0; k < markers.size(); ++k) {
        const int row = static_cast<int>(k);
        if (!targets.row(row).allFinite() || strain[markers[k]] <= kUnreachableStrain) continue;
        Positions without = targets;
        without.row(row).setConstant(std::numeric_limits<double>::quiet_NaN());
        const SolveResult others = solver.solve(without);
        if (!others.V.allFinite()) continue;
        const double mm = (markerPoint(solver, k, others.V) - targets.row(row).transpose()).norm() *
                          mmPerMeshUnit;
        if (mm > kUnreachableMm) unreachable.emplace_back(mm, k < labels.size() ? labels[k] : "?");
    }
    if (unreachable.empty()) return fit.V;
    // Farthest first: one wrong entry also drags its neighbours' markers past the bound (C7 mapped
    // onto a leg names the knee and shin too), and it is the farthest of them.
    std::sort(unreachable.begin(), unreachable.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<std::string> list;
    for (const auto& [mm, label] : unreachable) {
        char line[160];
        std::snprintf(line, sizeof line, "%s (%.0f mm from where the other markers put it)",
                      label.c_str(), mm);
        list.push_back(line);
    }
    // The map first: a map made on another file of the body (another vertex order) names other
    // places, and solved uncalibrated it pulls the body apart without a word.
    throw Error("the mesh cannot reach the actor at the calibration frame: marker " + joined(list) +
                " (farthest first); check the map first: it must name this mesh file's vertices "
                "in their order (a map made on another export or format of the body names other "
                "places). Only for a right map on an actor the mesh cannot take the shape of, "
                "solve without calibrating (calibrate none)");
}

}  // namespace boneless
