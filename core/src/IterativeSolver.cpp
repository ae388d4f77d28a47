#include "IterativeSolver.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "LineSearch.h"
#include "Parallel.h"
#include "boneless/Error.h"

namespace boneless {

IterativeSolver::IterativeSolver(Reconstruction::Impl& problem) : p_(problem) {
    const MeshTopology& topo = *p_.topology;
    n_ = topo.vertexCount();
    inOffsets_.assign(n_ + 1, 0);
    for (int u = 0; u < n_; ++u)
        if (p_.encoding->encoded(u))
            for (int k = 0; k < topo.valence(u); ++k) ++inOffsets_[topo.ring(u)[k] + 1];
    for (int v = 0; v < n_; ++v) inOffsets_[v + 1] += inOffsets_[v];
    inSlot_.resize(inOffsets_[n_]);
    inVertex_.resize(inOffsets_[n_]);
    std::vector<int> fill(inOffsets_.begin(), inOffsets_.end() - 1);
    for (int u = 0; u < n_; ++u)
        if (p_.encoding->encoded(u))
            for (int k = 0; k < topo.valence(u); ++k) {
                const int at = fill[topo.ring(u)[k]]++;
                inSlot_[at] = topo.offsets()[u] + k;
                inVertex_[at] = u;
            }
    scratchJ_.resize(solverThreadCount());
    pinned_.assign(n_, 0);
}

void IterativeSolver::zeroPinned(Eigen::VectorXd& x) const {
    for (int v = 0; v < n_; ++v)
        if (pinned_[v]) x.segment<3>(3 * v).setZero();
}

double IterativeSolver::evaluate(const Positions& V, const Positions& targets, Linearisation& L,
                                 bool withCurvature) {
    const MeshTopology& topo = *p_.topology;
    const ShapeEncoding& enc = *p_.encoding;
    L.residual.resize(n_);
    L.jacobian.resize(topo.neighbours().size());
    std::vector<double> partial(solverThreadCount(), 0.0);
    parallelFor(n_, [&](int begin, int end, int t) {
        std::vector<Mat3>& J = scratchJ_[t];
        double e = 0;
        for (int v = begin; v < end; ++v) {
            if (!enc.encoded(v)) {
                L.residual[v].setZero();
                continue;
            }
            Vec3 F;
            enc.decodeWithJacobian(v, V, F, J);
            std::copy(J.begin(), J.end(), L.jacobian.begin() + topo.offsets()[v]);
            L.residual[v] = V.row(v).transpose() - F;
            e += L.residual[v].squaredNorm();
        }
        partial[t] = e;
    });
    double e = 0;
    for (double x : partial) e += x;
    const int K = static_cast<int>(p_.markers.size());
    L.markerDn.resize(K);
    L.markerMiss.assign(K, Vec3::Zero());
    L.markerObserved.assign(K, 0);
    if (p_.softMarkers())
        for (int k = 0; k < K; ++k) {
            L.markerDn[k].clear();
            if (!rowIsFinite(targets, k)) continue;
            L.markerObserved[k] = 1;
            L.markerMiss[k] = p_.markerPoint(k, V, &L.markerDn[k]) - targets.row(k).transpose();
            e += p_.options.softWeight * L.markerMiss[k].squaredNorm();
        }
    e *= 0.5;
    // The rotations are needed by the preconditioner even when the fold guard is off.
    if (&L != &current_ && current_.rotation.size() == static_cast<size_t>(n_))
        L.rotation = current_.rotation;
    L.couplingEdgesValid = false;
    p_.rigidity->fitRotations(V, L.rotation, true,
                              p_.rigid() && withCurvature ? &L.curvature : nullptr);
    if (p_.rigid()) e += p_.options.rigidityWeight * p_.rigidity->energy(V, L.rotation);
    L.orientation.clear();
    if (p_.orientation) e += p_.orientation->linearise(V, L.orientation);
    L.energy = e;
    return e;
}

void IterativeSolver::gradient(const Positions& V, const Linearisation& L,
                               Eigen::VectorXd& g) const {
    g.resize(3 * n_);
    const ShapeEncoding& enc = *p_.encoding;
    Eigen::MatrixXd rigid;
    if (p_.rigid()) {
        // For the fitted rotations: α(6 L V − 2 b), the envelope theorem's gradient.
        rigid = p_.rigidity->rotatedRestEdges(L.rotation);
        rigid = p_.options.rigidityWeight * (6.0 * (p_.rigidity->laplacian() * V) - 2.0 * rigid);
    }
    parallelFor(n_, [&](int begin, int end, int) {
        for (int v = begin; v < end; ++v) {
            Vec3 s = enc.encoded(v) ? L.residual[v] : Vec3::Zero();
            for (int i = inOffsets_[v]; i < inOffsets_[v + 1]; ++i)
                s -= L.jacobian[inSlot_[i]].transpose() * L.residual[inVertex_[i]];
            if (p_.rigid()) s += rigid.row(v).transpose();
            g.segment<3>(3 * v) = s;
        }
    });
    if (p_.softMarkers())
        for (size_t k = 0; k < p_.markers.size(); ++k) {
            if (!L.markerObserved[k]) continue;
            const int v = p_.markers[k];
            const double lambda = p_.options.softWeight, d = p_.offset(k);
            g.segment<3>(3 * v) += lambda * L.markerMiss[k];
            const int* ring = p_.topology->ring(v);
            for (size_t j = 0; j < L.markerDn[k].size(); ++j)
                g.segment<3>(3 * ring[j]) +=
                    lambda * d * L.markerDn[k][j].transpose() * L.markerMiss[k];
        }
    if (p_.orientation) p_.orientation->addGradient(L.orientation, g);
    zeroPinned(g);
}

void IterativeSolver::multiply(const Linearisation& L, const Eigen::VectorXd& x,
                               Eigen::VectorXd& y) {
    const MeshTopology& topo = *p_.topology;
    const ShapeEncoding& enc = *p_.encoding;
    ax_.resize(3 * n_);
    y.resize(3 * n_);
    parallelFor(n_, [&](int begin, int end, int) {
        for (int u = begin; u < end; ++u) {
            if (!enc.encoded(u)) {
                ax_.segment<3>(3 * u).setZero();
                continue;
            }
            Vec3 s = x.segment<3>(3 * u);
            const int* ring = topo.ring(u);
            const Mat3* J = L.jacobian.data() + topo.offsets()[u];
            for (int k = 0; k < topo.valence(u); ++k) s -= J[k] * x.segment<3>(3 * ring[k]);
            ax_.segment<3>(3 * u) = s;
        }
    });
    const double guard = 6.0 * p_.options.rigidityWeight;
    const auto& lap = p_.rigidity->laplacian();
    parallelFor(n_, [&](int begin, int end, int) {
        for (int v = begin; v < end; ++v) {
            Vec3 s = ax_.segment<3>(3 * v);
            for (int i = inOffsets_[v]; i < inOffsets_[v + 1]; ++i)
                s -= L.jacobian[inSlot_[i]].transpose() * ax_.segment<3>(3 * inVertex_[i]);
            if (guard > 0)
                // The Laplacian is symmetric: column v is row v.
                for (Eigen::SparseMatrix<double>::InnerIterator it(lap, v); it; ++it)
                    s += guard * it.value() * x.segment<3>(3 * it.row());
            y.segment<3>(3 * v) = s;
        }
    });
    if (p_.softMarkers())
        for (size_t k = 0; k < p_.markers.size(); ++k) {
            if (!L.markerObserved[k]) continue;
            const int v = p_.markers[k];
            const double lambda = p_.options.softWeight, d = p_.offset(k);
            const int* ring = p_.topology->ring(v);
            Vec3 Gx = x.segment<3>(3 * v);
            for (size_t j = 0; j < L.markerDn[k].size(); ++j)
                Gx += d * L.markerDn[k][j] * x.segment<3>(3 * ring[j]);
            y.segment<3>(3 * v) += lambda * Gx;
            for (size_t j = 0; j < L.markerDn[k].size(); ++j)
                y.segment<3>(3 * ring[j]) += lambda * d * L.markerDn[k][j].transpose() * Gx;
        }
    if (p_.rigid() && exactGuardHessian_) {
        if (!L.couplingEdgesValid) {
            p_.rigidity->rotatedCouplingEdges(L.rotation, L.couplingEdges);
            L.couplingEdgesValid = true;
        }
        p_.rigidity->addRotationCoupling(L.couplingEdges, L.curvature, x,
                                         -2.0 * p_.options.rigidityWeight, y);
    }
    if (p_.orientation) p_.orientation->addProduct(L.orientation, x, y);
    zeroPinned(y);
}

void IterativeSolver::precondition(const Linearisation& L, const Eigen::VectorXd& r,
                                   Eigen::VectorXd& z) const {
    if (lastFactor()) {
        // The factor is of a pose's own matrix, in its own frame: turning it by the rotations
        // fitted since was measured to make it worse (koala bend, frame 45's step with the
        // factor made for frame 41's: 0.0135 % after 5 iterations turned, 0.0019 % as it is).
        // solve() only gets here with a factor; solveAtCurrent() could without one.
        if (p_.system && p_.system->hasFactor())
            z = p_.system->solve(r);
        else
            z = r;
        zeroPinned(z);
        return;
    }
    rotated_.resize(3 * n_);
    for (int v = 0; v < n_; ++v)
        rotated_.segment<3>(3 * v) =
            pinned_[v] ? Vec3::Zero() : Vec3(L.rotation[v].transpose() * r.segment<3>(3 * v));
    if (p_.scalarPreconditioner()) {
        scalarRhs_ = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
            rotated_.data(), n_, 3);
        scalarRhs_ = p_.restScalar->solve(scalarRhs_);
        z.resize(3 * n_);
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(z.data(), n_, 3) =
            scalarRhs_;
    } else {
        z = p_.system->solve(rotated_);
    }
    for (int v = 0; v < n_; ++v)
        z.segment<3>(3 * v) = pinned_[v] ? Vec3::Zero() : Vec3(L.rotation[v] * z.segment<3>(3 * v));
}

