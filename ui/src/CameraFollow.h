#pragma once

#include <optional>

#include "boneless/TriMesh.h"

class vtkRenderer;

namespace boneless::ui {

// Keeps a moving mesh on screen. While playing, the camera tracks the mesh's centroid across the
// floor (not up and down, so a walk does not bob the picture), smoothed over frames; paused, it
// stays where the user put it. Either way it moves whenever the centroid would come near the
// viewport's edge, or a part of the mesh would leave the screen while the whole mesh fits on it
// (a raised leg). The camera only translates: the user's angle and zoom are kept.
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
    bool enabled_ = true;
    bool playing_ = false;
    std::optional<Eigen::Vector3d> tracked_;  // the smoothed centroid the camera follows
};

Eigen::Vector3d centroid(const Positions& V);

}  // namespace boneless::ui
