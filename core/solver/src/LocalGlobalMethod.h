#pragma once

#include <memory>
#include <vector>

#include "LocalGlobal.h"

namespace boneless {

// SolverOptions::Method::LocalGlobal: each frame from its own markers alone, so that its answer
// does not depend on which frames came before it. A coarse level (the mesh simplified to about a
// thousand vertices, markers kept) is solved from the rest pose moved rigidly onto the markers,
// where a local/global iteration carries a rotation across the mesh in a few hops; its rotations,
// given to every input vertex by the coarse vertex it was collapsed into, start the input level's
// few iterations. The coarse level's markers hold their vertices alone: it only finds rotations. On
// a mesh too small for a coarse level the coarse solve runs on the mesh itself.
class LocalGlobalMethod {
  public:
    // rest, topology and encoding must outlive it.
    LocalGlobalMethod(const TriMesh& rest, const MeshTopology& topology,
                      const ShapeEncoding& encoding, const std::vector<MarkerPatch>& markers,
                      bool hard, double softWeight);
    ~LocalGlobalMethod();

    // start: the rest pose moved rigidly onto the markers (#V by 3), by the rotation `rigid`.
    SolveResult solve(const Positions& targets, const std::vector<double>& offsets,
                      const Positions& start, const Mat3& rigid,
                      const std::atomic<bool>* stop = nullptr);
    double energy(const Positions& V, const Positions& targets,
                  const std::vector<double>& offsets) const {
        return inputLevel_->energy(V, targets, offsets);
    }
    // The input level's settings (what a benchmark's converged reference iterates further).
    static LocalGlobalSolver::Settings inputSettings(bool hard, double softWeight);

  private:
    struct Coarse {
        TriMesh mesh;
        std::unique_ptr<MeshTopology> topology;
        std::unique_ptr<ShapeEncoding> encoding;
        std::unique_ptr<LocalGlobalSolver> solver;
        std::vector<int> original;  // coarse vertex -> input vertex
    };
    std::unique_ptr<LocalGlobalSolver> inputLevel_;
    std::unique_ptr<Coarse> coarse_;
    std::vector<int> coarseOf_;  // input vertex -> the coarse vertex whose rotation it starts with
    std::vector<Mat3> rotation_, arapRotation_;  // prolonged, scratch
};

}  // namespace boneless
