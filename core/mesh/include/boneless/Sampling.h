#pragma once

#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// K vertices by farthest-point sampling along the mesh's edges (Dijkstra on edge lengths): the
// first is `seed`, each next one the vertex farthest from those already picked, ties to the lower
// id. Vertices unreachable from the picked ones count as infinitely far, so every component gets
// markers before any gets a second. K is capped at the vertex count.
std::vector<int> geodesicFarthestPoints(const TriMesh& mesh, int K, int seed = 0);

// The same with straight-line distances (what deformation benchmarks use to pick handles).
std::vector<int> euclideanFarthestPoints(const Positions& V, int K, int seed);

}  // namespace boneless
