#include "FoldRepair.h"

#include <Eigen/SparseCholesky>
#include <cmath>

namespace boneless {

namespace {

constexpr double kWeight = 100;     // w, as the exact method's orientation guard
constexpr double kThreshold = 0.2;  // τ, and its step for a face that folds again
constexpr double kMaxThreshold = 0.8;
constexpr int kSteps = 10;          // Gauss–Newton steps with the rotations held, at most
constexpr int kRounds = 4;          // refits of the rotations per patch
constexpr double kEscalation = 10;  // the weight's growth from round to round
constexpr double kSettled = 1e-3;   // a step that gains less than this share ends the steps

Vec3 faceNormal(const Faces& F, const Positions& V, int f) {
    const Vec3 a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    return (b - a).cross(c - a);
}

}  // namespace

FoldRepair::FoldRepair(const TriMesh& rest, const RingFit& rings) : rest_(rest), rings_(rings) {
    const int n = rest.vertexCount(), faces = rest.faceCount();
    cornerStart_.assign(n + 1, 0);
    for (int f = 0; f < faces; ++f)
        for (int c = 0; c < 3; ++c) ++cornerStart_[rest.F(f, c) + 1];
    for (int v = 0; v < n; ++v) cornerStart_[v + 1] += cornerStart_[v];
    cornerFace_.resize(cornerStart_[n]);
    std::vector<int> fill(cornerStart_.begin(), cornerStart_.end() - 1);
    restNormal_.resize(faces);
    double total = 0;
    const double diagonal = boundingBoxDiagonal(rest.V, rest.F);
    for (int f = 0; f < faces; ++f) {
        for (int c = 0; c < 3; ++c) cornerFace_[fill[rest.F(f, c)]++] = f;
        // A face with no area has no side to fold over: a zero normal leaves it out.
        const Vec3 a = rest.V.row(rest.F(f, 0)), b = rest.V.row(rest.F(f, 1)),
                   c = rest.V.row(rest.F(f, 2));
        restNormal_[f] = zeroArea(a, b, c, diagonal) ? Vec3::Zero() : faceNormal(rest.F, rest.V, f);
        total += restNormal_[f].norm();
    }
    scale_ = faces ? kWeight * 0.5 * total / faces : 0.0;
}

Vec3 FoldRepair::carriedNormal(int f, const std::vector<Mat3>& rotations) const {
    const Vec3& n0 = restNormal_[f];
    if (!(n0.squaredNorm() > 0)) return Vec3::Zero();
    const Vec3 u =
        (rotations[rest_.F(f, 0)] + rotations[rest_.F(f, 1)] + rotations[rest_.F(f, 2)]) * n0;
    const double length = u.norm();
    return length > 0 ? Vec3(u / length) : Vec3::Zero();
}

double FoldRepair::projectedArea(const Positions& V, int f, const Vec3& u) const {
    return faceNormal(rest_.F, V, f).dot(u) / restNormal_[f].norm();
}

std::vector<int> FoldRepair::folded(const Positions& V, const std::vector<Mat3>& rotations,
                                    double margin) const {
    std::vector<int> out;
    for (int f = 0; f < rest_.faceCount(); ++f) {
        const Vec3 u = carriedNormal(f, rotations);
        if (!u.isZero() && projectedArea(V, f, u) < margin) out.push_back(f);
    }
    return out;
}

std::vector<int> FoldRepair::grow(std::vector<int> seeds, int rings) const {
    std::vector<char> in(rest_.vertexCount(), 0);
    std::vector<int> out;
    for (int v : seeds)
        if (!in[v]) in[v] = 1, out.push_back(v);
    std::size_t layerBegin = 0;
    for (int r = 0; r < rings; ++r) {
        const std::size_t layerEnd = out.size();
        for (std::size_t i = layerBegin; i < layerEnd; ++i)
            for (int c = cornerStart_[out[i]]; c < cornerStart_[out[i] + 1]; ++c)
                for (int k = 0; k < 3; ++k) {
                    const int w = rest_.F(cornerFace_[c], k);
                    if (!in[w]) in[w] = 1, out.push_back(w);
                }
        layerBegin = layerEnd;
    }
    return out;
}

Vec3 FoldRepair::Quadratic::gradient(int v, const Positions& V) const {
    Vec3 x = -rhs.row(v).transpose();
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, v); it; ++it)
        x += it.value() * V.row(it.row()).transpose();
    return x;
}

