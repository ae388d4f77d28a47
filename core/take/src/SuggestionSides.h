#pragma once

#include <string>

#include "boneless/Correspondence.h"
#include "boneless/TriMesh.h"

namespace boneless {

// Left and right as the picks name them: a marker named L… whose partner R… exists is on the
// left. The picks that come in such pairs (LWRA and RWRA) give the mesh's left direction and
// its mid-plane; a suggestion named for one side that lands on the other needs review.
class SideCheck {
  public:
    SideCheck(const TriMesh& rest, const Correspondence& picks);
    // Empty when the label has no side, no pair of picks shows the sides, or the point is on
    // the label's side (or within the margin of the mid-plane); otherwise why not.
    std::string mismatch(const std::string& label, const Vec3& restPoint) const;

    // 'L', 'R' or 0: the side a label names when `partner` (L↔R swapped) is also a label.
    static char side(const std::string& label);
    static std::string partner(const std::string& label);

  private:
    bool known_ = false;
    Vec3 left_ = Vec3::Zero();  // unit, from the mid-plane towards the left
    double mid_ = 0;            // the mid-plane's offset along left_
    double margin_ = 0;         // mesh units
};

}  // namespace boneless
