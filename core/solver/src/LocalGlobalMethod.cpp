#include "LocalGlobalMethod.h"

#include <algorithm>
#include <chrono>

#include "MeshHierarchy.h"
#include "boneless/Parallel.h"

namespace boneless {

namespace {

// Measured on horse-gallop and samba at 20, 40 and 80 markers (eval) and on CMU 85_02 on
// MakeHuman (docs/solver.md): a coarse level of about a thousand vertices, 20 iterations there
// with a stiffer ARAP term (thin parts are thinner there, and twisted more often).
constexpr int kCoarsestVertices = 1000;
constexpr int kCoarsestPerMarker = 10;
constexpr double kCoarseArapShare = 0.1;
constexpr int kCoarseIterations = 20;
// Hard markers sit on a mesh that is the actor (eval's sequences): the shape term leads, and one
// iteration on the input does it (a second changed no eval row's error by more than 0.01
// points). Soft markers come from a take, where the mesh is never the actor: the stiffer ARAP
// term keeps the mismatch from stretching the mesh, and the pull needs a second iteration to
// settle (CMU 85_02: marker residual 0.62 mm RMS, 1.95 mm with one; edge distortion 0.158,
// 0.229 with the hard markers' share).
constexpr double kHardArapShare = 0.01;
constexpr double kSoftArapShare = 0.1;
constexpr int kHardIterations = 1;
constexpr int kSoftIterations = 2;

}  // namespace

LocalGlobalSolver::Settings LocalGlobalMethod::inputSettings(bool hard, double softWeight) {
    return {hard, softWeight, hard ? kHardArapShare : kSoftArapShare,
            hard ? kHardIterations : kSoftIterations, true};
}

LocalGlobalMethod::LocalGlobalMethod(const TriMesh& rest, const MeshTopology& topology,
                                     const ShapeEncoding& encoding,
                                     const std::vector<MarkerPatch>& markers, bool hard,
                                     double softWeight) {
    const int n = rest.vertexCount();
    const LocalGlobalSolver::Settings input = inputSettings(hard, softWeight);
    const LocalGlobalSolver::Settings coarse{hard, softWeight, kCoarseArapShare, kCoarseIterations,
                                             false};
    const int coarsest =
        std::max(kCoarsestVertices, kCoarsestPerMarker * static_cast<int>(markers.size()));
    std::vector<int> markerVertices;
    for (const MarkerPatch& p : markers) markerVertices.push_back(p.vertex);
    coarse_ = std::make_unique<Coarse>();
    Coarse& c = *coarse_;
    // The input level's factorisation on one core, the hierarchy and the coarse level's on the
    // other.
    auto prepareCoarse = [&] {
        coarseOf_.resize(n);
        for (int v = 0; v < n; ++v) coarseOf_[v] = v;
        if (n < 2 * coarsest) {
            c.mesh = rest;
            c.original = coarseOf_;
        } else {
            HierarchyOptions options;
            options.coarsestVertices = coarsest;
            const MeshHierarchy hierarchy(rest, topology, markerVertices, options);
            c.mesh = hierarchy.coarsest().mesh;
            c.original = hierarchy.coarsest().original;
            // Down the levels: a vertex that survives keeps its index there, a removed one
            // follows the vertex it was collapsed into (which survives).
            for (int l = 0; l + 1 < hierarchy.levelCount(); ++l) {
                const HierarchyLevel& level = hierarchy.level(l);
                std::vector<int> next = level.coarser;
                for (size_t i = 0; i < level.removed.size(); ++i)
                    next[level.removed[i]] = level.coarser[level.collapsedInto[i]];
                for (int& x : coarseOf_) x = next[x];
            }
        }
        c.topology = std::make_unique<MeshTopology>(c.mesh);
        c.encoding = std::make_unique<ShapeEncoding>(c.mesh, *c.topology);
        // Each marker pulls its vertex there, from where its point sits on the input's rest
        // (with its normal), so that rest markers still give the rest and a rigid motion stays
        // rigid on the coarse level.
        std::vector<MarkerPatch> coarseMarkers = vertexPatches(c.mesh, *c.encoding, {});
        for (const MarkerPatch& m : markers) {
            SurfacePoint point;
            point.vertex = coarseOf_[m.vertex];
            MarkerPatch p = makeMarkerPatch(c.mesh, *c.encoding, point);
            p.sag = m.restCentroid + m.sag - c.mesh.V.row(point.vertex).transpose();
            p.restNormal = m.restNormal;
            coarseMarkers.push_back(std::move(p));
        }
        c.solver = std::make_unique<LocalGlobalSolver>(c.mesh, *c.topology, *c.encoding,
                                                       coarseMarkers, coarse);
    };
    auto prepareInputLevel = [&] {
        inputLevel_ = std::make_unique<LocalGlobalSolver>(rest, topology, encoding, markers, input);
    };
    runOnWorkers(2, [&](int task) { task == 0 ? prepareInputLevel() : prepareCoarse(); });
}

LocalGlobalMethod::~LocalGlobalMethod() = default;

SolveResult LocalGlobalMethod::solve(const Positions& targets, const std::vector<double>& offsets,
                                     const Positions& start, const Mat3& rigid,
                                     const std::atomic<bool>* stop) {
    const auto t0 = std::chrono::steady_clock::now();
    Coarse& c = *coarse_;
    const int nc = c.mesh.vertexCount();
    Positions coarseStart(nc, 3);
    for (int i = 0; i < nc; ++i) coarseStart.row(i) = start.row(c.original[i]);
    // The start is the rest moved rigidly (hard markers on their targets): the rotations are
    // fitted to it from that motion's, a Newton step or two away.
    rotation_.assign(nc, rigid);
    if (c.solver->solve(targets, offsets, coarseStart, {&rotation_, &rotation_, true}, stop)
            .report.stopped) {
        SolveResult stopped;
        stopped.report.stopped = true;
        return stopped;
    }
    const int n = static_cast<int>(coarseOf_.size());
    rotation_.resize(n);
    arapRotation_.resize(n);
    for (int v = 0; v < n; ++v) {
        rotation_[v] = c.solver->rotations()[coarseOf_[v]];
        arapRotation_[v] = c.solver->arapRotations()[coarseOf_[v]];
    }
    SolveResult result =
        inputLevel_->solve(targets, offsets, start, {&rotation_, &arapRotation_}, stop);
    result.report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return result;
}

}  // namespace boneless