int FoldRepair::repair(Positions& V, const Quadratic& q, const std::vector<char>& pinned,
                       std::vector<Mat3>& rotations) const {
    std::vector<int> bad = folded(V, rotations);
    // A patch that cannot unfold (a pinned marker on the fold's far side, a fingertip whose
    // rings turn with it) is tried wider.
    for (int rings = 2; rings <= 8 && !bad.empty(); rings += 2) {
        for (const std::vector<int>& cluster : clusters(bad))
            solvePatch(V, q, pinned, rotations, cluster, rings);
        bad = folded(V, rotations);
    }
    return static_cast<int>(bad.size());
}

std::vector<std::vector<int>> FoldRepair::clusters(const std::vector<int>& faces) const {
    // Folded faces that share a vertex are one cluster; each is solved in its own patch, so
    // that a fold that unfolds at once does not wait for a stubborn one elsewhere.
    std::vector<int> group(faces.size(), -1);
    std::vector<std::vector<int>> out;
    for (size_t i = 0; i < faces.size(); ++i) {
        if (group[i] >= 0) continue;
        group[i] = static_cast<int>(out.size());
        out.push_back({faces[i]});
        for (size_t q = 0; q < out.back().size(); ++q) {
            const int f = out.back()[q];
            for (size_t j = i + 1; j < faces.size(); ++j) {
                if (group[j] >= 0) continue;
                bool shares = false;
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b)
                        shares = shares || rest_.F(f, a) == rest_.F(faces[j], b);
                if (!shares) continue;
                group[j] = group[i];
                out.back().push_back(faces[j]);
            }
        }
    }
    return out;
}

void FoldRepair::solvePatch(Positions& V, const Quadratic& q, const std::vector<char>& pinned,
                            std::vector<Mat3>& rotations, const std::vector<int>& faces,
                            int rings) const {
    const Faces& F = rest_.F;
    std::vector<int> seeds;
    for (int f : faces)
        for (int c = 0; c < 3; ++c) seeds.push_back(F(f, c));
    // The patch's free vertices; the faces whose carried normal they can change (their own, and
    // those of vertices whose ring they are in); the vertices whose rotation those faces need.
    Patch patch;
    patch.local.assign(rest_.vertexCount(), -1);
    for (int v : grow(seeds, rings))
        if (!pinned[v]) {
            patch.local[v] = static_cast<int>(patch.vertices.size());
            patch.vertices.push_back(v);
        }
    if (patch.vertices.empty()) return;
    std::vector<int> ringVertices;
    {
        std::vector<char> seen(rest_.faceCount(), 0), seenVertex(rest_.vertexCount(), 0);
        for (int v : grow(patch.vertices, 1))
            for (int c = cornerStart_[v]; c < cornerStart_[v + 1]; ++c) {
                const int f = cornerFace_[c];
                if (seen[f]) continue;
                seen[f] = 1;
                patch.faces.push_back(f);
                for (int k = 0; k < 3; ++k)
                    if (!seenVertex[F(f, k)]) {
                        seenVertex[F(f, k)] = 1;
                        ringVertices.push_back(F(f, k));
                    }
            }
    }
    patch.threshold.assign(patch.faces.size(), kThreshold);
    for (int p = 0; p < static_cast<int>(patch.vertices.size()); ++p) {
        const int v = patch.vertices[p];
        for (Eigen::SparseMatrix<double>::InnerIterator it(q.A, v); it; ++it)
            if (patch.local[it.row()] >= 0)
                patch.A.emplace_back(patch.local[it.row()], p, it.value());
    }
    // The penalty's u_f follow the ring rotations, which follow the fold: the patch is solved
    // with them held, then they are refitted, until no face of the patch is folded in them.
    for (int round = 0; round < kRounds; ++round) {
        for (int v : ringVertices) rings_.fit(v, V, rotations[v], true, kCountStep);
        bool anyFolded = false;
        for (size_t i = 0; i < patch.faces.size(); ++i) {
            const Vec3 u = carriedNormal(patch.faces[i], rotations);
            if (u.isZero() || projectedArea(V, patch.faces[i], u) >= 0) continue;
            anyFolded = true;
            // Folded again once its rings' rotations followed it: pushed further next time.
            if (round > 0)
                patch.threshold[i] = std::min(kMaxThreshold, patch.threshold[i] + kThreshold);
        }
        if (!anyFolded) return;
        // A fold the markers hold against the penalty is held harder each round.
        solveHeld(V, q, patch, rotations, scale_ * std::pow(kEscalation, round));
    }
    // The rotations stay fitted to V, which the last round moved.
    for (int v : ringVertices) rings_.fit(v, V, rotations[v], true, kCountStep);
}

