#include "CameraFollow.h"

#include <vtkCamera.h>
#include <vtkMatrix4x4.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>

#include <QScopeGuard>
#include <algorithm>
#include <utility>

namespace boneless::ui {
namespace {

// Per frame, the share of the way to the centroid the camera moves while smoothing: enough to
// keep up with a run at 30 Hz, little enough to iron out a stride's sway.
constexpr double kSmoothing = 0.3;
// The share of the viewport's width and height kept clear at each edge when the whole mesh fits.
constexpr double kEdge = 0.03;

void translateCamera(vtkRenderer* renderer, const Eigen::Vector3d& d) {
    vtkCamera* camera = renderer->GetActiveCamera();
    double p[3], f[3];
    camera->GetPosition(p);
    camera->GetFocalPoint(f);
    camera->SetPosition(p[0] + d.x(), p[1] + d.y(), p[2] + d.z());
    camera->SetFocalPoint(f[0] + d.x(), f[1] + d.y(), f[2] + d.z());
}

Eigen::Vector3d displayOf(vtkRenderer* renderer, const Eigen::Vector3d& p) {
    renderer->SetWorldPoint(p.x(), p.y(), p.z(), 1.0);
    renderer->WorldToDisplay();
    double d[3];
    renderer->GetDisplayPoint(d);
    return {d[0], d[1], d[2]};
}

Eigen::Vector3d worldOf(vtkRenderer* renderer, const Eigen::Vector3d& d) {
    renderer->SetDisplayPoint(d.x(), d.y(), d.z());
    renderer->DisplayToWorld();
    double w[4];
    renderer->GetWorldPoint(w);
    return Eigen::Vector3d(w[0], w[1], w[2]) / (w[3] != 0 ? w[3] : 1.0);
}

// The mesh's extent on screen, in display pixels: lowest and highest x and y over its vertices in
// front of the camera (none: lo > hi).
std::pair<Eigen::Vector2d, Eigen::Vector2d> screenExtent(vtkRenderer* renderer,
                                                         const Positions& V) {
    vtkMatrix4x4* m = renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
        renderer->GetTiledAspectRatio(), -1, 1);
    Eigen::Matrix4d P;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) P(r, c) = m->GetElement(r, c);
    const int* size = renderer->GetSize();
    const int* origin = renderer->GetOrigin();
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for (int v = 0; v < V.rows(); ++v) {
        const Eigen::Vector4d q = P * Eigen::Vector4d(V(v, 0), V(v, 1), V(v, 2), 1.0);
        if (q.w() <= 0) continue;
        const Eigen::Vector2d d(origin[0] + 0.5 * (q.x() / q.w() + 1) * size[0],
                                origin[1] + 0.5 * (q.y() / q.w() + 1) * size[1]);
        lo = lo.cwiseMin(d);
        hi = hi.cwiseMax(d);
    }
    return {lo, hi};
}

}  // namespace

CameraFollow::Placement CameraFollow::cameraOf(vtkRenderer* renderer) {
    double p[3], f[3];
    renderer->GetActiveCamera()->GetPosition(p);
    renderer->GetActiveCamera()->GetFocalPoint(f);
    Placement out;
    out << p[0], p[1], p[2], f[0], f[1], f[2];
    return out;
}

Eigen::Vector3d centroid(const Positions& V) {
    if (V.rows() == 0) return Eigen::Vector3d::Zero();
    return V.colwise().mean().transpose();
}

void CameraFollow::setEnabled(bool enabled) {
    enabled_ = enabled;
    tracked_.reset();
}

void CameraFollow::restart(const Positions& V) {
    tracked_ = V.rows() > 0 ? std::optional(centroid(V)) : std::nullopt;
    userFramed_ = false;
}

void CameraFollow::follow(vtkRenderer* renderer, const Positions& V, const Eigen::Vector3d& up) {
    if (!enabled_ || V.rows() == 0 || !V.allFinite()) return;
    const Eigen::Vector3d c = centroid(V);
    if (!tracked_) {
        tracked_ = c;
        return;
    }
    const Eigen::Vector3d u = up.normalized();
    const int* size =
        renderer->GetRenderWindow() ? renderer->GetRenderWindow()->GetSize() : nullptr;
    const bool sized = size && size[0] > 1 && size[1] > 1;
    const double hx = sized ? 0.5 * size[0] : 0, hy = sized ? 0.5 * size[1] : 0;
    // Where the inner box would have a display point be.
    auto boxed = [&](const Eigen::Vector3d& d) {
        return Eigen::Vector3d(std::clamp(d.x(), hx - kInnerBox * hx, hx + kInnerBox * hx),
                               std::clamp(d.y(), hy - kInnerBox * hy, hy + kInnerBox * hy), d.z());
    };
    if (sized) renderer->ResetCameraClippingRange();
    // Paused, the camera is the user's. Moved by them (not by following) so that the last frame's
    // middle is off the inner box (zoomed onto a marker, panned to look at a hand), it stays:
    // keeping the body on screen would take it back to the hips at each step.
    if (playing_) {
        userFramed_ = false;
    } else if (sized && cameraOf(renderer) != left_) {
        const Eigen::Vector3d last = displayOf(renderer, *tracked_);
        userFramed_ = !(last.z() > 0 && last.z() < 1) || !boxed(last).isApprox(last);
    }
    const auto leave = qScopeGuard([&] { left_ = cameraOf(renderer); });
    if (!playing_ && userFramed_) {
        *tracked_ = c;
        return;
    }
    // Paused, a new frame is looked at from where the camera is: scrubbing, reopening a project
    // or mapping keeps the user's view.
    Eigen::Vector3d step = (playing_ ? kSmoothing : 0.0) * (c - *tracked_);
    step -= step.dot(u) * u;  // across the floor only
    *tracked_ = playing_ ? Eigen::Vector3d(*tracked_ + step) : c;
    translateCamera(renderer, step);

    // Energetic frames: whatever the smoothing, the centroid stays in the inner box.
    if (!sized) return;
    renderer->ResetCameraClippingRange();
    const Eigen::Vector3d d = displayOf(renderer, c);
    if (!(d.z() > 0 && d.z() < 1)) return;  // behind the camera: nothing sensible to do
    const Eigen::Vector3d inside = boxed(d);
    if (!inside.isApprox(d)) {
        const Eigen::Vector3d shift = worldOf(renderer, d) - worldOf(renderer, inside);
        translateCamera(renderer, shift);
        *tracked_ += shift - shift.dot(u) * u;
    }

    // A raised leg or a reach: the whole mesh comes on screen, where it fits, along each axis.
    const auto [lo, hi] = screenExtent(renderer, V);
    const int* view = renderer->GetSize();
    const int* origin = renderer->GetOrigin();
    Eigen::Vector2d over = Eigen::Vector2d::Zero();
    for (int a = 0; a < 2; ++a) {
        const double first = origin[a] + kEdge * view[a], last = origin[a] + (1 - kEdge) * view[a];
        if (lo[a] > hi[a] || hi[a] - lo[a] > last - first) continue;
        over[a] = lo[a] < first ? lo[a] - first : hi[a] > last ? hi[a] - last : 0.0;
    }
    if (over.isZero()) return;
    const Eigen::Vector3d at = displayOf(renderer, c);
    Eigen::Vector3d shift =
        worldOf(renderer, at + Eigen::Vector3d(over.x(), over.y(), 0)) - worldOf(renderer, at);
    if (playing_) shift -= shift.dot(u) * u;  // a leap does not bob the picture
    translateCamera(renderer, shift);
    *tracked_ += shift - shift.dot(u) * u;
}

}  // namespace boneless::ui
