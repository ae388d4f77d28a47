// The exact method's Gauss–Newton iteration and its direct solver. The problem it solves (the
// energy, its linearisation and the assembled system) is in Reconstruction.cpp.

#include <chrono>

#include "LineSearch.h"
#include "ReconstructionImpl.h"
#include "boneless/Metrics.h"

namespace boneless {

namespace {

// A step solved with an earlier factor is as good as a factorised one once conjugate gradients
// reach this relative residual.
constexpr double kReusedFactorTolerance = 1e-6;

}  // namespace

std::vector<int> Reconstruction::Impl::pinnedVertices(const Positions& targets) const {
    std::vector<int> pinned;
    for (int v = 0; v < rest.vertexCount(); ++v)
        if (topology->isIsolated(v)) pinned.push_back(v);
    if (!softMarkers())
        for (int k = 0; k < static_cast<int>(markers.size()); ++k)
            if (rowIsFinite(targets, k)) pinned.push_back(markers[k]);
    return pinned;
}

void Reconstruction::Impl::buildSystem(GuardHessian kind, const Positions& V,
                                       const Positions& targets, const std::vector<int>& pinned,
                                       Eigen::VectorXd& gradient) {
    assemble(V, targets, gradient);
    if (kind == GuardHessian::Exact) addRotationCoupling();
    for (int v : pinned) {
        system->pin(v);
        gradient.segment<3>(3 * v).setZero();
    }
}

std::optional<Reconstruction::Impl::GuardHessian> Reconstruction::Impl::solveStep(
    GuardHessian wanted, const std::function<void(GuardHessian)>& build,
    const std::vector<int>& pinned, bool& factorisedThisSolve, Eigen::VectorXd& gradient,
    Eigen::VectorXd& step, SolveReport& report) {
    // The last factor, made earlier in this solve, preconditions conjugate gradients on this
    // step's matrix (of either kind: a frame alternates them); three quarters of a
    // factorisation's cost at most, so that a failed try costs less than the factorisation after
    // it. Not while the orientation guard has terms (then or now): they are stiff, and come and
    // go between steps, so the tries mostly fail (docs/benchmarks.md).
    const int reuseIterations = system->reuseAllowance();
    if (factorisedThisSolve && factorWithoutOrientationTerms && orientationTerms.empty() &&
        reuseIterations >= BlockSystem::kMinimumReuseIterations) {
        build(wanted);
        system->addToDiagonal(tikhonov());
        int its = 0;
        const bool solved = system->solveByLastFactor(gradient, step, reuseIterations,
                                                      kReusedFactorTolerance, &its);
        report.linearIterations += its;
        if (solved) {
            // An earlier factor may lack this frame's pins (a marker back from a gap): conjugate
            // gradients leave their rows near zero, a factorisation exactly zero.
            for (int v : pinned) step.segment<3>(3 * v).setZero();
            return wanted;
        }
    }
    // Indefinite with the coupling: this step goes without it.
    const std::optional<GuardHessian> kind =
        wanted == GuardHessian::Exact
            ? factorizeFirstOf({GuardHessian::Exact, GuardHessian::GaussNewton}, build)
            : factorizeFirstOf({GuardHessian::GaussNewton}, build);
    if (!kind) return std::nullopt;
    factorWithoutOrientationTerms = orientationTerms.empty();
    factorisedThisSolve = true;
    ++report.directSteps;
    step = system->solve(gradient);
    return kind;
}

SolveResult Reconstruction::Impl::solveExact(const Positions& targets, const Positions* guess,
                                             const std::atomic<bool>* stop) {
    const auto start = std::chrono::steady_clock::now();
    SolveResult result;
    result.V = startingPose(targets, guess);
    Positions& V = result.V;
    // The last factor is reused as a preconditioner by the steps after it, in this solve only:
    // one from another frame would make the answer depend on which frame came before.
    bool factorisedThisSolve = false;
    const std::vector<int> pinned = pinnedVertices(targets);

    Eigen::VectorXd gradient;
    const auto build = [&](GuardHessian kind) { buildSystem(kind, V, targets, pinned, gradient); };
    const double still = 1e-10 * boundingBoxDiagonal(rest.V, rest.F);
    double E = linearise(V, targets);
    result.report.energyBefore = E;
    result.report.energies.push_back(E);
    // With the orientation guard on, the fold guard's exact Hessian (its rotations' derivative
    // added) once a step is accepted whole, gains less than 30 % and leaves no face at the
    // guard's threshold: near a minimum. The Gauss–Newton matrix otherwise, which converges only
    // linearly where a bend turns the rings. Far from a minimum the exact matrix can lead into
    // another basin. Without the orientation guard it is not used: converging further there
    // flips more faces, and nothing else holds them (figures: docs/benchmarks.md, "The exact
    // method's step choices").
    bool exact = false;
    for (int it = 0; it < options.maxIterations && E > 0; ++it) {
        if (stop && stop->load()) {
            result.report.stopped = true;
            return result;
        }
        Eigen::VectorXd step;
        const std::optional<GuardHessian> solvedWith =
            solveStep(exact ? GuardHessian::Exact : GuardHessian::GaussNewton, build, pinned,
                      factorisedThisSolve, gradient, step, result.report);
        if (!solvedWith) break;
        step = -step;
        exact = *solvedWith == GuardHessian::Exact;
        if (!step.allFinite()) break;
        // A step no vertex would visibly take: the energy is at round-off (a rest or rigid
        // pose), where every step still halves it and the relative test never stops.
        if (step.cwiseAbs().maxCoeff() < still) {
            result.report.converged = true;
            break;
        }

        const bool exactStep = exact;
        double Enew = E, alpha = 0;
        Positions trial;
        const bool accepted = armijoBacktrack(
            V, step, E, gradient.dot(step), [&](const Positions& X) { return energy(X, targets); },
            trial, Enew, &alpha);
        exact = false;
        if (!accepted) {
            // The exact matrix can point where the guards' terms rise at once (the orientation
            // guard is one-sided): such a step is taken again with the Gauss–Newton matrix.
            if (exactStep) continue;
            result.report.converged = true;  // no descent left along the Gauss–Newton direction
            break;
        }
        V.swap(trial);
        const double decrease = (E - Enew) / E;
        result.report.iterations = it + 1;
        E = linearise(V, targets);
        result.report.energies.push_back(E);
        exact = orientation && foldGuardOn() && alpha == 1.0 && decrease < 0.3 &&
                orientationTerms.empty();
        // One face turning over barely changes the total: the relative decrease alone would
        // stop with the fold in place.
        if (decrease < options.relativeTolerance && !anyTurnedOver()) {
            result.report.converged = true;
            break;
        }
    }
    result.report.energyAfter = E;
    result.report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace boneless