int IterativeSolver::conjugateGradients(const Linearisation& L, const Eigen::VectorXd& g,
                                        Eigen::VectorXd& x) {
    // x may hold a starting guess (the last frame's motion); it is dropped when it does not
    // beat zero.
    cgR_ = -g;
    if (x.size() == 3 * n_ && x.allFinite() && x.squaredNorm() > 0) {
        zeroPinned(x);
        multiply(L, x, cgHp_);
        cgHp_ = cgR_ - cgHp_;
        if (cgHp_.norm() < cgR_.norm())
            cgR_ = cgHp_;
        else
            x.setZero(3 * n_);
    } else {
        x.setZero(3 * n_);
    }
    const double stop = p_.options.cgTolerance * g.norm();
    precondition(L, cgR_, cgZ_);
    cgP_ = cgZ_;
    double rz = cgR_.dot(cgZ_);
    int it = 0;
    cgConverged_ = cgR_.norm() <= stop;
    int cap = p_.options.maxCgIterations;
    if (lastFactor())
        cap = std::min(cap,
                       std::max(BlockSystem::kMinimumReuseIterations, p_.system->reuseAllowance()));
    while (it < cap) {
        multiply(L, cgP_, cgHp_);
        const double pHp = cgP_.dot(cgHp_);
        if (!(pHp > 0)) {
            // Negative curvature (the fold guard's exact Hessian is indefinite far from a
            // minimum): keep what was found, or the preconditioned gradient if nothing was; the
            // line search takes care of the rest, this is no reason to factorise.
            if (it == 0 && x.squaredNorm() == 0) x = cgP_;
            cgConverged_ = true;
            break;
        }
        const double a = rz / pHp;
        x += a * cgP_;
        cgR_ -= a * cgHp_;
        ++it;
        if (cgR_.norm() <= stop) {
            cgConverged_ = true;
            break;
        }
        precondition(L, cgR_, cgZ_);
        const double rzNew = cgR_.dot(cgZ_);
        cgP_ = cgZ_ + (rzNew / rz) * cgP_;
        rz = rzNew;
    }
    return it;
}

