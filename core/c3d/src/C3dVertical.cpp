#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "C3dDetail.h"
#include "boneless/Axis.h"
#include "boneless/Text.h"

namespace boneless::c3d_detail {

namespace {

// Frames judged: enough for a take's markers to show where its floor is, few enough that a
// streamed take reads them in a blink.
constexpr std::size_t kVerticalFrames = 256;
// The file's axis is reversed only when two signs agree that it points down. Nearly every marker
// lies below the origin along it (a lab's origin is on its floor; one at hip height leaves half
// the markers above) ...
constexpr double kBelowShare = 0.9;
// ... and the take's floor is at its top: the frames' highest markers along the axis keep to one
// level (the feet, a body on the ground) far more than their lowest do (a head that crouches,
// hands that reach). An origin above the actor turns only the first; an upper-body capture whose
// head keeps still, only the second.
constexpr double kFloorSteadier = 0.5;
constexpr std::size_t kFloorFrames = 10;  // frames showing 3 markers, for the floor to be judged

// The axis POINT:Y_SCREEN names ("+X" … "-Z", any case, spaces around), the axis the C3D format
// says points up on screen; `unread` is set for a value that names none.
std::optional<Eigen::Vector3d> screenUp(const C3dParameters& parameters, std::string& unread) {
    const C3dParameter* screen = parameters.find("POINT", "Y_SCREEN");
    if (!screen) return std::nullopt;
    std::string axis;
    for (char c : screen->string())
        if (!isAsciiSpace(c)) axis += asciiLower(c);
    const std::optional<Eigen::Vector3d> up = parseAxis(axis);
    if (!up) unread = screen->string();
    return up;
}

// The spread of `v` between its 10th and 90th percentiles.
double spread(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() * 9 / 10] - v[v.size() / 10];
}

}  // namespace

void setVertical(C3dTake& take, std::size_t frames,
                 const std::function<C3dSamples(std::size_t frame)>& frameAt) {
    std::string unread;
    const std::optional<Eigen::Vector3d> claimed = screenUp(take.parameters, unread);
    const Eigen::Vector3d up = claimed.value_or(Eigen::Vector3d::UnitZ());
    take.vertical = up;
    if (!unread.empty())
        take.warnings.push_back("POINT:Y_SCREEN is \"" + unread +
                                "\", which names no axis (+X … -Z): taking +z for the take's up");
    const std::vector<std::size_t> markers = take.markerIndices();
    std::size_t above = 0, below = 0;
    std::vector<double> lowest, highest;  // per frame showing 3 markers, along `up`
    const std::size_t judged = std::min(frames, kVerticalFrames);
    for (std::size_t i = 0; i < judged; ++i) {
        const C3dSamples frame = frameAt(i * frames / judged);
        double lo = INFINITY, hi = -INFINITY;
        int seen = 0;
        for (std::size_t k : markers)
            if (const auto p = frame.position(0, k)) {
                const double height = p->dot(up);
                above += height > 0;
                below += height < 0;
                lo = std::min(lo, height);
                hi = std::max(hi, height);
                ++seen;
            }
        if (seen >= 3) {
            lowest.push_back(lo);
            highest.push_back(hi);
        }
    }
    if (below == 0 || double(below) < kBelowShare * double(above + below)) return;
    if (lowest.size() < kFloorFrames || !(spread(highest) < kFloorSteadier * spread(lowest)))
        return;
    take.vertical = -up;
    char share[16];
    std::snprintf(share, sizeof share, "%.0f%%", 100.0 * double(below) / double(above + below));
    take.warnings.push_back(
        (claimed ? "POINT:Y_SCREEN says " + axisName(up) + " points up"
                 : "the file does not say which axis points up (POINT:Y_SCREEN), and +z would") +
        ", but " + share + " of the markers lie below the origin along it and their floor is " +
        "at its top: taking " + axisName(-up) + " for the take's up");
}

}  // namespace boneless::c3d_detail
