#pragma once

// One motion-capture take read from (or to be written to) a C3D file.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "boneless/C3dNumbers.h"
#include "boneless/C3dParameters.h"

namespace boneless {

enum class C3dStorage { Int16, Float };

// How the file stores text (labels, descriptions, units). The take always holds UTF-8.
enum class C3dTextEncoding { Utf8, Latin1 };

enum class C3dPointKind { Marker, Angle, Force, Moment, Power, Scalar, Virtual };

const char* toString(C3dProcessor processor);  // "intel", "dec", "mips"
const char* toString(C3dStorage storage);      // "int16", "float"
const char* toString(C3dPointKind kind);       // "marker", "angle", ...

// A run of frames [first, first + frames) in which a point is missing.
struct C3dGap {
    std::size_t first = 0, frames = 0;
};

// Frames x points samples. A missing sample has no position: position() returns nullopt and the
// coordinate block holds NaN there, so forgetting to check validity poisons results instead of
// silently using a stale or (0,0,0) position.
//
// A take read whole is held at about its file's size (docs/c3d.md, "A take in memory"): the
// coordinates as float (what a C3D file stores; Double keeps what a filter computes), NaN as the
// mark of a missing sample, and residuals only once one is not 0. Copies share the block until
// one of them is changed, so the app's solver and export hold the take without a second copy.
class C3dSamples {
  public:
    enum class Precision { Float, Double };

    C3dSamples() = default;
    C3dSamples(std::size_t frames, std::size_t points,
               Precision precision = Precision::Float);  // all missing

    std::size_t frames() const { return frames_; }
    std::size_t points() const { return points_; }
    Precision precision() const {
        return block_ && !block_->wide.empty() ? Precision::Double : Precision::Float;
    }

    bool valid(std::size_t frame, std::size_t point) const;
    std::optional<Eigen::Vector3d> position(std::size_t frame, std::size_t point) const;
    // Residual in the file's units (>= 0) for a valid sample, -1 for a missing one.
    float residual(std::size_t frame, std::size_t point) const;
    std::size_t missingFrames(std::size_t point) const;
    std::size_t missingCount() const;
    // Per point, its gaps in frame order (inspect's table, the app's timeline), in one pass over
    // the frames: a pass per point read a 25-minute take from memory once for each.
    std::vector<std::vector<C3dGap>> gaps() const;
    // The same positions, missing where the other's are missing (a take read again, say).
    bool samePositions(const C3dSamples& other) const;

    // A non-finite position (also one past the float range in a Float block) is stored as
    // missing: it is not a position either.
    void set(std::size_t frame, std::size_t point, double x, double y, double z,
             float residual = 0.0f) {
        const std::size_t i = frame * points_ + point;
        Block& b = own();
        if (b.wide.empty()) {
            const float fx = static_cast<float>(x), fy = static_cast<float>(y),
                        fz = static_cast<float>(z);
            if (!(std::isfinite(fx) && std::isfinite(fy) && std::isfinite(fz)))
                return setMissingAt(i);
            b.xyz[3 * i] = fx;
            b.xyz[3 * i + 1] = fy;
            b.xyz[3 * i + 2] = fz;
        } else {
            if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) return setMissingAt(i);
            b.wide[3 * i] = x;
            b.wide[3 * i + 1] = y;
            b.wide[3 * i + 2] = z;
        }
        setResidualAt(i, residual < 0.0f ? 0.0f : residual);
    }
    void setMissing(std::size_t frame, std::size_t point) { setMissingAt(frame * points_ + point); }

    // Whether the two hold one block (a copy not changed since): the same samples, unread.
    bool sharesData(const C3dSamples& other) const { return block_ == other.block_; }
    // Bytes the samples hold (their block, whether shared or not).
    std::size_t bytes() const;

  private:
    struct Block {
        std::vector<float> xyz;       // Float: row-major frame, point, xyz; NaN where missing
        std::vector<double> wide;     // Double: the same
        std::vector<float> residual;  // empty while every valid sample's is 0
    };
    // The block, copied first when another C3dSamples shares it.
    Block& own() {
        if (block_.use_count() > 1) block_ = std::make_shared<Block>(*block_);
        return *block_;
    }
    bool validAt(std::size_t i) const {
        return block_->wide.empty() ? !std::isnan(block_->xyz[3 * i])
                                    : !std::isnan(block_->wide[3 * i]);
    }
    void setResidualAt(std::size_t i, float residual) {
        Block& b = *block_;  // owned: set() called own()
        if (b.residual.empty()) {
            if (residual == 0.0f) return;
            b.residual.assign(frames_ * points_, 0.0f);
        }
        b.residual[i] = residual;
    }
    Eigen::Vector3d at(std::size_t i) const {  // a valid sample's position
        const Block& b = *block_;
        if (b.wide.empty()) return {b.xyz[3 * i], b.xyz[3 * i + 1], b.xyz[3 * i + 2]};
        return {b.wide[3 * i], b.wide[3 * i + 1], b.wide[3 * i + 2]};
    }
    void setMissingAt(std::size_t i);
    void check(std::size_t frame, std::size_t point) const;

