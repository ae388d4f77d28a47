#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "SuggestionSides.h"
#include "boneless/Alignment.h"
#include "boneless/C3dTake.h"

namespace boneless {

namespace {

// Up is +Y, else +Z, when that axis is at least this share of the mesh's longest: a T-posed
// body is about as wide as it is tall.
constexpr double kUpShare = 0.6;
// The L…/R… offsets give the actor's facing only when they are mostly level (not an actor
// lying on its side).
constexpr double kLevelShare = 0.3;
// Frames sampled for the actor's height: enough for a median, cheap on a long take.
constexpr std::size_t kHeightSamples = 200;
// A body's widest level axis runs left to right (shoulders and hips are wider than it is
// deep) when its variance is at least this multiple of the other's; MakeHuman's A-pose gives
// 7.7, a scanned dancer with her arms down 3.5.
constexpr double kWideShare = 1.5;
// The soles (the lowest 3 % of the height) reach further forward than the ankles (5-12 %) by
// at least this share of the height when the mesh has feet (4-8 % on human meshes).
constexpr double kToeShare = 0.01;
// A lab's origin is on its floor (C3dVertical.cpp); a take's lowest markers (median over the
// frames) above it by a share of its highest in this range are no feet (ankles and toes: 2-4 % on
// the shared data's takes) but knees (30 % on CMU 85_02 without its feet), shins or hips: the
// actor stands on the origin's level, not on them. Above the range a prop (a cube, 78 %).
constexpr double kFeetShare = 0.1;
constexpr double kLegShare = 0.6;
// A standing body is about as tall as its widest level extent (a T-pose's arm span) or taller; a
// horse is longer than it is tall.
constexpr double kUprightShare = 0.8;

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

// The mesh's left, level: along its widest level axis, towards the side that puts the toes in
// front. `convention` unless the mesh stands upright (at least kUprightShare as tall as its
// widest level extent), is clearly wider than deep and shows feet.
Vec3 meshLeft(const TriMesh& mesh, int up, const Vec3& convention) {
    const int a = (up + 1) % 3, b = (up + 2) % 3;
    const Vec3 extent = mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff();
    if (extent[up] < kUprightShare * std::max(extent[a], extent[b])) return convention;
    Eigen::MatrixX2d level(mesh.vertexCount(), 2);
    level << mesh.V.col(a), mesh.V.col(b);
    level.rowwise() -= level.colwise().mean();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> spread(level.transpose() * level);
    const Eigen::Vector2d variance = spread.eigenvalues();
    if (variance(1) <= 0 || variance(1) < kWideShare * variance(0)) return convention;
    Vec3 left = Vec3::Zero();
    left[a] = spread.eigenvectors()(0, 1);
    left[b] = spread.eigenvectors()(1, 1);
    // The front is left x up: +Z for left +X and up +Y.
    const Vec3 front = left.cross(Vec3::Unit(up)), lowest = mesh.V.colwise().minCoeff().transpose();
    const double height = mesh.V.col(up).maxCoeff() - lowest[up];
    double sole = 0, ankle = 0;
    int soles = 0, ankles = 0;
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3 x = mesh.V.row(v).transpose();
        const double h = (x[up] - lowest[up]) / height;
        if (h < 0.03)
            sole += front.dot(x), ++soles;
        else if (h >= 0.05 && h < 0.12)
            ankle += front.dot(x), ++ankles;
    }
    // Only a body with feet is read this way: a horse is widest along its spine, and a mesh
    // without feet gives no front to sign the axis by.
    const double toes = soles && ankles ? (sole / soles - ankle / ankles) / height : 0;
    if (std::abs(toes) < kToeShare) return convention;
    return toes > 0 ? left : Vec3(-left);
}

}  // namespace

