#include "LocalGlobal.h"

#include <Eigen/LU>
#include <chrono>
#include <cmath>
#include <limits>

#include "Rotation.h"
#include "boneless/Error.h"
#include "boneless/Parallel.h"

namespace boneless {

namespace {

double trace(const Eigen::SparseMatrix<double>& A) {
    double t = 0;
    for (int k = 0; k < A.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
            if (it.row() == k) t += it.value();
    return t;
}

// The local steps are a few hundred nanoseconds a vertex: worth a second thread from a few
// hundred vertices on (a coarse level's thousand).
constexpr int kMinimumPerThread = 128;
// A rotation is fitted once a Newton step turns it by less than this: Newton converges
// quadratically, so it is then within about 1e-4 rad, plenty for a local step.
constexpr double kRotationStep = 1e-2;
// Rotations fitted that far only screen for faces whose projected area is below this share of
// their rest area; the folds themselves are counted in rotations fitted to about 1e-12 rad
// (FoldRepair::kCountStep), as a fresh fit would judge a face on the edge of folding.
constexpr double kNearlyFolded = 0.05;

}  // namespace

LocalGlobalSolver::LocalGlobalSolver(const TriMesh& rest, const MeshTopology& topology,
                                     const ShapeEncoding& encoding,
                                     std::vector<MarkerPatch> markers, Settings settings)
    : rest_(rest),
      encoding_(encoding),
      markers_(std::move(markers)),
      settings_(settings),
      arap_(rest),
      rings_(rest, topology) {
    const int n = rest.vertexCount();
    const int K = static_cast<int>(markers_.size());
    // L = I − W over the encoded vertices; the others have no row (no shape of their own). A
    // boundary vertex's ring is closed by a chord it lies close to, where mean-value weights
    // are ill-conditioned (docs/algorithm.md §2): it takes uniform weights instead (horse gallop,
    // 40 markers: 0.945 % RMS and 150 faces flipped at worst, against 0.953 % and 247).
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(topology.neighbours().size() + n);
    weight_.assign(topology.neighbours().size(), 0.0);
    for (int v = 0; v < n; ++v) {
        if (!encoding.encoded(v)) continue;
        entries.emplace_back(v, v, 1.0);
        const int m = topology.valence(v);
        const int* ring = topology.ring(v);
        const double* w = encoding.weights(v);
        double* mine = weight_.data() + topology.offsets()[v];
        for (int k = 0; k < m; ++k) {
            mine[k] = topology.isBoundary(v) ? 1.0 / m : w[k];
            entries.emplace_back(v, ring[k], -mine[k]);
        }
    }
    L_.resize(n, n);
    L_.setFromTriplets(entries.begin(), entries.end());
    Lt_ = L_.transpose();

    delta0_.resize(n);
    parallelFor(n, [&](int begin, int end, int) {
        for (int v = begin; v < end; ++v) {
            delta0_[v].setZero();
            if (!encoding.encoded(v)) continue;
            const int* ring = topology.ring(v);
            const double* w = weight_.data() + topology.offsets()[v];
            delta0_[v] = rest.V.row(v).transpose();
            for (int k = 0; k < topology.valence(v); ++k)
                delta0_[v] -= w[k] * rest.V.row(ring[k]).transpose();
        }
    });
    for (const MarkerPatch& p : markers_)
        if (settings_.hard && p.vertices.size() != 1)
            throw SolverError("a hard marker holds one vertex, not a patch");

    const Eigen::SparseMatrix<double> Lc = L_;
    const Eigen::SparseMatrix<double> LtL = Eigen::SparseMatrix<double>(Lc.transpose()) * Lc;
    const Eigen::SparseMatrix<double>& cot = arap_.laplacian();
    const double cotTrace = trace(cot);
    arapWeight_ = cotTrace > 0 ? settings_.arapShare * trace(LtL) / cotTrace : 0.0;
    A_ = LtL + arapWeight_ * cot;
    // A tiny pull towards the start pose keeps what no marker pins down (a component without
    // markers, an isolated vertex) from making the matrix singular.
    tikhonov_ = 1e-9 * std::max(trace(A_) / std::max(n, 1), 1e-300);
    for (int v = 0; v < n; ++v) A_.coeffRef(v, v) += tikhonov_;
    if (!settings_.hard) {
        // λ u_k u_kᵀ per marker: a patch's vertices are coupled through its centroid.
        std::vector<Eigen::Triplet<double>> pull;
        for (const MarkerPatch& p : markers_)
            for (size_t i = 0; i < p.vertices.size(); ++i)
                for (size_t j = 0; j < p.vertices.size(); ++j)
                    pull.emplace_back(p.vertices[i], p.vertices[j],
                                      settings_.softWeight * p.weights[i] * p.weights[j]);
        Eigen::SparseMatrix<double> P(n, n);
        P.setFromTriplets(pull.begin(), pull.end());
        A_ += P;
    }
    A_.makeCompressed();

    std::vector<char> isMarker(n, 0);
    if (settings_.hard)
        for (const MarkerPatch& p : markers_) isMarker[p.vertex] = 1;
    unknownOf_.assign(n, -1);
    vertexOf_.clear();
    for (int v = 0; v < n; ++v)
        if (!settings_.hard || !isMarker[v]) {
            unknownOf_[v] = static_cast<int>(vertexOf_.size());
            vertexOf_.push_back(v);
        }
    bool factorised = false;
    if (settings_.hard) {
        std::vector<Eigen::Triplet<double>> kept;
        kept.reserve(A_.nonZeros());
        for (int c = 0; c < A_.outerSize(); ++c)
            for (Eigen::SparseMatrix<double>::InnerIterator it(A_, c); it; ++it)
                if (unknownOf_[it.row()] >= 0 && unknownOf_[c] >= 0 && it.row() >= c)
                    kept.emplace_back(unknownOf_[it.row()], unknownOf_[c], it.value());
        const int size = static_cast<int>(vertexOf_.size());
        Eigen::SparseMatrix<double> B(size, size);
        B.setFromTriplets(kept.begin(), kept.end());
        factorised = factor_.factorize(B);
    } else {
        factorised = factor_.factorize(A_);
    }
    if (!factorised) throw SolverError("the local/global system could not be factorised");
    correction_.assign(K, Eigen::VectorXd());
    diagonal_ = boundingBoxDiagonal(rest.V, rest.F);
    if (settings_.repairFolds) repair_ = std::make_unique<FoldRepair>(rest, rings_);
}

LocalGlobalSolver::~LocalGlobalSolver() = default;

void LocalGlobalSolver::fitRotations(const Positions& V, std::vector<Mat3>& rotation,
                                     std::vector<Mat3>& arapRotation, bool warm) const {
    rings_.fit(V, rotation, warm, kRotationStep);
    arap_.fitRotations(V, arapRotation, warm, nullptr, kRotationStep);
}

Vec3 LocalGlobalSolver::markerTarget(int k, const Positions& targets,
                                     const std::vector<double>& offsets, const Mat3& R) const {
    // The offset goes along the rest normal turned by the patch's fitted rotation: the current
    // ring normal turns over on thin parts, the rotation does not.
    const MarkerPatch& p = markers_[k];
    const double o = k < static_cast<int>(offsets.size()) ? offsets[k] : 0.0;
    return targets.row(k).transpose() - R * (p.sag + o * p.restNormal);
}

void LocalGlobalSolver::fitPatchRotations(const Positions& V, const std::vector<Mat3>& rotation,
                                          std::vector<Mat3>& patchRotation) const {
    patchRotation.resize(markers_.size());
    for (size_t k = 0; k < markers_.size(); ++k)
        patchRotation[k] = markers_[k].rotation(rest_.V, V, rotation[markers_[k].vertex]);
}

Eigen::SparseMatrix<double> LocalGlobalSolver::frameMatrix(const std::vector<int>& missing) const {
    Eigen::SparseMatrix<double> A = A_;
    if (settings_.hard) return A;
    for (int k : missing) {
        const MarkerPatch& p = markers_[k];
        for (size_t i = 0; i < p.vertices.size(); ++i)
            for (size_t j = 0; j < p.vertices.size(); ++j)
                A.coeffRef(p.vertices[i], p.vertices[j]) -=
                    settings_.softWeight * p.weights[i] * p.weights[j];
    }
    return A;
}

void LocalGlobalSolver::rightHandSide(const Positions& targets, const std::vector<double>& offsets,
                                      const std::vector<int>& visible, const Eigen::MatrixXd& base,
                                      Eigen::MatrixXd& rhs) {
    const int n = rest_.vertexCount();
    rotatedDelta_.resize(n);
    parallelFor(
        n,
        [&](int begin, int end, int) {
            for (int v = begin; v < end; ++v) rotatedDelta_[v] = rotation_[v] * delta0_[v];
        },
        kMinimumPerThread);
    arap_.turnCornerEdges(arapRotation_, cornerEdges_);
    const double arapScale = arapWeight_ / 3.0;
    rhs.resize(n, 3);
    parallelFor(
        n,
        [&](int begin, int end, int) {
            for (int v = begin; v < end; ++v) {
                Vec3 s = base.row(v).transpose();
                for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Lt_, v); it;
                     ++it)
                    s.noalias() += it.value() * rotatedDelta_[it.col()];
                s.noalias() += arapScale * arap_.rotatedRestEdges(v, cornerEdges_);
                rhs.row(v) = s.transpose();
            }
        },
        kMinimumPerThread);
    if (!settings_.hard)
        for (int k : visible) {
            const MarkerPatch& p = markers_[k];
            const Vec3 t = markerTarget(k, targets, offsets, patchRotation_[k]);
            for (size_t j = 0; j < p.vertices.size(); ++j)
                rhs.row(p.vertices[j]) += settings_.softWeight * p.weights[j] * t.transpose();
        }
}