    std::size_t frames_ = 0, points_ = 0;
    std::shared_ptr<Block> block_;
};

struct C3dPoint {
    std::string label;        // as stored, e.g. "male:LFHD"
    std::string subject;      // "male", empty without a prefix
    std::string name;         // "LFHD"
    std::string description;  // from POINT:DESCRIPTIONS
    C3dPointKind kind = C3dPointKind::Marker;
};

// Whether a take's markers span what a body does in the units the file states (docs/c3d.md, "A
// take's units"): CMU 85_02 with its coordinates in metres under POINT:UNITS "mm" spans 1.8 mm.
struct MarkerSpan {
    // The median over frames showing 3 markers of their bounding box's longest side, in mm as
    // the take's units say; 0 when no frame shows 3.
    double mm = 0.0;
    // The same median in the take's coordinates as stored: judged again in other units
    // (setTakeUnits) without reading the frames again.
    double stored = 0.0;
    // When that span is no body's (outside 50 mm to 50 m): "its markers span 1.8 mm although
    // POINT:UNITS says mm: are they in metres (1.8 m)? A body spans 0.3 to 3 m", and the units
    // that make it one's ("m"); both "" otherwise.
    std::string doubt, likelyUnits;
};

struct C3dTake {
    std::string file;
    C3dProcessor processor = C3dProcessor::Intel;
    C3dStorage storage = C3dStorage::Float;
    double pointScale = -1.0;  // POINT:SCALE as stored (sign gives the storage)
    double rate = 0.0;         // frames per second; 0 when the file gives none (hasFrameRate)
    std::string units = "mm";  // POINT:UNITS as stored, or as setTakeUnits set them
    double unitToMm = 1.0;     // multiply coordinates by this to get millimetres
    // What set units when not the file ("--take-units"), for messages; "" for POINT:UNITS.
    std::string unitsFrom;
    int firstFrameWord = 1;  // header words 4 and 5 (1-based, 16-bit)
    int lastFrameWord = 0;
    std::int64_t firstFrame = 1;  // first frame number, from TRIAL when the header cannot hold it
    int analogChannels = 0;
    double analogRate = 0.0;
    int analogSamplesPerFrame = 0;
    // Latin-1 when some label, description or unit in the file was not UTF-8; the writer encodes
    // the take's text this way again, so a file read and written keeps its bytes.
    C3dTextEncoding textEncoding = C3dTextEncoding::Utf8;

    std::vector<C3dPoint> points;
    C3dSamples samples;
    C3dParameters parameters;
    std::vector<std::string> warnings;  // header/parameter disagreements, truncation, ...
    // The take's up, a unit coordinate axis the readers set (docs/c3d.md, "The take's vertical"):
    // the one POINT:Y_SCREEN names, else +Z, reversed when nearly all markers lie below the
    // origin along it. The alignment's levelling, the view's floor, the sidecar and the glb ask it.
    Eigen::Vector3d vertical = Eigen::Vector3d::UnitZ();
    // The readers measure it over the frames they judge the vertical by, and a doubt is also among
    // the warnings.
    MarkerSpan markerSpan;

    std::size_t frameCount() const { return samples.frames(); }
    // Whether the take says how long a frame is: the reader reports 0 for a rate that is 0, not
    // a number or negative in both POINT:RATE and the header, with a warning.
    bool hasFrameRate() const { return std::isfinite(rate) && rate > 0; }
    // The rate as messages give it: "120 Hz", "0 Hz", "not a number".
    std::string rateText() const;
    // The points `label` names (case-insensitive, surrounding spaces ignored): those whose full
    // label equals it, else every one whose name without the subject prefix equals its name and
    // whose subject is the label's, or either has none ("other:T10" finds T10, never
    // walker:T10). More than one means two subjects wear the marker, and the label must say
    // which, or that the take holds two points with one label (sharedLabels), which no label can
    // tell apart.
    std::vector<std::size_t> pointsNamed(std::string_view label) const;
    // The subject prefixes the points' labels carry ("walker"), each once, in the order of their
    // first points.
    std::vector<std::string> subjects() const;
    // The groups of points whose full labels are one label as pointsNamed compares them, each in
    // ascending order, in the order of their first points.
    std::vector<std::vector<std::size_t>> sharedLabels() const;
    // One such group as messages give it: "points 1 and 3 are both labelled Male:LFWT" (indices
    // 0-based, as inspect lists them; the first few of a long list and how many more).
    std::string sharedLabelText(const std::vector<std::size_t>& group) const;
    // The point `label` names, when exactly one does.
    std::optional<std::size_t> findPoint(std::string_view label) const;
    // The shortest label that finds `point`: its name without the subject ("LFWT" for
    // "Male:LFWT") unless another subject wears that name too.
    std::string shortLabel(std::size_t point) const;
    std::vector<std::size_t> markerIndices() const;
};

// Splits "subject:NAME" at the first colon.
void splitC3dLabel(std::string_view label, std::string& subject, std::string& name);

}  // namespace boneless
