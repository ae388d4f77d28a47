#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "boneless/Axis.h"
#include "boneless/RigidFit.h"
#include "boneless/TriMesh.h"

namespace boneless {

struct C3dTake;

// The take's frame chosen to align it with the rest mesh, and the alignment found there.
struct Calibration {
    int frame = -1;  // 0-based frame of the take
    Similarity takeToMesh;
    double residual = 0;     // RMS marker distance after alignment, in mesh units
    int visibleMarkers = 0;  // markers seen at that frame (all of them unless the take is gappy)
    // The map's entries (0-based) the frame does not show, gaps filled as solving fills them: the
    // rest is fitted to the actor without them (calibrate shape), so a limb there keeps the
    // mesh's length in every frame. Solve and batch warn.
    std::vector<int> unseen;
    // `residual` in millimetres, for a take whose unit is takeUnitToMm mm (C3dTake::unitToMm).
    double residualMm(double takeUnitToMm) const {
        return residual / (takeToMesh.scale / takeUnitToMm);  // as sidecars always wrote it
    }
};

// The fewest mapped markers a frame must show to be aligned at: a similarity is fitted from 3.
// The solver refuses a calibration frame that shows fewer, and the app's Calibrate at This Frame.
constexpr int kMinAlignmentMarkers = 3;

// A frame whose pose is far from the rest's (a stride) can align the body turned against its
// markers, as can a wrong mesh up: CMU 85_02 on MakeHuman aligns at 104.6 mm (RMS) at the automatic
// frame 171, at 256.3 mm at frame 300, and at 743.6 mm with the mesh's up given as +z. An alignment
// the user chose (a calibration frame, a mesh up) is much worse than the automatic choice when its
// residual is both this many times that one's and this much more: a few millimetres more on a
// good take are no concern, nor a small share more on a poor one. The app, solve and batch warn.
constexpr double kMuchWorseAlignmentRatio = 1.5;
constexpr double kMuchWorseAlignmentMm = 50.0;
bool alignsMuchWorse(double chosenMm, double automaticMm);

// Among the frames where every given point is visible, the one that is closest to the rest pose
// after its own similarity alignment (docs/algorithm.md §8); when no frame shows them all, among
// the frames that show the most. restPositions: the mapped vertices' rest positions, one row per
// entry of `points`. Throws Error when no frame shows three usable markers.
Calibration calibrate(const C3dTake& take, const std::vector<std::size_t>& points,
                      const Positions& restPositions);

// The same over frames given one at a time by frameAt (K by 3, NaN rows where missing), for a
// take not held in memory; `file` names the take in the error.
Calibration calibrate(int frames, const std::function<Positions(int)>& frameAt,
                      const std::string& file, const Positions& restPositions);

// calibrate's search over one take for several rest positions in turn, as TakeSolver aligns
// three times while the markers' offsets take the mesh's scale: each find() gives what calibrate
// gives, but the take is not read whole for each. The first find reads every frame once (the
// frames' visibility and their fits in one go); a later one reads and fits only the frames an
// earlier residual leaves in the running: a frame's best fit to one rest is within the largest
// distance between the two rests' rows of its best fit to the other. Holds 4 bytes a frame.
class CalibrationSearch {
  public:
    CalibrationSearch(int frames, std::function<Positions(int)> frameAt, std::string file);
    Calibration find(const Positions& restPositions);
    // How many frames have been read (frameAt called) so far, over every find.
    long framesRead() const { return framesRead_; }

  private:
    int frames_;
    std::function<Positions(int)> frameAt_;
    std::string file_;
    long framesRead_ = 0;
    int mostVisible_ = 0;
    std::optional<Positions> previous_;  // the last find's rest
    // Per frame: at most its residual at the last find's rest, or NaN for a frame that is no
    // candidate (fewer markers seen than the most, or no fit).
    std::vector<float> bound_;
    int best_ = -1;  // the last find's frame
};

// Where the view draws the take before three markers are mapped, from conventions alone. The
// take's vertical (C3dTake::vertical) goes to the mesh's up: +Y, else +Z, when that axis is at
// least 0.6 of the mesh's longest (a T-posed body is about as wide as tall), else +X. The actor's
// left (each L… marker's offset from its R… partner, when mostly level) goes to the mesh's left:
// its widest level axis, towards the side that puts its soles' front in front, or by convention +X
// (a mesh facing +Z with Y up, or -Y with Z up), +Y for an X-up mesh. The actor's median height
// goes to the mesh's, and the lowest marker of the frame that shows the most of `points` (`frame`
// of the result) to the mesh's lowest point, centred on it; a take whose lowest markers are far
// above the origin (knees: no foot markers) stands there with the origin's level on the mesh's
// lowest point, its highest markers' height above it going to the mesh's height. Identity when
// no frame shows any.
Calibration roughAlignment(const C3dTake& take, const std::vector<std::size_t>& points,
                           const TriMesh& mesh);

// `free` (a similarity fitted from `take` onto `mesh` rows, #K by 3 each, NaN rows skipped) turned
// so that the take's vertical `takeUp` (C3dTake::vertical) goes exactly to `up` (a signed
// coordinate axis), or when none is given to the one nearest where `free` put it, then turned
// about that axis and moved to
// fit again; the scale is kept. A pose unlike the rest's tilts a free fit, and the exported floor
// with it (a walk on MakeHuman climbed 8°); an actor who never stands tips it over, and only the
// user can say where the mesh's up is. The result is `free` followed by a rigid motion.
Similarity levelled(const Similarity& free, const Positions& take, const Positions& mesh,
                    const Vec3& takeUp, const std::optional<Vec3>& up = std::nullopt);

// The take's positions of `points` at `frame`, NaN rows where missing.
Positions takeFrame(const C3dTake& take, const std::vector<std::size_t>& points, int frame);
// How many rows of such a frame are seen (finite).
int visibleRows(const Positions& P);

}  // namespace boneless