void LocalGlobalSolver::cacheCorrections(const std::vector<int>& missing) {
    const int rows = static_cast<int>(vertexOf_.size());
    for (int k : missing) {
        if (correction_[k].size() != 0) continue;
        // One column at a time: solved with others, CHOLMOD takes another kernel, and a last
        // bit could depend on which markers went missing first.
        Eigen::MatrixXd column = Eigen::MatrixXd::Zero(rows, 1);
        const MarkerPatch& p = markers_[k];
        if (settings_.hard) {
            for (Eigen::SparseMatrix<double>::InnerIterator it(A_, p.vertex); it; ++it)
                if (unknownOf_[it.row()] >= 0) column(unknownOf_[it.row()], 0) = it.value();
        } else {
            for (size_t j = 0; j < p.vertices.size(); ++j)
                column(unknownOf_[p.vertices[j]], 0) = p.weights[j];
        }
        correction_[k] = factor_.solve(column).col(0);
    }
}

LocalGlobalSolver::Gaps LocalGlobalSolver::gaps(const std::vector<int>& missing) {
    cacheCorrections(missing);
    Gaps g;
    g.missing = missing;
    const int m = static_cast<int>(missing.size());
    if (m == 0) return g;
    Eigen::MatrixXd S(m, m);
    for (int j = 0; j < m; ++j) {
        const int cj = markers_[missing[j]].vertex;
        if (settings_.hard) {
            // The missing markers' vertices join the unknowns: a bordered system, solved through
            // its Schur complement S = A_MM − A_Mf B⁻¹ A_fM.
            for (int k = 0; k < m; ++k) S(j, k) = A_.coeff(cj, markers_[missing[k]].vertex);
            for (Eigen::SparseMatrix<double>::InnerIterator it(A_, cj); it; ++it) {
                const int u = unknownOf_[it.row()];
                if (u < 0) continue;
                for (int k = 0; k < m; ++k) S(j, k) -= it.value() * correction_[missing[k]](u);
            }
        } else {
            // Woodbury: each missing marker's λ u uᵀ taken off again.
            const MarkerPatch& p = markers_[missing[j]];
            for (int k = 0; k < m; ++k) {
                double uBu = 0;
                for (size_t i = 0; i < p.vertices.size(); ++i)
                    uBu += p.weights[i] * correction_[missing[k]](unknownOf_[p.vertices[i]]);
                S(j, k) = (j == k ? 1.0 / settings_.softWeight : 0.0) - uBu;
            }
        }
    }
    g.S.compute(S);
    return g;
}