bool IterativeSolver::directStep(const Positions& V, const Positions& targets,
                                 Eigen::VectorXd& step) {
    // The blocks preconditioner lives in the system's factor, which this would overwrite.
    if (!lastFactor() && (!p_.options.directFallback || !p_.scalarPreconditioner())) return false;
    if (!p_.system) p_.buildBlockSystem();  // Preconditioner::LastFactor has no rest system
    BlockSystem& system = *p_.system;
    Eigen::VectorXd gradient;
    // With SolverOptions::exactFallback, the matrix conjugate gradients were solving: the fold
    // guard's exact Hessian once a step has been taken whole. Where that is indefinite (the inside
    // of a bend, rings compressed), each vertex's share clamped to its positive part; the
    // Gauss–Newton matrix last. Clamping where the sum is positive definite anyway slows
    // convergence (a tube bent 1.2 rad: 23 steps to 1e-10 instead of 13), so it is not the first
    // choice; where the sum is indefinite it is what converges (koala, bend frame 50: 0.0708 after
    // 20 steps, Gauss–Newton 0.0719).
    using Kind = Reconstruction::Impl::GuardHessian;
    auto build = [&](Kind kind) {
        p_.assemble(V, targets, gradient);
        if (kind != Kind::GaussNewton) p_.addRotationCoupling(kind == Kind::Clamped);
        for (int v = 0; v < n_; ++v)
            if (pinned_[v]) system.pin(v);
    };
    p_.linearise(V, targets);
    // A factor that is the next steps' preconditioner must be of the matrix they solve.
    const bool exact =
        (p_.options.exactFallback || lastFactor()) && exactGuardHessian_ && p_.rigid();
    ownFactor_ = false;
    if (!(exact ? p_.factorizeFirstOf({Kind::Exact, Kind::Clamped, Kind::GaussNewton}, build)
                : p_.factorizeFirstOf({Kind::GaussNewton}, build)))
        return false;
    for (int v = 0; v < n_; ++v)
        if (pinned_[v]) gradient.segment<3>(3 * v).setZero();
    Eigen::VectorXd direct = -system.solve(gradient);
    if (!direct.allFinite()) return false;
    ownFactor_ = true;
    step.swap(direct);
    return true;
}

