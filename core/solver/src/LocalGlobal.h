#pragma once

#include <Eigen/LU>
#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "ArapEnergy.h"
#include "FoldRepair.h"
#include "MarkerPatch.h"
#include "RingFit.h"
#include "SparseCholesky.h"
#include "boneless/Reconstruction.h"

namespace boneless {

// Local/global iterations on one factorisation (docs/algorithm.md §3–4), on one mesh. With W the
// projected mean-value weights and L = I − W, the seed energy is ½ Σ |(L V)_i − s_i n_i|², and
// the rest's (L V⁰)_i = δ⁰_i lies along the ring's normal. The local step fits each ring's
// rotation R_i from rest to pose (centre included, uniform weights), and the ARAP term's own
// rotations (cotangent covariance); the global step then minimises, for those rotations,
//   |L V − R δ⁰|² + (a/3) E_arap(V) + λ Σ_visible |u_kᵀ V + R_k (s_k + o_k n⁰_k) − m_k|²
//   (+ ε |V − start|²), with u_k marker k's patch weights and R_k the patch's fitted rotation,
// whose matrix LᵀL + a L_cot (+ λ Σ u_k u_kᵀ) never changes: it is factorised once,
// and an iteration is a 3-column back-substitution. The ARAP term keeps thin parts that few
// markers hold from twisting. A marker missing from a frame is taken out by a low-rank
// correction of that one factor (a Schur complement when hard, Woodbury when soft), so a gap
// never costs a factorisation.
class LocalGlobalSolver {
  public:
    struct Settings {
        bool hard = true;
        double softWeight = 100;  // λ
        double arapShare = 0.01;  // α, the ARAP term's share: a = α tr(LᵀL) / tr(L_cot)
        int iterations = 3;
        bool repairFolds = false;  // FoldRepair on the answer
    };

    // rest and encoding must outlive the solver; topology is read only while it is built.
    // Hard markers hold one vertex each (their patches of radius 0 at a vertex).
    LocalGlobalSolver(const TriMesh& rest, const MeshTopology& topology,
                      const ShapeEncoding& encoding, std::vector<MarkerPatch> markers,
                      Settings settings);
    ~LocalGlobalSolver();

    // The first iteration's rotations (#V each): used as they are, or (refit) fitted to the
    // start by Newton steps from them. Without them, fitted from scratch.
    struct FirstRotations {
        const std::vector<Mat3>* rotations = nullptr;
        const std::vector<Mat3>* arapRotations = nullptr;
        bool refit = false;
    };
    // targets: K by 3, NaN rows missing; offsets: K (soft) or empty; start: #V by 3.
    // stop: read before each iteration (Reconstruction::solve's).
    SolveResult solve(const Positions& targets, const std::vector<double>& offsets,
                      const Positions& start, FirstRotations first,
                      const std::atomic<bool>* stop = nullptr);
    // The rotations of the last local step.
    const std::vector<Mat3>& rotations() const { return rotation_; }
    const std::vector<Mat3>& arapRotations() const { return arapRotation_; }

    // What the global step minimises at V, for rotations fitted to V (no ε term).
    double energy(const Positions& V, const Positions& targets,
                  const std::vector<double>& offsets) const;
    const Settings& settings() const { return settings_; }

  private:
    void fitRotations(const Positions& V, std::vector<Mat3>& rotation,
                      std::vector<Mat3>& arapRotation, bool warm) const;
    // The global step's right-hand side for the current rotations (#V by 3).
    void rightHandSide(const Positions& targets, const std::vector<double>& offsets,
                       const std::vector<int>& visible, const Eigen::MatrixXd& base,
                       Eigen::MatrixXd& rhs);
    // A frame's missing markers and the small system that takes them out of the factor (the
    // same for every iteration of the frame).
    struct Gaps {
        std::vector<int> missing;
        Eigen::PartialPivLU<Eigen::MatrixXd> S;
    };
    Gaps gaps(const std::vector<int>& missing);
    // A x = raw over every vertex (hard: the visible markers' rows of x are theirs), with the
    // frame's missing markers taken out; fixed: A's columns of the visible hard markers times
    // their targets.
    Eigen::MatrixXd solveSystem(const Eigen::MatrixXd& raw, const Eigen::MatrixXd& fixed,
                                const Gaps& gaps);
    // The factor's answer to each missing marker's column, made the first time it is missing.
    void cacheCorrections(const std::vector<int>& missing);
    // Where the patch's centroid must go for marker k to meet its target, for the patch
    // rotation R.
    Vec3 markerTarget(int k, const Positions& targets, const std::vector<double>& offsets,
                      const Mat3& R) const;
    // Each patch's rotation for the pose V, given the ring rotations fitted to it.
    void fitPatchRotations(const Positions& V, const std::vector<Mat3>& rotation,
                           std::vector<Mat3>& patchRotation) const;
    // The frame's matrix: A_ with the missing soft markers' terms taken off (for the repair).
    Eigen::SparseMatrix<double> frameMatrix(const std::vector<int>& missing) const;

    const TriMesh& rest_;
    const ShapeEncoding& encoding_;
    std::vector<MarkerPatch> markers_;
    Settings settings_;
    ArapEnergy arap_;
    double arapWeight_ = 0;  // a
    double tikhonov_ = 0;    // ε
    double diagonal_ = 0;    // the rest pose's bounding-box diagonal
    // L by rows (for the energy) and by columns (the global step's Lᵀ gather).
    Eigen::SparseMatrix<double, Eigen::RowMajor> L_, Lt_;
    std::vector<double> weight_;  // W's row per vertex, at the topology's ring offsets
    std::vector<Vec3> delta0_;    // (L V⁰)_i, zero for an unencoded vertex
    RingFit rings_;
    Eigen::SparseMatrix<double> A_;  // #V by #V, the whole matrix
    // Unknowns: the free vertices when hard (unknownOf_ is −1 for a marker's), every vertex when
    // soft.
    std::vector<int> unknownOf_, vertexOf_;
    SparseCholesky factor_;
    std::vector<Eigen::VectorXd> correction_;  // per marker, empty until first missing
    // The last local step's rotations, and per-iteration scratch.
    std::vector<Mat3> rotation_, arapRotation_, patchRotation_;
    std::vector<Vec3> cornerEdges_;  // the ARAP term's turned rest edges (turnCornerEdges)
    std::vector<Vec3> rotatedDelta_;
    std::unique_ptr<FoldRepair> repair_;
};

}  // namespace boneless
