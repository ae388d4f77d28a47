#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>

#include "C3dDetail.h"

namespace boneless::c3d_detail {

namespace {

// Frames judged: enough for a take's markers to show which side of the floor they stand on,
// few enough that a streamed take reads them in a blink.
constexpr std::size_t kVerticalFrames = 256;
// The file's axis is reversed only when nearly every marker lies below the origin along it: a
// lab's origin sits on its floor, and an origin at hip height leaves half the markers above.
constexpr double kBelowShare = 0.9;

// The axis POINT:Y_SCREEN names ("+X" … "-Z", any case, spaces around), the axis the C3D format
// says points up on screen.
std::optional<Eigen::Vector3d> screenUp(const C3dParameters& parameters) {
    const C3dParameter* screen = parameters.find("POINT", "Y_SCREEN");
    if (!screen) return std::nullopt;
    std::string axis;
    for (char c : screen->string())
        if (!std::isspace(static_cast<unsigned char>(c))) axis += c;
    if (axis.size() != 2 || (axis[0] != '+' && axis[0] != '-')) return std::nullopt;
    const int k = std::toupper(static_cast<unsigned char>(axis[1])) - 'X';
    if (k < 0 || k > 2) return std::nullopt;
    return (axis[0] == '-' ? -1.0 : 1.0) * Eigen::Vector3d::Unit(k);
}

std::string axisText(const Eigen::Vector3d& a) {
    int k = 0;
    a.cwiseAbs().maxCoeff(&k);
    return std::string(a[k] < 0 ? "-" : "+") + char('X' + k);
}

}  // namespace

void setVertical(C3dTake& take, std::size_t frames,
                 const std::function<C3dSamples(std::size_t frame)>& frameAt) {
    const std::optional<Eigen::Vector3d> claimed = screenUp(take.parameters);
    const Eigen::Vector3d up = claimed.value_or(Eigen::Vector3d::UnitZ());
    take.vertical = up;
    const std::vector<std::size_t> markers = take.markerIndices();
    std::size_t above = 0, below = 0;
    const std::size_t judged = std::min(frames, kVerticalFrames);
    for (std::size_t i = 0; i < judged; ++i) {
        const C3dSamples frame = frameAt(i * frames / judged);
        for (std::size_t k : markers)
            if (const auto p = frame.position(0, k)) {
                const double height = p->dot(up);
                above += height > 0;
                below += height < 0;
            }
    }
    if (below == 0 || double(below) < kBelowShare * double(above + below)) return;
    take.vertical = -up;
    char share[16];
    std::snprintf(share, sizeof share, "%.0f%%", 100.0 * double(below) / double(above + below));
    take.warnings.push_back(
        (claimed ? "POINT:Y_SCREEN says " + axisText(up) + " points up"
                 : "the file does not say which axis points up (POINT:Y_SCREEN), and +Z would") +
        ", but " + share + " of the markers lie below the origin along it: taking " +
        axisText(-up) + " for the take's up");
}

}  // namespace boneless::c3d_detail
