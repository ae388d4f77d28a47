#pragma once

// The "bend" workload of issue 4 and the meshes of its size sweep.

#include <vector>

#include "boneless/TriMesh.h"

namespace boneless::bench {

struct BendWorkload {
    std::vector<int> markers;  // 50 vertices by Euclidean farthest-point sampling
    std::vector<char> moving;  // per marker: beyond the mid-plane, so it turns
    Eigen::Vector3d centre;    // bounding-box centre
    int longest = 0, second = 1;
    Positions restMarkers;

    static BendWorkload make(const TriMesh& mesh, int markerCount = 50);
    // Frame f of 120: the far markers turned by 60·(1 − cos(2πf/120))/2 degrees.
    Positions targets(int frame) const;
};

// Quadric-error decimation (OpenMesh) down to about `faces` faces.
TriMesh decimate(const TriMesh& mesh, int faces);
// Loop subdivision: each triangle into four, every vertex moved towards the smooth limit.
TriMesh subdivide(const TriMesh& mesh);
// The input brought to about `faces` faces: decimated when larger, subdivided (then decimated)
// when smaller.
TriMesh resizedMesh(const TriMesh& mesh, int faces);

}  // namespace boneless::bench
