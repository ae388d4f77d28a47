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

    // 'L', 'R' or 0: the side a label names when `partner` (L↔R swapped) is also a label. A
    // subject prefix is kept: "B:LWRA"'s partner is "B:RWRA".
    static char side(const std::string& label);
    static std::string partner(const std::string& label);

  private:
    bool known_ = false;
    Vec3 left_ = Vec3::Zero();  // unit, from the mid-plane towards the left
    double mid_ = 0;            // the mid-plane's offset along left_
    double margin_ = 0;         // mesh units

    friend class MirrorPlane;
};

// The rest mesh's plane of left-right symmetry, when it has one: started from the picks' pairs
// (as SideCheck) and fitted to the mesh, so that a marker's partner can be looked for at the
// mirror image of its vertex. A mesh whose reflection does not land on itself (a scan in an
// uneven pose) has none.
class MirrorPlane {
  public:
    MirrorPlane(const TriMesh& rest, const SideCheck& sides);
    bool known() const { return known_; }
    Vec3 reflect(const Vec3& p) const { return p - 2 * (normal_.dot(p) - offset_) * normal_; }

  private:
    bool known_ = false;
    Vec3 normal_ = Vec3::Zero();
    double offset_ = 0;
};

}  // namespace boneless
