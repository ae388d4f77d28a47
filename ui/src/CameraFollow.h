#pragma once

#include <limits>
#include <optional>

#include "boneless/TriMesh.h"

class vtkRenderer;

namespace boneless::ui {

// Keeps a moving mesh on screen. While playing, the camera tracks the mesh's centroid across the
// floor (not up and down, so a walk does not bob the picture), smoothed over frames; paused, it
// stays where the user put it. Either way it moves whenever the centroid would come near the
// viewport's edge, or a part of the mesh would leave the screen while the whole mesh fits on it
// (a raised leg); paused, not when the user put the camera with the centroid out there already
// (zoomed onto a marker). The camera only translates: the user's angle and zoom are kept.
class CameraFollow {
  public:
    void setEnabled(bool enabled);
    bool enabled() const { return enabled_; }
    void setPlaying(bool playing) { playing_ = playing; }
    bool playing() const { return playing_; }
    // A new mesh or a camera fitted afresh: follow from these positions on.
    void restart(const Positions& V);
    // The mesh now has positions V; the renderer's window must have its size.
    void follow(vtkRenderer* renderer, const Positions& V, const Eigen::Vector3d& up);

    // The fraction of the viewport's half-size the centroid may drift from the centre.
    static constexpr double kInnerBox = 0.6;

  private:
    using Placement = Eigen::Matrix<double, 6, 1>;  // the camera's position and focal point
    static Placement cameraOf(vtkRenderer* renderer);

    bool enabled_ = true;
    bool playing_ = false;
    // Where follow() left the camera: moved since, it was the user.
    Placement left_ = Placement::Constant(std::numeric_limits<double>::quiet_NaN());
    // Paused, the user moved the camera off the body's middle: it stays there.
    bool userFramed_ = false;
    std::optional<Eigen::Vector3d> tracked_;  // the smoothed centroid the camera follows
};

Eigen::Vector3d centroid(const Positions& V);

}  // namespace boneless::ui