Calibration roughAlignment(const C3dTake& take, const std::vector<std::size_t>& points,
                           const TriMesh& mesh) {
    Calibration c;
    const std::size_t frames = take.frameCount();
    if (frames == 0 || points.empty() || mesh.vertexCount() == 0) return c;
    const Vec3 takeUp = take.vertical;
    int best = 0;
    std::vector<double> heights, spans, bottoms, tops;
    const std::size_t step = std::max<std::size_t>(1, frames / kHeightSamples);
    for (std::size_t f = 0; f < frames; ++f) {
        int seen = 0;
        Vec3 lo = Vec3::Constant(HUGE_VAL), hi = -lo;
        for (std::size_t p : points)
            if (const auto x = take.samples.position(f, p)) {
                ++seen;
                lo = lo.cwiseMin(*x);
                hi = hi.cwiseMax(*x);
            }
        if (seen > best) {
            best = seen;
            c.frame = int(f);
        }
        if (seen > 1 && f % step == 0) {
            heights.push_back(std::abs((hi - lo).dot(takeUp)));
            spans.push_back((hi - lo).norm());
            // takeUp is a signed axis: lo and hi along it are the frame's lowest and highest.
            bottoms.push_back(std::min(lo.dot(takeUp), hi.dot(takeUp)));
            tops.push_back(std::max(lo.dot(takeUp), hi.dot(takeUp)));
        }
    }
    if (c.frame < 0) return c;
    c.visibleMarkers = best;

    const Vec3 mlo = mesh.V.colwise().minCoeff().transpose();
    const Vec3 mhi = mesh.V.colwise().maxCoeff().transpose();
    const Vec3 extent = mhi - mlo;
    int up = 0;
    if (extent.y() >= kUpShare * extent.maxCoeff())
        up = 1;
    else if (extent.z() >= kUpShare * extent.maxCoeff())
        up = 2;
    // By convention a body's left is +X, whether its mesh is Y-up (facing +Z) or Z-up (facing
    // -Y, Blender's way); a scan may face anywhere, and its shape says where.
    const Vec3 meshUp = Vec3::Unit(up);
    const Vec3 meshLeftAxis = meshLeft(mesh, up, up == 0 ? Vec3::UnitY() : Vec3::UnitX());

    // The actor's left at the frame, level: each L… marker's offset from its R… partner, summed.
    Vec3 left = Vec3::Zero();
    Vec3 centre = Vec3::Zero();
    double floor = HUGE_VAL;
    int counted = 0;
    for (std::size_t p : points) {
        const auto x = take.samples.position(c.frame, p);
        if (!x) continue;
        centre += *x;
        floor = std::min(floor, x->dot(takeUp));
        ++counted;
        const std::string& label = take.points[p].label;
        if (SideCheck::side(label) != 'L') continue;
        const auto partner = take.findPoint(SideCheck::partner(label));
        if (!partner) continue;
        if (const auto y = take.samples.position(c.frame, *partner)) left += *x - *y;
    }
    centre /= counted;
    const double offset = left.norm();
    left -= left.dot(takeUp) * takeUp;
    // Without sided names: +X, or +Y for a take whose vertical is X.
    if (offset == 0 || left.norm() < kLevelShare * offset)
        left = takeUp.x() != 0 ? Vec3::UnitY() : Vec3::UnitX();
    left.normalize();
    Mat3 from, to;
    from << left, takeUp, left.cross(takeUp);
    to << meshLeftAxis, meshUp, meshLeftAxis.cross(meshUp);
    c.takeToMesh.R = to * from.transpose();

    // The actor's height to the mesh's; markers all at one height give their span to the mesh's
    // size instead, and a take that never shows two markers at once scale 1. Without foot
    // markers the height is the highest markers' above the lab's floor, which the feet stand on.
    const double bottom = median(bottoms), top = median(tops);
    const bool feetUnmarked = bottom > kFeetShare * top && bottom < kLegShare * top;
    if (feetUnmarked) floor = 0;
    const double height = feetUnmarked ? top : median(heights), span = median(spans);
    c.takeToMesh.scale = height > 0 ? extent[up] / height : span > 0 ? extent.norm() / span : 1.0;
    const double s = c.takeToMesh.scale;
    const Vec3 middle = 0.5 * (mlo + mhi);
    c.takeToMesh.t = middle - s * (c.takeToMesh.R * centre) +
                     meshUp * (mlo[up] + s * (centre.dot(takeUp) - floor) - middle[up]);
    return c;
}

}  // namespace boneless
