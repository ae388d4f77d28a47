#include "boneless/Reconstruction.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "ReconstructionImpl.h"
#include "boneless/Error.h"
#include "boneless/Metrics.h"

namespace boneless {

const char* methodName(SolverOptions::Method method) {
    return method == SolverOptions::Method::Exact ? "exact" : "local-global";
}

bool parseMethod(const std::string& name, SolverOptions::Method& method) {
    for (auto m : {SolverOptions::Method::LocalGlobal, SolverOptions::Method::Exact})
        if (name == methodName(m)) {
            method = m;
            return true;
        }
    return false;
}

Reconstruction::Impl::Impl() = default;
Reconstruction::Impl::~Impl() = default;

Vec3 Reconstruction::Impl::markerPoint(size_t k, const Positions& V, std::vector<Mat3>* dn) const {
    const int v = markers[k];
    Vec3 x = V.row(v).transpose();
    const double d = offset(k);
    if (d != 0 && encoding->encoded(v)) x += d * encoding->ringNormal(v, V, dn);
    return x;
}

double Reconstruction::Impl::markerEnergy(const Positions& V, const Positions& targets) const {
    double e = 0;
    if (softMarkers())
        for (size_t k = 0; k < markers.size(); ++k)
            if (rowIsFinite(targets, static_cast<int>(k)))
                e += options.markerWeight *
                     (markerPoint(k, V) - targets.row(k).transpose()).squaredNorm();
    return e;
}

double Reconstruction::Impl::foldGuardEnergy(const Positions& V, std::vector<Mat3>& R,
                                             std::vector<Mat3>* curvature) const {
    foldGuardTerm->fitRotations(V, R, false, curvature);
    return options.foldGuard * foldGuardTerm->energy(V, R);
}

double Reconstruction::Impl::energy(const Positions& V, const Positions& targets) const {
    double e = markerEnergy(V, targets);
    for (int v : residualOf) e += (V.row(v).transpose() - encoding->decode(v, V)).squaredNorm();
    e *= 0.5;
    if (foldGuardOn()) {
        std::vector<Mat3> R;
        e += foldGuardEnergy(V, R);
    }
    if (orientation) e += orientation->energy(V);
    return e;
}

void Reconstruction::Impl::updateOrientationGuard() {
    orientation.reset();
    if (options.orientationGuard <= 0) return;
    orientation = std::make_unique<OrientationGuard>(rest, options.orientationGuard, 0.2);
}

double Reconstruction::Impl::linearise(const Positions& V, const Positions& targets) {
    const int count = static_cast<int>(residualOf.size());
    residual.resize(count);
    jacobian.resize(topology->neighbours().size());
    std::vector<Mat3> J;
    double e = 0;
    for (int r = 0; r < count; ++r) {
        const int v = residualOf[r];
        Vec3 F;
        encoding->decodeWithJacobian(v, V, F, J);
        std::copy(J.begin(), J.end(), jacobian.begin() + topology->offsets()[v]);
        residual[r] = V.row(v).transpose() - F;
        e += residual[r].squaredNorm();
    }
    e += markerEnergy(V, targets);
    e *= 0.5;
    if (foldGuardOn()) e += foldGuardEnergy(V, rotations, &rotationCurvature);
    if (orientation) e += orientation->linearise(V, orientationTerms);
    return e;
}

void Reconstruction::Impl::assemble(const Positions& V, const Positions& targets,
                                    Eigen::VectorXd& g) {
    BlockSystem& system = *this->system;
    system.clear();
    Eigen::VectorXd* gradient = &g;
    const int n = rest.vertexCount();
    gradient->setZero(3 * n);
    const auto& topo = *topology;
    for (int r = 0; r < static_cast<int>(residualOf.size()); ++r) {
        const int v = residualOf[r];
        const int m = topo.valence(v);
        const int* ring = topo.ring(v);
        const Mat3* J = jacobian.data() + topo.offsets()[v];
        const Vec3& res = residual[r];
        // Stencil slot 0 is v itself (∂r/∂v = I), slot k+1 its k-th neighbour (∂r/∂p_k = −J_k).
        system.add(r, 0, 0, Mat3::Identity());
        if (gradient) gradient->segment<3>(3 * v) += res;
        for (int k = 0; k < m; ++k) {
            const Mat3 Jt = J[k].transpose();
            system.add(r, 0, k + 1, -J[k]);
            system.add(r, k + 1, 0, -Jt);
            if (gradient) gradient->segment<3>(3 * ring[k]) -= Jt * res;
            for (int l = 0; l < m; ++l) system.addGram(r, k + 1, l + 1, J[k], J[l]);
        }
    }
    if (foldGuardOn()) {
        // For the rotations fitted at V: Hessian 6αL ⊗ I, gradient α(6 L V − 2 b).
        const double a = options.foldGuard;
        const int firstFaceStencil = static_cast<int>(residualOf.size());
        for (int f = 0; f < rest.faceCount(); ++f)
            for (int c = 0; c < 3; ++c) {
                const Mat3 W = 6.0 * a * foldGuardTerm->cotangent(f, c) * Mat3::Identity();
                const int j = (c + 1) % 3, k = (c + 2) % 3;
                system.add(firstFaceStencil + f, j, j, W);
                system.add(firstFaceStencil + f, k, k, W);
                system.add(firstFaceStencil + f, j, k, -W);
                system.add(firstFaceStencil + f, k, j, -W);
            }
        if (gradient) {
            const Eigen::MatrixXd b = foldGuardTerm->rotatedRestEdges(rotations);
            const Eigen::MatrixXd LV = foldGuardTerm->laplacian() * V;
            for (int v = 0; v < n; ++v)
                gradient->segment<3>(3 * v) += a * (6.0 * LV.row(v) - 2.0 * b.row(v)).transpose();
        }
    }
    if (orientation) {
        const int firstFaceStencil = static_cast<int>(residualOf.size());
        for (const auto& t : orientationTerms)
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    system.add(firstFaceStencil + t.face, a, b,
                               t.derivative[a] * t.derivative[b].transpose());
        if (gradient) orientation->addGradient(orientationTerms, *gradient);
    }
    if (softMarkers())
        for (size_t k = 0; k < markers.size(); ++k) {
            if (!rowIsFinite(targets, static_cast<int>(k))) continue;
            const int v = markers[k];
            const double lambda = options.markerWeight;
            std::vector<Mat3> dn;
            const Vec3 miss = markerPoint(k, V, &dn) - targets.row(k).transpose();
            if (gradient) gradient->segment<3>(3 * v) += lambda * miss;
            if (dn.empty() || residualIndex[v] < 0) {
                system.addDiagonal(v, lambda * Mat3::Identity());
                continue;
            }
            // ∂g/∂v = I, ∂g/∂p_j = δ ∂n/∂p_j: the stencil of v's own residual holds them all.
            const double d = offset(k);
            const int r = residualIndex[v];
            const int* ring = topology->ring(v);
            const int m = topology->valence(v);
            system.add(r, 0, 0, lambda * Mat3::Identity());
            for (int j = 0; j < m; ++j) {
                const Mat3 Aj = d * dn[j];
                if (gradient) gradient->segment<3>(3 * ring[j]) += lambda * Aj.transpose() * miss;
                system.add(r, 0, j + 1, lambda * Aj);
                system.add(r, j + 1, 0, lambda * Aj.transpose());
                for (int i = 0; i < m; ++i)
                    system.add(r, j + 1, i + 1, lambda * Aj.transpose() * (d * dn[i]));
            }
        }
}

void Reconstruction::Impl::addRotationCoupling() {
    BlockSystem& system = *this->system;
    // Placed in the stencil of v's own residual: G_v only touches v and its ring.
    std::vector<std::pair<int, Mat3>> blocks;
    std::vector<Mat3> G, CG;
    const double scale = -2.0 * options.foldGuard;
    for (int v = 0; v < rest.vertexCount(); ++v) {
        const int r = residualIndex[v];
        const Mat3& C = rotationCurvature[v];
        // A vertex without a residual has no stencil to hold G_v, and a zero C_v (the rotation's
        // fit not at a maximum) couples nothing: the fixed-rotation matrix stands for both.
        if (r < 0 || C.isZero(0)) continue;
        foldGuardTerm->couplingBlocks(v, rotations[v], blocks);
        const int m = topology->valence(v);
        const int* ring = topology->ring(v);
        auto slotOf = [&](int u) {
            if (u == v) return 0;
            for (int k = 0; k < m; ++k)
                if (ring[k] == u) return k + 1;
            return -1;
        };
        G.assign(m + 1, Mat3::Zero());
        bool inside = true;
        for (const auto& [u, block] : blocks) {
            const int slot = slotOf(u);
            if (slot < 0)
                inside = false;
            else
                G[slot] += block;
        }
        if (!inside) continue;  // a face around v that is not in its ring: leave it out
        CG.resize(m + 1);
        for (int b = 0; b <= m; ++b) CG[b] = scale * C * G[b];
        for (int a = 0; a <= m; ++a)
            for (int b = 0; b <= m; ++b) system.addGram(r, a, b, G[a], CG[b]);
    }
}

std::optional<Reconstruction::Impl::GuardHessian> Reconstruction::Impl::factorizeFirstOf(
    std::initializer_list<GuardHessian> kinds, const std::function<void(GuardHessian)>& build) {
    double term = 0;
    for (GuardHessian kind : kinds) {
        build(kind);
        term = tikhonov();
        if (system->factorize(term)) return kind;
    }
    const GuardHessian last = *(kinds.end() - 1);
    build(last);  // factorize() added the first term to the values already
    if (system->factorize(term * 1e4)) return last;
    return std::nullopt;
}

Reconstruction::Reconstruction() : impl_(std::make_unique<Impl>()) {}
Reconstruction::~Reconstruction() = default;
Reconstruction::Reconstruction(Reconstruction&&) noexcept = default;
Reconstruction& Reconstruction::operator=(Reconstruction&&) noexcept = default;

void Reconstruction::prepare(const TriMesh& rest, std::vector<int> markerVertices,
                             SolverOptions options) {
    std::vector<SurfacePoint> points(markerVertices.size());
    for (size_t k = 0; k < points.size(); ++k) points[k].vertex = markerVertices[k];
    prepare(rest, std::move(points), std::move(options));
}

void Reconstruction::prepare(const TriMesh& rest, std::vector<SurfacePoint> points,
                             SolverOptions options) {
    auto impl = std::make_unique<Impl>();
    impl->rest = rest;
    impl->options = options;
    const int n = rest.vertexCount();
    impl->markerOf.assign(n, -1);
    std::vector<int> markerVertices;
    for (size_t k = 0; k < points.size(); ++k) {
        const SurfacePoint& p = points[k];
        if (p.face >= rest.faceCount() ||
            (p.face >= 0 && (rest.F.row(p.face).array() != p.vertex).all()))
            throw SolverError("marker " + std::to_string(k) + " is on face " +
                              std::to_string(p.face) + ", which is not a face of the mesh around " +
                              "vertex " + std::to_string(p.vertex));
        markerVertices.push_back(p.vertex);
    }
    for (size_t k = 0; k < markerVertices.size(); ++k) {
        const int v = markerVertices[k];
        if (v < 0 || v >= n)
            throw SolverError("marker " + std::to_string(k) + " is attached to vertex " +
                              std::to_string(v) + ", but the mesh has " + std::to_string(n) +
                              " vertices");
        if (impl->markerOf[v] != -1)
            throw SolverError("markers " + std::to_string(impl->markerOf[v]) + " and " +
                              std::to_string(k) + " are both attached to vertex " +
                              std::to_string(v));
        impl->markerOf[v] = static_cast<int>(k);
    }
    impl->markers = std::move(markerVertices);

    if (!options.markerOffsets.empty() && options.markerOffsets.size() != impl->markers.size())
        throw SolverError(std::to_string(options.markerOffsets.size()) + " marker offsets for " +
                          std::to_string(impl->markers.size()) + " markers");
    if (options.constraints == SolverOptions::Constraints::Hard)
        for (double d : options.markerOffsets)
            if (d != 0)
                throw SolverError(
                    "marker offsets need soft constraints (a hard constraint puts the "
                    "vertex itself on the marker)");
    if (options.constraints == SolverOptions::Constraints::Hard)
        for (const SurfacePoint& p : points)
            if (p.face >= 0)
                throw SolverError(
                    "a hard constraint puts a vertex on its marker, not a face point");
    impl->topology = std::make_unique<MeshTopology>(impl->rest);
    impl->encoding = std::make_unique<ShapeEncoding>(impl->rest, *impl->topology);
    if (auto carried = std::make_unique<CarriedParts>(impl->rest, impl->markers);
        !carried->empty()) {
        std::vector<SurfacePoint> solvedPoints = points;
        for (SurfacePoint& p : solvedPoints) {
            p.vertex = carried->solvedVertex(p.vertex);
            if (p.face >= 0) p.face = carried->solvedFace(p.face);
        }
        impl->solved = std::make_unique<Reconstruction>();
        impl->solved->prepare(carried->solvedMesh(), std::move(solvedPoints), options);
        impl->carried = std::move(carried);
    } else if (options.method == SolverOptions::Method::LocalGlobal) {
        for (const SurfacePoint& p : points)
            impl->patches.push_back(makeMarkerPatch(impl->rest, *impl->encoding, p));
        impl->localGlobal = std::make_unique<LocalGlobalMethod>(
            impl->rest, *impl->topology, *impl->encoding, impl->patches,
            options.constraints == SolverOptions::Constraints::Hard, options.markerWeight);
    } else {
        impl->residualIndex.assign(n, -1);
        for (int v = 0; v < n; ++v) {
            if (!impl->encoding->encoded(v)) continue;
            impl->residualIndex[v] = static_cast<int>(impl->residualOf.size());
            impl->residualOf.push_back(v);
        }
        impl->foldGuardTerm = std::make_unique<ArapEnergy>(impl->rest);
        impl->updateOrientationGuard();
        impl->system = std::make_unique<BlockSystem>(n, impl->stencils());
    }
    impl->points = std::move(points);
    impl_ = std::move(impl);
    impl_->restMarkers = markerPositions(impl_->rest.V);
}

Positions Reconstruction::markerPositions(const Positions& V) const {
    const Impl& s = *impl_;
    if (s.solved) return s.solved->markerPositions(s.carried->solvedRows(V));
    const int K = static_cast<int>(s.markers.size());
    Positions P(K, 3);
    for (int k = 0; k < K; ++k) {
        if (s.patches.empty()) {  // the exact method: the vertex, off along its ring's normal
            P.row(k) = s.markerPoint(k, V).transpose();
            continue;
        }
        const MarkerPatch& p = s.patches[k];
        // A patch too small to fit a rotation turns its offset with the ring's normal.
        Mat3 R = Mat3::Identity();
        if (!p.fittable && s.encoding->encoded(p.vertex)) {
            const Vec3 from = s.encoding->ringNormal(p.vertex, s.rest.V);
            const Vec3 to = s.encoding->ringNormal(p.vertex, V);
            R = Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
        }
        P.row(k) = p.point(V, p.rotation(s.rest.V, V, R), s.offset(k)).transpose();
    }
    return P;
}

Positions Reconstruction::Impl::startingPose(const Positions& targets,
                                             const Positions* guess) const {
    const int n = rest.vertexCount();
    const int K = static_cast<int>(markers.size());
    const RigidMotion motion = fitRigidMotion(restMarkers, targets);
    Positions V;
    if (guess) {
        V = *guess;
    } else {
        V.resize(n, 3);
        for (int v = 0; v < n; ++v) V.row(v) = motion.apply(rest.V.row(v).transpose()).transpose();
    }
    // Isolated vertices have no shape to keep; they follow the markers' overall rigid motion.
    for (int v = 0; v < n; ++v)
        if (topology->isIsolated(v)) V.row(v) = motion.apply(rest.V.row(v).transpose()).transpose();
    if (!softMarkers())
        for (int k = 0; k < K; ++k)
            if (rowIsFinite(targets, k)) V.row(markers[k]) = targets.row(k);
    return V;
}

SolveResult Reconstruction::solve(const Positions& targets, const Positions* guess,
                                  const std::atomic<bool>* stop) {
    Impl& s = *impl_;
    if (!s.topology) throw SolverError("solve() called before prepare()");
    const int n = s.rest.vertexCount();
    const int K = static_cast<int>(s.markers.size());
    if (targets.rows() != K)
        throw SolverError("expected " + std::to_string(K) + " marker targets, got " +
                          std::to_string(targets.rows()));
    if (guess && guess->rows() != n)
        throw SolverError("the initial guess has " + std::to_string(guess->rows()) +
                          " vertices, the mesh " + std::to_string(n));
    if (s.solved) {
        Positions solvedGuess;
        if (guess) solvedGuess = s.carried->solvedRows(*guess);
        SolveResult result = s.solved->solve(targets, guess ? &solvedGuess : nullptr, stop);
        // A stopped solve's positions are no answer (often none): nothing to carry.
        if (!result.report.stopped) result.V = s.carried->whole(result.V);
        return result;
    }
    if (s.localGlobal) {
        // Each frame from its own markers: no guess, so that no history can matter. With none
        // visible there is nothing to follow: the rest pose.
        bool anyVisible = false;
        for (int k = 0; k < K; ++k) anyVisible = anyVisible || rowIsFinite(targets, k);
        if (!anyVisible) {
            SolveResult rest;
            rest.V = s.rest.V;
            return rest;
        }
        return s.localGlobal->solve(targets, s.options.markerOffsets,
                                    s.startingPose(targets, nullptr),
                                    fitRigidMotion(s.restMarkers, targets).R, stop);
    }
    return s.solveExact(targets, guess, stop);
}

Stencils Reconstruction::Impl::stencils() const {
    Stencils stencils;
    stencils.offsets.reserve(residualOf.size() + rest.faceCount() + 1);
    stencils.vertices.reserve(topology->neighbours().size() + residualOf.size() +
                              3 * static_cast<size_t>(rest.faceCount()));
    for (int v : residualOf) {
        stencils.push(v);
        for (int k = 0; k < topology->valence(v); ++k) stencils.push(topology->ring(v)[k]);
        stencils.close();
    }
    // Faces are stencils too, for the fold guard's terms (no residual of their own).
    for (int f = 0; f < rest.faceCount(); ++f) {
        for (int c = 0; c < 3; ++c) stencils.push(rest.F(f, c));
        stencils.close();
    }
    return stencils;
}

double Reconstruction::energy(const Positions& V, const Positions& targets) const {
    if (impl_->solved) return impl_->solved->energy(impl_->carried->solvedRows(V), targets);
    if (impl_->localGlobal)
        return impl_->localGlobal->energy(V, targets, impl_->options.markerOffsets);
    return impl_->energy(V, targets);
}
const TriMesh& Reconstruction::rest() const {
    return impl_->rest;
}
const ShapeEncoding& Reconstruction::encoding() const {
    return *impl_->encoding;
}
const std::vector<int>& Reconstruction::markerVertices() const {
    return impl_->markers;
}
const SolverOptions& Reconstruction::options() const {
    return impl_->options;
}
void Reconstruction::setOptions(const SolverOptions& options) {
    const SolverOptions& old = impl_->options;
    // The method, and what the local/global factorisation holds, need preparing again.
    if (options.method != old.method || options.constraints != old.constraints ||
        (options.method == SolverOptions::Method::LocalGlobal &&
         options.markerWeight != old.markerWeight)) {
        prepare(TriMesh(impl_->rest), std::vector<SurfacePoint>(impl_->points), options);
        return;
    }
    const bool guardChanged = options.orientationGuard != old.orientationGuard;
    impl_->options = options;
    if (impl_->solved) impl_->solved->setOptions(options);
    impl_->restMarkers = markerPositions(impl_->rest.V);  // the offsets may have changed
    if (guardChanged && impl_->system) impl_->updateOrientationGuard();
}

}  // namespace boneless
