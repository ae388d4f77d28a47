#pragma once

#include <vector>

#include "boneless/MeshTopology.h"
#include "boneless/Reconstruction.h"

namespace boneless {

// The surface a soft marker holds (docs/markers.md): its point's corners, weighted
// barycentrically (one vertex for a marker on a vertex). Where the marker sits is their weighted
// sum plus its offset along the point's rest normal, turned by the corners' rigid fit (a single
// vertex: its ring's). The pull is a fixed combination of vertices, so the global step's matrix
// stays constant.
struct MarkerPatch {
    int vertex = -1;                   // the point's nearest vertex
    std::vector<int> vertices;         // the point's corners with a weight
    std::vector<double> weights;       // per corner, summing to 1
    Vec3 restCentroid = Vec3::Zero();  // Σ w v⁰
    Vec3 sag = Vec3::Zero();           // rest point − restCentroid
    Vec3 restNormal = Vec3::Zero();    // unit, or zero where the surface has none
    // Whether the corners span a plane, so that a rotation can be fitted to them.
    bool fittable = false;

    // Σ w v over the pose V.
    Vec3 centroid(const Positions& V) const;
    // The rotation that best carries the corners from rest onto V (weighted), or `fallback`
    // when they are too few to fit one.
    Mat3 rotation(const Positions& rest, const Positions& V, const Mat3& fallback) const;
    // Where the marker sits, `offset` off the surface, for the patch rotation R.
    Vec3 point(const Positions& V, const Mat3& R, double offset) const {
        return centroid(V) + R * (sag + offset * restNormal);
    }
};

MarkerPatch makeMarkerPatch(const TriMesh& rest, const ShapeEncoding& encoding,
                            const SurfacePoint& p);
// One patch per vertex, each holding that vertex alone.
std::vector<MarkerPatch> vertexPatches(const TriMesh& rest, const ShapeEncoding& encoding,
                                       const std::vector<int>& vertices);

}  // namespace boneless
