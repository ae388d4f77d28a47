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

double median(std::vector<double> values) {
    if (values.empty()) return 0;
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

}  // namespace

Calibration roughAlignment(const C3dTake& take, const std::vector<std::size_t>& points,
                           const TriMesh& mesh) {
    Calibration c;
    const std::size_t frames = take.frameCount();
    if (frames == 0 || points.empty() || mesh.vertexCount() == 0) return c;
    int best = 0;
    std::vector<double> heights, spans;
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
            heights.push_back(hi.z() - lo.z());
            spans.push_back((hi - lo).norm());
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
        const std::string name = markerName(take.points[p]);
        if (SideCheck::side(name) != 'L') continue;
        const auto partner = take.findPoint(SideCheck::partner(name));
        if (!partner) continue;
        if (const auto y = take.samples.position(c.frame, *partner)) left += *x - *y;
    }
    centre /= counted;
    const double offset = left.norm();
    left.z() = 0;
    if (offset == 0 || left.norm() < kLevelShare * offset) left = Vec3::UnitX();
    left.normalize();
    const Vec3 takeUp = Vec3::UnitZ();
    Mat3 from, to;
    from << left, takeUp, left.cross(takeUp);
    to << meshLeft, meshUp, meshLeft.cross(meshUp);
    c.takeToMesh.R = to * from.transpose();

    // The actor's height to the mesh's; markers all at one height give their span to the mesh's
    // size instead, and a take that never shows two markers at once scale 1.
    const double height = median(heights), span = median(spans);
    c.takeToMesh.scale = height > 0 ? extent[up] / height : span > 0 ? extent.norm() / span : 1.0;
    const double s = c.takeToMesh.scale;
    const Vec3 middle = 0.5 * (mlo + mhi);
    c.takeToMesh.t = middle - s * (c.takeToMesh.R * centre) +
                     meshUp * (mlo[up] + s * (centre.z() - floor) - middle[up]);
    return c;
}

}  // namespace boneless