double FoldRepair::penalty(const Positions& V, const Patch& patch,
                           const std::vector<Mat3>& rotations, double scale) const {
    double e = 0;
    for (size_t i = 0; i < patch.faces.size(); ++i) {
        const int f = patch.faces[i];
        const Vec3 u = carriedNormal(f, rotations);
        if (u.isZero()) continue;
        const double gap = patch.threshold[i] - projectedArea(V, f, u);
        if (gap > 0) e += scale * gap * gap;
    }
    return e;
}

void FoldRepair::solveHeld(Positions& V, const Quadratic& q, const Patch& patch,
                           const std::vector<Mat3>& rotations, double scale) const {
    const Faces& F = rest_.F;
    const int m = static_cast<int>(patch.vertices.size());
    const double k = std::sqrt(scale);
    double before = penalty(V, patch, rotations, scale);
    // Every face's blocks are in the matrix from the start, zero while the face is inactive, so
    // that its pattern, and the symbolic analysis, are the same at every step.
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    bool analysed = false;
    Positions trial = V;  // only the patch's rows ever differ from V
    for (int step = 0; step < kSteps && before > 0; ++step) {
        // ½ ∇ of VᵀAV − 2 Vᵀrhs on the patch; g adds the penalty's.
        Eigen::VectorXd gQ(3 * m);
        for (int p = 0; p < m; ++p) gQ.segment<3>(3 * p) = q.gradient(patch.vertices[p], V);
        Eigen::VectorXd g = gQ;
        std::vector<Eigen::Triplet<double>> H;
        H.reserve(3 * patch.A.size());
        for (const auto& t : patch.A)
            for (int d = 0; d < 3; ++d) H.emplace_back(3 * t.row() + d, 3 * t.col() + d, t.value());
        for (size_t i = 0; i < patch.faces.size(); ++i) {
            const int f = patch.faces[i];
            const double tau = patch.threshold[i];
            const Vec3 u = carriedNormal(f, rotations);
            const double s = u.isZero() ? tau : projectedArea(V, f, u);
            // n = (b − a) × (c − a), so ∂(n·u)/∂a = (b − c) × u, and cyclically. An inactive
            // face's blocks are there too, as zeros.
            const double r = s < tau ? k * (tau - s) : 0.0;
            Vec3 d[3];
            for (int c = 0; c < 3; ++c) {
                const Vec3 edge = V.row(F(f, (c + 1) % 3)) - V.row(F(f, (c + 2) % 3));
                d[c] = r > 0 ? Vec3(-k * edge.cross(u) / restNormal_[f].norm()) : Vec3::Zero();
            }
            for (int a = 0; a < 3; ++a) {
                const int pa = patch.local[F(f, a)];
                if (pa < 0) continue;
                g.segment<3>(3 * pa) += r * d[a];
                for (int b = 0; b < 3; ++b) {
                    const int pb = patch.local[F(f, b)];
                    if (pb < 0) continue;
                    const Mat3 block = d[a] * d[b].transpose();
                    for (int x = 0; x < 3; ++x)
                        for (int y = 0; y < 3; ++y)
                            H.emplace_back(3 * pa + x, 3 * pb + y, block(x, y));
                }
            }
        }
        Eigen::SparseMatrix<double> matrix(3 * m, 3 * m);
        matrix.setFromTriplets(H.begin(), H.end());
        if (!analysed) ldlt.analyzePattern(matrix);
        analysed = true;
        ldlt.factorize(matrix);
        if (ldlt.info() != Eigen::Success) return;
        const Eigen::VectorXd delta = ldlt.solve(-g);
        if (!delta.allFinite()) return;
        // The quadratic's change along delta is exact: 2α δ·g_Q + α² δᵀAδ.
        Eigen::VectorXd Ad = Eigen::VectorXd::Zero(3 * m);
        for (const auto& t : patch.A)
            Ad.segment<3>(3 * t.row()) += t.value() * delta.segment<3>(3 * t.col());
        const double linear = 2 * delta.dot(gQ), quadratic = delta.dot(Ad);
        bool accepted = false, settled = false;
        for (double alpha = 1; alpha > 1e-4 && !accepted; alpha *= 0.5) {
            for (int p = 0; p < m; ++p)
                trial.row(patch.vertices[p]) =
                    V.row(patch.vertices[p]) + alpha * delta.segment<3>(3 * p).transpose();
            const double after = penalty(trial, patch, rotations, scale);
            const double change = alpha * linear + alpha * alpha * quadratic + after - before;
            if (change < 0) {
                accepted = true;
                // Settled: the penalty and the quadratic balance (a stubborn fold waits for
                // its rotations to be refitted).
                settled = -change < kSettled * (before + std::abs(alpha * linear));
                before = after;
            }
        }
        if (!accepted) return;
        for (int p : patch.vertices) V.row(p) = trial.row(p);
        if (settled) return;
    }
}

}  // namespace boneless
