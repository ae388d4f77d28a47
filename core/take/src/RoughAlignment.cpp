#include <algorithm>
#include <cmath>
#include <vector>

#include "SuggestionSides.h"
#include "boneless/Alignment.h"
#include "boneless/C3dTake.h"

namespace boneless {

namespace {

// An axis within this share of the mesh's longest is taken for up when it is +Y: a T-posed
// body is about as wide as it is tall.
constexpr double kUpShare = 0.6;
// Frames sampled for the actor's height: enough for a median, cheap on a long take.
constexpr std::size_t kHeightSamples = 200;

std::string nameOf(const C3dPoint& p) {
    return p.name.empty() ? p.label : p.name;
}

}  // namespace

Calibration roughAlignment(const C3dTake& take, const std::vector<std::size_t>& points,
                           const TriMesh& mesh) {
    Calibration c;
    const std::size_t frames = take.frameCount();
    if (frames == 0 || points.empty() || mesh.vertexCount() == 0) return c;
    int best = 0;
    std::vector<double> heights;
    const std::size_t step = std::max<std::size_t>(1, frames / kHeightSamples);
    for (std::size_t f = 0; f < frames; ++f) {
        int seen = 0;
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for (std::size_t p : points)
            if (const auto x = take.samples.position(f, p)) {
                ++seen;
                lo = std::min(lo, x->z());
                hi = std::max(hi, x->z());
            }
        if (seen > best) {
            best = seen;
            c.frame = int(f);
        }
        if (seen > 1 && f % step == 0) heights.push_back(hi - lo);
    }
    if (c.frame < 0) return c;
    c.visibleMarkers = best;

    const Vec3 mlo = mesh.V.colwise().minCoeff().transpose();
    const Vec3 mhi = mesh.V.colwise().maxCoeff().transpose();
    const Vec3 extent = mhi - mlo;
    int up = 1;
    if (extent.y() < kUpShare * extent.maxCoeff()) extent.maxCoeff(&up);
    // A body's left is +X whether its mesh is Y-up (facing +Z) or Z-up (facing -Y, Blender's way).
    const Vec3 meshUp = Vec3::Unit(up), meshLeft = up == 0 ? Vec3::UnitY() : Vec3::UnitX();

    // The actor's left at the frame, level: each L… marker's offset from its R… partner, summed.
    Vec3 left = Vec3::Zero();
    Vec3 centre = Vec3::Zero();
    double floor = HUGE_VAL;
    int counted = 0;
    for (std::size_t p : points) {
        const auto x = take.samples.position(c.frame, p);
        if (!x) continue;
        centre += *x;
        floor = std::min(floor, x->z());
        ++counted;
        const std::string name = nameOf(take.points[p]);
        if (SideCheck::side(name) != 'L') continue;
        const auto partner = take.findPoint(SideCheck::partner(name));
        if (!partner) continue;
        if (const auto y = take.samples.position(c.frame, *partner)) left += *x - *y;
    }
    centre /= counted;
    left.z() = 0;
    if (left.norm() < 1e-9 * (1 + centre.norm())) left = Vec3::UnitX();
    left.normalize();
    const Vec3 takeUp = Vec3::UnitZ();
    Mat3 from, to;
    from << left, takeUp, left.cross(takeUp);
    to << meshLeft, meshUp, meshLeft.cross(meshUp);
    c.takeToMesh.R = to * from.transpose();

    double height = 0;
    if (!heights.empty()) {
        std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
        height = heights[heights.size() / 2];
    }
    c.takeToMesh.scale = height > 0 ? extent[up] / height : 1.0;
    const double s = c.takeToMesh.scale;
    const Vec3 middle = 0.5 * (mlo + mhi);
    c.takeToMesh.t = middle - s * (c.takeToMesh.R * centre) +
                     meshUp * (mlo[up] + s * (centre.z() - floor) - middle[up]);
    return c;
}

}  // namespace boneless