Eigen::MatrixXd LocalGlobalSolver::solveSystem(const Eigen::MatrixXd& raw,
                                               const Eigen::MatrixXd& fixed, const Gaps& gaps) {
    const Eigen::MatrixXd rhs = settings_.hard ? Eigen::MatrixXd(raw - fixed) : raw;
    const int rows = static_cast<int>(vertexOf_.size());
    Eigen::MatrixXd r(rows, 3);
    for (int i = 0; i < rows; ++i) r.row(i) = rhs.row(vertexOf_[i]);
    Eigen::MatrixXd x = factor_.solve(r);
    Eigen::MatrixXd out = rhs;  // hard: the visible markers' rows are the caller's to set
    const std::vector<int>& missing = gaps.missing;
    const int m = static_cast<int>(missing.size());
    if (m > 0) {
        Eigen::MatrixXd g(m, 3);
        for (int j = 0; j < m; ++j) {
            const MarkerPatch& p = markers_[missing[j]];
            const int cj = p.vertex;
            if (settings_.hard) {
                g.row(j) = rhs.row(cj);
                for (Eigen::SparseMatrix<double>::InnerIterator it(A_, cj); it; ++it)
                    if (unknownOf_[it.row()] >= 0)
                        g.row(j) -= it.value() * x.row(unknownOf_[it.row()]);
            } else {
                g.row(j).setZero();
                for (size_t i = 0; i < p.vertices.size(); ++i)
                    g.row(j) += p.weights[i] * x.row(unknownOf_[p.vertices[i]]);
            }
        }
        const Eigen::MatrixXd y = gaps.S.solve(g);
        for (int k = 0; k < m; ++k) {
            if (settings_.hard) {
                x -= correction_[missing[k]] * y.row(k);
                out.row(markers_[missing[k]].vertex) = y.row(k);
            } else {
                x += correction_[missing[k]] * y.row(k);
            }
        }
    }
    for (int i = 0; i < rows; ++i) out.row(vertexOf_[i]) = x.row(i);
    return out;
}