void IterativeSolver::recycledStart(const Eigen::VectorXd& g, Eigen::VectorXd& step) {
    std::vector<Eigen::VectorXd> B;
    for (const Eigen::VectorXd& w : recycled_) {
        Eigen::VectorXd b = w;
        zeroPinned(b);
        const double before = b.norm();
        for (const Eigen::VectorXd& q : B) b -= q.dot(b) * q;
        const double after = b.norm();
        if (after > 1e-6 * before && after > 0) B.push_back(b / after);
    }
    const int m = static_cast<int>(B.size());
    step.setZero(3 * n_);
    if (m == 0) return;
    std::vector<Eigen::VectorXd> HB(m);
    for (int j = 0; j < m; ++j) multiply(current_, B[j], HB[j]);
    Eigen::MatrixXd A(m, m);
    Eigen::VectorXd rhs(m);
    for (int i = 0; i < m; ++i) {
        rhs[i] = -B[i].dot(g);
        for (int j = 0; j < m; ++j) A(i, j) = 0.5 * (B[i].dot(HB[j]) + B[j].dot(HB[i]));
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
    const double top = eig.eigenvalues().cwiseAbs().maxCoeff();
    Eigen::VectorXd y = Eigen::VectorXd::Zero(m);
    for (int k = 0; k < m; ++k) {
        const double lambda = eig.eigenvalues()[k];
        if (lambda > 1e-10 * top)
            y += eig.eigenvectors().col(k) * (eig.eigenvectors().col(k).dot(rhs) / lambda);
    }
    for (int j = 0; j < m; ++j) step += y[j] * B[j];
}

void IterativeSolver::blockJacobi(const Eigen::VectorXd& g, Eigen::VectorXd& d) const {
    const ShapeEncoding& enc = *p_.encoding;
    const auto& lap = p_.rigidity->laplacian();
    const double guard = 6.0 * p_.options.rigidityWeight;
    d.resize(3 * n_);
    parallelFor(n_, [&](int begin, int end, int) {
        for (int v = begin; v < end; ++v) {
            if (pinned_[v]) {
                d.segment<3>(3 * v).setZero();
                continue;
            }
            Mat3 D = enc.encoded(v) ? Mat3(Mat3::Identity()) : Mat3(Mat3::Zero());
            for (int i = inOffsets_[v]; i < inOffsets_[v + 1]; ++i) {
                const Mat3& J = current_.jacobian[inSlot_[i]];
                D.noalias() += J.transpose() * J;
            }
            D.diagonal().array() += guard * lap.coeff(v, v) + 1e-12;
            d.segment<3>(3 * v) = -D.ldlt().solve(g.segment<3>(3 * v));
        }
    });
}

void IterativeSolver::pinFor(const Positions& targets) {
    for (int v = 0; v < n_; ++v) pinned_[v] = p_.topology->isIsolated(v);
    if (!p_.softMarkers())
        for (size_t k = 0; k < p_.markers.size(); ++k)
            if (rowIsFinite(targets, static_cast<int>(k))) pinned_[p_.markers[k]] = 1;
}

double IterativeSolver::gradientAt(const Positions& V, const Positions& targets, Eigen::VectorXd& g,
                                   bool lastSolved) {
    if (!lastSolved) {
        pinFor(targets);
        // Gradient only: the Hessian's rotation curvature is not needed.
        evaluate(V, targets, current_, false);
    }
    gradient(V, current_, g);
    return current_.energy;
}

SolveResult IterativeSolver::solve(const Positions& targets, const Positions* guess) {
    const auto start = std::chrono::steady_clock::now();
    SolveResult result;
    result.V = p_.startingPose(targets, guess);
    Positions& V = result.V;
    const Positions startPose = V;
    pinFor(targets);

    double E = evaluate(V, targets, current_);
    result.report.energyBefore = E;
    result.report.energies.push_back(E);
    Eigen::VectorXd g, step;
    bool goDirect = false;
    Positions trial(n_, 3);
    // The fold guard's exact Hessian (with its rotations' derivative) converges quadratically
    // near a minimum, but far from one it can lead into another basin. The horse gallop at 40
    // markers (big moves between frames), multiresolution, worst frame: 902 faces flipped
    // against the truth with the exact Hessian throughout, 217 with the Gauss–Newton matrix
    // throughout (which on koala needs 7.5 coarse iterations a frame instead of 2.5). So a solve
    // starts with the Gauss–Newton matrix and takes the exact one once a step is accepted whole,
    // near the minimum: 361 faces, 3.0 iterations. A start known to be near the minimum (a
    // prolongation) takes the exact one at once.
    exactGuardHessian_ = startsNearMinimum_;
    if (!callerTellsJumps_ && !recycled_.empty() &&
        !(guess && guess->rows() == lastAnswer_.rows() &&
          (*guess - lastAnswer_).cwiseAbs().maxCoeff() == 0))
        forgetMotions();
    ++frames_;
    const bool projectOnly =
        p_.options.refreshEvery > 1 && !recycled_.empty() && frames_ % p_.options.refreshEvery != 0;
    // A face the orientation guard sees turned over (a multiresolution input level's, whose
    // guard this is) is worth a few more steps, as the direct method does not stop with one
    // either. The horse gallop at 40 markers, one fine step a frame: 5 faces folded in the worst
    // frame and none with up to 4 more steps, 2 % more time a frame.
    const int steps = projectOnly ? 1 : p_.options.maxIterations;
    constexpr int turnedOverSteps = 4;
    auto turnedOver = [&] {
        return p_.orientation && p_.orientation->anyTurnedOver(current_.orientation);
    };
    for (int it = 0; (it < steps || (it < steps + turnedOverSteps && turnedOver())) && E > 0;
         ++it) {
        gradient(V, current_, g);
        if (it == 0 && !recycled_.empty())
            recycledStart(g, step);
        else if (it == 0 && lastMotion_.size() == 3 * n_)
            step = lastMotion_;
        else
            step.resize(0);
        if (!projectOnly) {
            // Without a factor of its own, a Preconditioner::LastFactor step makes one.
            if (lastFactor() && !(ownFactor_ && p_.system->hasFactor())) goDirect = true;
            int cgIts = 0;
            if (goDirect)
                step = -g;  // kept if the factorisation fails
            else
                cgIts = conjugateGradients(current_, g, step);
            if ((goDirect || !cgConverged_) && directStep(V, targets, step)) {
                ++result.report.directSteps;
                // Once conjugate gradients have failed in a frame, its remaining steps go direct;
                // with the last factor as preconditioner, the factor just made serves them.
                goDirect = !lastFactor();
            }
            result.report.linearIterations += cgIts;
        }
        if (!step.allFinite()) break;
        double slope = g.dot(step);
        if (!(slope < 0)) {
            step = -g;  // never happens with an SPD system; steepest descent keeps it safe
            slope = -g.squaredNorm();
        }
        double Enew = E, alpha = 0;
        const bool accepted = armijoBacktrack(
            V, step, E, slope, [&](const Positions& X) { return evaluate(X, targets, trial_); },
            trial, Enew, &alpha);
        exactGuardHessian_ = accepted && alpha == 1.0;
        if (!accepted) {
            result.report.converged = true;  // no descent left along the Gauss–Newton direction
            break;
        }
        V.swap(trial);
        std::swap(current_, trial_);
        const double decrease = (E - Enew) / E;
        E = Enew;
        result.report.iterations = it + 1;
        result.report.energies.push_back(E);
        if (decrease < p_.options.relativeTolerance) {
            // Conjugate gradients meet their relative tolerance on the gradient's largest part: a
            // marker whose ring has nearly collapsed gives its offset's normal a huge derivative,
            // and they stop at a step 1e-7 long with the rest of the gradient untouched. A frame
            // whose first step gains that little is stepped directly before being called done.
            // Seen on the coarsest level of the demo at twice its resolution: stopped 22 mm from
            // the markers after one step; 1.5 mm after direct steps.
            // (Preconditioner::LastFactor: a factorisation of this pose's own matrix. Kept in
            // this frame's goDirect, so that a frame with no step left does not leave the next
            // one a factorisation: the multiresolution method's input takes one step a frame.)
            if (it == 0 && !goDirect && !projectOnly && result.report.directSteps == 0 &&
                (p_.options.directFallback || lastFactor())) {
                goDirect = true;
                continue;
            }
            result.report.converged = true;
            break;
        }
    }
    lastMotion_.resize(3 * n_);
    for (int v = 0; v < n_; ++v)
        lastMotion_.segment<3>(3 * v) = (V.row(v) - startPose.row(v)).transpose();
    if (p_.options.recycledMotions > 0 && !projectOnly && lastMotion_.squaredNorm() > 0) {
        if (static_cast<int>(recycled_.size()) >= p_.options.recycledMotions)
            recycled_.erase(recycled_.begin());
        recycled_.push_back(lastMotion_);
    }
    if (p_.options.recycledMotions > 0 && !callerTellsJumps_) lastAnswer_ = V;
    result.report.energyAfter = E;
    result.report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace boneless
