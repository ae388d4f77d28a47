#pragma once

#include <functional>
#include <string>
#include <vector>

#include "boneless/MeshSequence.h"
#include "boneless/Reconstruction.h"

namespace boneless {

// Drives marker vertices of a ground-truth sequence with their true positions, reconstructs every
// frame (Boneless as a take is solved, each frame from its own markers; ARAP as it is used, each
// frame from the previous one's answer, the chain starting at the rest pose at frame 0) and
// measures the result against the truth. This is how a user finds out how many markers a mesh
// needs, and how Boneless is compared with ARAP.
struct EvaluationOptions {
    enum class Method { Boneless, Arap };
    Method method = Method::Boneless;
    std::vector<int> markers;  // vertex ids
    int firstFrame = 0;
    int endFrame = -1;       // one past the last frame; -1 = the end of the sequence
    double dropPercent = 0;  // each frame, this share of the markers goes missing
    unsigned seed = 1;       // a frame's missing markers are drawn from (seed, frame)
    // As a take is solved (TakeSolveOptions), so that what eval measures is what a user gets:
    // the orientation guard on for the exact method.
    SolverOptions solver = [] {
        SolverOptions s;
        s.orientationGuard = 100.0;
        return s;
    }();
    int arapIterations = 10;
    // How many markers each frame drops: dropPercent of them, rounded.
    int droppedPerFrame() const;
};

struct FrameEvaluation {
    int frame = 0;
    double rmsPct = 0;  // RMS vertex error, % of the rest pose's bounding-box diagonal
    double maxPct = 0;
    // Faces facing away from the truth's (more than 90° off), and faces folded over against
    // their own neighbourhood (Metrics' foldedFaces, no truth needed). A part no marker holds
    // can turn away from the truth without folding: the first counts it, the second does not.
    int flippedFaces = 0;
    int foldedFaces = 0;
    // The truth's own folded faces, by the same measure: a sequence that folds itself is folded
    // in a faithful answer too, and this tells those folds from the method's.
    int truthFoldedFaces = 0;
    int iterations = 0;
    double milliseconds = 0;
    int markersUsed = 0;  // the markers this frame was reconstructed from: those not dropped
};

struct EvaluationSummary {
    int frames = 0;       // frames summarised: those after the rest pose
    int markersUsed = 0;  // the fewest markers any of them was reconstructed from
    double rmsPctMean = 0, rmsPctWorstFrame = 0, maxPctWorstFrame = 0;
    int flippedFacesWorstFrame = 0;
    double flippedFacesMean = 0;
    int foldedFacesWorstFrame = 0;
    int truthFoldedFacesWorstFrame = 0;
    double msPerFrameMean = 0, msPerFrameWorst = 0, msPerFrameMedian = 0, iterationsMean = 0;
};

struct Evaluation {
    std::vector<FrameEvaluation> frames;
    EvaluationSummary summary;
    // The rest pose's bounding-box diagonal (mesh units): what the % figures are a share of.
    double bboxDiagonal = 0;
};

const char* methodName(EvaluationOptions::Method method);

// Expensive: prepares the method once (Boneless: encoding, coarse level, factorisation), then
// solves every frame of the range. onFrame (optional) is given each frame's figures and its
// answer (#V by 3, the rest pose's vertex order) as they come, to print or write them.
// Throws Error when the range is empty or a frame it needs was not read.
Evaluation evaluateSequence(
    const MeshSequence& sequence, const EvaluationOptions& options,
    const std::function<void(const FrameEvaluation&, const Positions& V)>& onFrame = {});

// The figures of an answer V (#V by 3) found elsewhere, by a method of one's own, for the
// sequence's frame `frame`: measured as evaluateSequence measures its own (iterations,
// milliseconds and markersUsed stay 0). Throws Error when V's row count is not the mesh's or the
// frame was not read.
FrameEvaluation measureFrame(const MeshSequence& sequence, int frame, const Positions& V);

// The summary of frames measured one by one: over those after the rest pose.
EvaluationSummary summarise(const std::vector<FrameEvaluation>& frames);

}  // namespace boneless
