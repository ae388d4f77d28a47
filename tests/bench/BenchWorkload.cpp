#include "BenchWorkload.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "boneless/Sampling.h"

namespace boneless::bench {

BendWorkload BendWorkload::make(const TriMesh& mesh, int markerCount) {
    BendWorkload w;
    const Eigen::Vector3d lo = mesh.V.colwise().minCoeff().transpose();
    const Eigen::Vector3d hi = mesh.V.colwise().maxCoeff().transpose();
    const Eigen::Vector3d extent = hi - lo;
    std::array<int, 3> axes{0, 1, 2};
    std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return extent[a] > extent[b]; });
    w.longest = axes[0];
    w.second = axes[1];
    w.centre = 0.5 * (lo + hi);
    // Seed: the vertex with the largest coordinate along the longest axis (lowest id on ties).
    int seed = 0;
    for (int v = 1; v < mesh.vertexCount(); ++v)
        if (mesh.V(v, w.longest) > mesh.V(seed, w.longest)) seed = v;
    w.markers = euclideanFarthestPoints(mesh.V, markerCount, seed);
    w.restMarkers.resize(w.markers.size(), 3);
    w.moving.resize(w.markers.size());
    for (size_t k = 0; k < w.markers.size(); ++k) {
        w.restMarkers.row(k) = mesh.V.row(w.markers[k]);
        w.moving[k] = mesh.V(w.markers[k], w.longest) > w.centre[w.longest];
    }
    return w;
}

Positions BendWorkload::targets(int frame) const {
    const double degrees = 60.0 * (1.0 - std::cos(2.0 * M_PI * frame / 120.0)) / 2.0;
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d::Unit(second)).matrix();
    Positions T = restMarkers;
    for (int k = 0; k < static_cast<int>(T.rows()); ++k)
        if (moving[k])
            T.row(k) = (centre + R * (restMarkers.row(k).transpose() - centre)).transpose();
    return T;
}

namespace {

using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

OMesh toOpenMesh(const TriMesh& mesh) {
    OMesh om;
    std::vector<OMesh::VertexHandle> vh(mesh.vertexCount());
    for (int v = 0; v < mesh.vertexCount(); ++v)
        vh[v] = om.add_vertex(OMesh::Point(mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2)));
    for (int f = 0; f < mesh.faceCount(); ++f)
        om.add_face(vh[mesh.F(f, 0)], vh[mesh.F(f, 1)], vh[mesh.F(f, 2)]);
    return om;
}

TriMesh fromOpenMesh(OMesh& om) {
    om.garbage_collection();
    TriMesh mesh;
    mesh.V.resize(om.n_vertices(), 3);
    for (auto v : om.vertices()) {
        const auto p = om.point(v);
        mesh.V.row(v.idx()) << p[0], p[1], p[2];
    }
    mesh.F.resize(om.n_faces(), 3);
    for (auto f : om.faces()) {
        int c = 0;
        for (auto v : om.fv_range(f)) mesh.F(f.idx(), c++) = v.idx();
    }
    return mesh;
}

}  // namespace

TriMesh decimate(const TriMesh& mesh, int faces) {
    if (mesh.faceCount() <= faces) return mesh;
    OMesh om = toOpenMesh(mesh);
    OpenMesh::Decimater::DecimaterT<OMesh> decimater(om);
    OpenMesh::Decimater::ModQuadricT<OMesh>::Handle quadric;
    decimater.add(quadric);
    decimater.initialize();
    decimater.decimate_to_faces(0, static_cast<size_t>(faces));
    return fromOpenMesh(om);
}

TriMesh subdivide(const TriMesh& mesh) {
    // Loop subdivision, a smooth surface as a finer scan or sculpt would give. Midpoint
    // subdivision made flat four-triangle patches, which quadric decimation then collapsed into
    // rings that are not star-shaped (the multiresolution hierarchy stopped at 9,500 of 100,000
    // vertices on the 200K-face mesh so made).
    OMesh om = toOpenMesh(mesh);
    OpenMesh::Subdivider::Uniform::LoopT<OMesh> loop;
    loop.attach(om);
    loop(1);
    loop.detach();
    return fromOpenMesh(om);
}

TriMesh resizedMesh(const TriMesh& mesh, int faces) {
    // Within 2 % counts as the size asked for: decimating a mesh that is nearly there only
    // spends time.
    if (std::abs(mesh.faceCount() - faces) <= faces / 50) return mesh;
    TriMesh m = mesh;
    while (m.faceCount() < faces) m = subdivide(m);
    return decimate(m, faces);
}

}  // namespace boneless::bench