SolveResult LocalGlobalSolver::solve(const Positions& targets, const std::vector<double>& offsets,
                                     const Positions& start, FirstRotations first,
                                     const std::atomic<bool>* stop) {
    const auto t0 = std::chrono::steady_clock::now();
    const int n = rest_.vertexCount();
    const int K = static_cast<int>(markers_.size());
    std::vector<int> missing, visible;
    for (int k = 0; k < K; ++k) (targets.row(k).allFinite() ? visible : missing).push_back(k);
    const Gaps frameGaps = gaps(missing);

    SolveResult result;
    result.V = start;
    Positions& V = result.V;
    std::vector<char> pinned(n, 0);
    // The ε pull towards the start; (hard) the visible markers' columns, which are known.
    const Eigen::MatrixXd base = tikhonov_ * start;
    Eigen::MatrixXd fixed;
    if (settings_.hard) {
        fixed = Eigen::MatrixXd::Zero(n, 3);
        for (int k : visible) {
            const int c = markers_[k].vertex;
            V.row(c) = targets.row(k);
            pinned[c] = 1;
            for (Eigen::SparseMatrix<double>::InnerIterator it(A_, c); it; ++it)
                fixed.row(it.row()) += it.value() * targets.row(k);
        }
    }
    const double still = 1e-7 * diagonal_;
    Eigen::MatrixXd rhs;
    for (int it = 0; it < settings_.iterations; ++it) {
        if (stop && stop->load()) {
            result.report.stopped = true;
            return result;
        }
        if (it == 0 && first.rotations) {
            rotation_ = *first.rotations;
            arapRotation_ = *first.arapRotations;
            if (first.refit) fitRotations(V, rotation_, arapRotation_, true);
        } else {
            fitRotations(V, rotation_, arapRotation_, it > 0);
        }
        fitPatchRotations(V, rotation_, patchRotation_);
        rightHandSide(targets, offsets, visible, base, rhs);
        const Eigen::MatrixXd x = solveSystem(rhs, fixed, frameGaps);
        double moved = 0;
        for (int v = 0; v < n; ++v) {
            if (pinned[v]) continue;
            moved = std::max(moved, (x.row(v) - V.row(v)).cwiseAbs().maxCoeff());
            V.row(v) = x.row(v);
        }
        result.report.iterations = it + 1;
        if (moved < still) {
            result.report.converged = true;
            break;
        }
    }
    if (repair_ && rhs.size() > 0) {
        // Folds are judged in the ring rotations of the answer itself, as Metrics judges them:
        // first roughly (a Newton step), and only where a face comes near folding, exactly.
        std::vector<Mat3> ring = rotation_;
        rings_.fit(V, ring, true, kRotationStep);
        result.report.foldedFaces = 0;
        if (!repair_->folded(V, ring, kNearlyFolded).empty()) {
            rings_.fit(V, ring, true, FoldRepair::kCountStep);
            // A missing soft marker's pull is not in this frame's matrix.
            if (!settings_.hard && !missing.empty()) {
                const Eigen::SparseMatrix<double> A = frameMatrix(missing);
                result.report.foldedFaces = repair_->repair(V, {A, rhs}, pinned, ring);
            } else {
                result.report.foldedFaces = repair_->repair(V, {A_, rhs}, pinned, ring);
            }
        }
    }
    result.report.energyBefore = result.report.energyAfter =
        std::numeric_limits<double>::quiet_NaN();
    result.report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

double LocalGlobalSolver::energy(const Positions& V, const Positions& targets,
                                 const std::vector<double>& offsets) const {
    std::vector<Mat3> R, RA;
    fitRotations(V, R, RA, false);
    const Eigen::MatrixXd LV = L_ * V;
    double e = 0;
    for (int v = 0; v < rest_.vertexCount(); ++v)
        if (encoding_.encoded(v)) e += (LV.row(v).transpose() - R[v] * delta0_[v]).squaredNorm();
    e += arapWeight_ / 3.0 * arap_.energy(V, RA);
    if (!settings_.hard) {
        std::vector<Mat3> P;
        fitPatchRotations(V, R, P);
        for (int k = 0; k < static_cast<int>(markers_.size()); ++k)
            if (targets.row(k).allFinite())
                e += settings_.softWeight *
                     (markers_[k].centroid(V) - markerTarget(k, targets, offsets, P[k]))
                         .squaredNorm();
    }
    return e;
}

}  // namespace boneless
