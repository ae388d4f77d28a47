#include "boneless/ArapDeformer.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <chrono>
#include <string>

#include "ArapEnergy.h"
#include "boneless/Error.h"

namespace boneless {

struct ArapDeformer::Impl {
    TriMesh rest;
    std::vector<int> markers;
    Options options;
    std::unique_ptr<ArapEnergy> energy;
    Eigen::SparseMatrix<double> laplacian;
    std::vector<char> activeKey;  // markers present when the factorisation was made
    std::vector<int> freeIndex;   // vertex -> row in the free system, or -1
    std::vector<int> fixedIndex;  // vertex -> column of freeToFixed, or -1
    // Simplicial: CHOLMOD's Supernodal module is GPL (docs/licence.md).
    Eigen::CholmodSimplicialLLT<Eigen::SparseMatrix<double>> factor;
    Eigen::SparseMatrix<double> freeToFixed;

    void refactorise(const std::vector<char>& active) {
        const int n = rest.vertexCount();
        std::vector<char> fixed(n, 0);
        for (size_t k = 0; k < markers.size(); ++k)
            if (active[k]) fixed[markers[k]] = 1;
        freeIndex.assign(n, -1);
        fixedIndex.assign(n, -1);
        int nf = 0, nc = 0;
        for (int v = 0; v < n; ++v) (fixed[v] ? fixedIndex[v] = nc++ : freeIndex[v] = nf++);
        std::vector<Eigen::Triplet<double>> ff, fc;
        for (int col = 0; col < laplacian.outerSize(); ++col)
            for (Eigen::SparseMatrix<double>::InnerIterator it(laplacian, col); it; ++it) {
                const int r = static_cast<int>(it.row());
                if (freeIndex[r] < 0) continue;
                if (freeIndex[col] >= 0)
                    ff.emplace_back(freeIndex[r], freeIndex[col], it.value());
                else
                    fc.emplace_back(freeIndex[r], fixedIndex[col], it.value());
            }
        Eigen::SparseMatrix<double> Lff(nf, nf);
        Lff.setFromTriplets(ff.begin(), ff.end());
        // Vertices with no faces have an empty row: give them an identity row so they stay put.
        for (int v = 0; v < n; ++v)
            if (freeIndex[v] >= 0 && laplacian.col(v).nonZeros() == 0)
                Lff.coeffRef(freeIndex[v], freeIndex[v]) = 1.0;
        freeToFixed.resize(nf, nc);
        freeToFixed.setFromTriplets(fc.begin(), fc.end());
        factor.compute(Lff);
        if (factor.info() != Eigen::Success)
            throw SolverError(
                "ARAP: the constrained Laplacian is not positive definite (a "
                "component without markers?)");
        activeKey = active;
    }
};

ArapDeformer::ArapDeformer() : impl_(std::make_unique<Impl>()) {}
ArapDeformer::~ArapDeformer() = default;

void ArapDeformer::prepare(const TriMesh& rest, std::vector<int> markerVertices, Options options) {
    auto impl = std::make_unique<Impl>();
    impl->rest = rest;
    impl->markers = std::move(markerVertices);
    impl->options = options;
    const int n = rest.vertexCount();
    for (size_t k = 0; k < impl->markers.size(); ++k)
        if (impl->markers[k] < 0 || impl->markers[k] >= n)
            throw SolverError("ARAP: marker " + std::to_string(k) + " is attached to vertex " +
                              std::to_string(impl->markers[k]) + ", but the mesh has " +
                              std::to_string(n) + " vertices");
    impl->energy = std::make_unique<ArapEnergy>(impl->rest);
    impl->laplacian = impl->energy->laplacian();
    impl_ = std::move(impl);
}

SolveResult ArapDeformer::solve(const Positions& targets, const Positions* guess) {
    Impl& s = *impl_;
    const auto start = std::chrono::steady_clock::now();
    const int n = s.rest.vertexCount(), K = static_cast<int>(s.markers.size());
    if (targets.rows() != K)
        throw SolverError("ARAP: expected " + std::to_string(K) + " marker targets, got " +
                          std::to_string(targets.rows()));
    std::vector<char> active(K);
    for (int k = 0; k < K; ++k) active[k] = targets.row(k).allFinite();
    if (active != s.activeKey) s.refactorise(active);

    Positions restMarkers(K, 3);
    for (int k = 0; k < K; ++k) restMarkers.row(k) = s.rest.V.row(s.markers[k]);
    SolveResult result;
    if (guess) {
        result.V = *guess;
    } else {
        const RigidMotion motion = fitRigidMotion(restMarkers, targets);
        result.V.resize(n, 3);
        for (int v = 0; v < n; ++v)
            result.V.row(v) = motion.apply(s.rest.V.row(v).transpose()).transpose();
    }
    Positions& V = result.V;
    Eigen::MatrixXd fixedPositions(s.freeToFixed.cols(), 3);
    for (int k = 0; k < K; ++k)
        if (active[k]) {
            V.row(s.markers[k]) = targets.row(k);
            fixedPositions.row(s.fixedIndex[s.markers[k]]) = targets.row(k);
        }

    std::vector<Mat3> R(n);
    for (int it = 0; it < s.options.iterations; ++it) {
        // Local step: each vertex's best rotation; global step: L V = b / 3 for those rotations.
        s.energy->fitRotations(V, R);
        const Eigen::MatrixXd b = s.energy->rotatedRestEdges(R) / 3.0;
        Eigen::MatrixXd bFree(s.freeToFixed.rows(), 3);
        for (int v = 0; v < n; ++v)
            if (s.freeIndex[v] >= 0) bFree.row(s.freeIndex[v]) = b.row(v);
        bFree -= s.freeToFixed * fixedPositions;
        const Eigen::MatrixXd x = s.factor.solve(bFree);
        for (int v = 0; v < n; ++v)
            if (s.freeIndex[v] >= 0 && s.laplacian.col(v).nonZeros() > 0)
                V.row(v) = x.row(s.freeIndex[v]);
        result.report.iterations = it + 1;
    }
    result.report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace boneless
