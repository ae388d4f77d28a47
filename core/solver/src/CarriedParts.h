#pragma once

#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// A mesh split into what the solver solves (the connected components that hold a marker, and any
// isolated vertex) and the components that hold none (eyes, teeth, a garment, joint helpers).
// Solved together, a part without a marker is held only by the Tikhonov pull towards its start
// and changes the ARAP term's scale for the whole mesh; instead each is carried rigidly with the
// nearest part of the solved mesh: per pose, the best rigid motion (Kabsch) of its anchors, the
// solved vertices nearest to it at rest, as many as it has vertices and at least kMinAnchors.
class CarriedParts {
  public:
    static constexpr int kMinAnchors = 32;

    // markerVertices: each marker's vertex. Nothing is carried (empty()) when every component
    // holds a marker, or none does.
    CarriedParts(const TriMesh& rest, const std::vector<int>& markerVertices);

    bool empty() const { return parts_.empty(); }
    int count() const { return static_cast<int>(parts_.size()); }
    // The solved components: the rest's vertices and faces in their order, renumbered.
    const TriMesh& solvedMesh() const { return solved_; }
    int solvedVertex(int v) const { return solvedOf_[v]; }
    int solvedFace(int f) const { return solvedFaceOf_[f]; }
    // The solved vertices' rows of V (#V by 3).
    Positions solvedRows(const Positions& V) const;
    // The whole mesh's pose for a pose of the solved mesh: its rows in place, every carried part
    // moved by its anchors' rigid motion from rest.
    Positions whole(const Positions& solved) const;

  private:
    struct Part {
        std::vector<int> vertices;  // of the rest
        std::vector<int> anchors;   // of the solved mesh
        Positions anchorRest;
    };
    Positions rest_;
    TriMesh solved_;
    std::vector<int> solvedOf_, vertexOf_;  // rest <-> solved vertex ids, −1 where none
    std::vector<int> solvedFaceOf_;         // rest face -> solved face, −1 where carried
    std::vector<Part> parts_;
};

// Each vertex's connected component over the faces (isolated vertices: −1), numbered from 0 in
// the order of their first vertex; returns the count.
int connectedComponents(const TriMesh& mesh, std::vector<int>& componentOf);

}  // namespace boneless
