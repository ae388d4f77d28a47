#include "boneless/SequenceEvaluation.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "boneless/ArapDeformer.h"
#include "boneless/Error.h"
#include "boneless/Metrics.h"
#include "boneless/Statistics.h"

namespace boneless {

int EvaluationOptions::droppedPerFrame() const {
    return static_cast<int>(std::lround(markers.size() * dropPercent / 100.0));
}

const char* methodName(EvaluationOptions::Method method) {
    return method == EvaluationOptions::Method::Arap ? "arap" : "boneless";
}

EvaluationSummary summarise(const std::vector<FrameEvaluation>& frames) {
    EvaluationSummary s;
    std::vector<double> ms;
    double iterations = 0;
    for (const auto& f : frames) {
        if (f.frame == 0) continue;  // the rest pose is reproduced by construction
        s.markersUsed = s.frames == 0 ? f.markersUsed : std::min(s.markersUsed, f.markersUsed);
        ++s.frames;
        s.rmsPctMean += f.rmsPct;
        s.rmsPctWorstFrame = std::max(s.rmsPctWorstFrame, f.rmsPct);
        s.maxPctWorstFrame = std::max(s.maxPctWorstFrame, f.maxPct);
        s.flippedFacesWorstFrame = std::max(s.flippedFacesWorstFrame, f.flippedFaces);
        s.flippedFacesMean += f.flippedFaces;
        s.foldedFacesWorstFrame = std::max(s.foldedFacesWorstFrame, f.foldedFaces);
        s.truthFoldedFacesWorstFrame = std::max(s.truthFoldedFacesWorstFrame, f.truthFoldedFaces);
        iterations += f.iterations;
        ms.push_back(f.milliseconds);
    }
    if (s.frames > 0) {
        s.rmsPctMean /= s.frames;
        s.flippedFacesMean /= s.frames;
        s.iterationsMean = iterations / s.frames;
        s.msPerFrameMean = std::accumulate(ms.begin(), ms.end(), 0.0) / s.frames;
        s.msPerFrameWorst = *std::max_element(ms.begin(), ms.end());
        s.msPerFrameMedian = median(ms);
    }
    return s;
}

namespace {

// The truth of `frame`, refused when it was not read.
const Positions& truthOf(const MeshSequence& sequence, int frame) {
    const Positions& truth = sequence.frames.at(frame);
    if (truth.rows() != sequence.rest.V.rows())
        throw Error("frame " + std::to_string(frame) +
                    (frame < static_cast<int>(sequence.files.size())
                         ? " (" + sequence.files[frame] + ")"
                         : std::string()) +
                    " was not read, and the evaluation needs it");
    return truth;
}

FrameEvaluation measure(const MeshSequence& sequence, int frame, const Positions& V,
                        const Positions& truth, double diagonal) {
    FrameEvaluation f;
    f.frame = frame;
    f.rmsPct = 100.0 * rmsVertexError(V, truth) / diagonal;
    f.maxPct = 100.0 * maxVertexError(V, truth) / diagonal;
    f.flippedFaces = flippedFaceCount(sequence.rest.F, V, truth);
    f.foldedFaces = foldedFaceCount(sequence.rest.F, V, sequence.rest.V);
    f.truthFoldedFaces = foldedFaceCount(sequence.rest.F, truth, sequence.rest.V);
    return f;
}

}  // namespace

FrameEvaluation measureFrame(const MeshSequence& sequence, int frame, const Positions& V) {
    if (frame < 0 || frame >= static_cast<int>(sequence.frames.size()))
        throw Error("frame " + std::to_string(frame) + " is not in the sequence (it has " +
                    std::to_string(sequence.frames.size()) + " frames)");
    const Positions& truth = truthOf(sequence, frame);
    if (V.rows() != truth.rows())
        throw Error("the answer for frame " + std::to_string(frame) + " has " +
                    std::to_string(V.rows()) + " vertices, the sequence " +
                    std::to_string(truth.rows()));
    return measure(sequence, frame, V, truth, boundingBoxDiagonal(sequence.rest.V));
}

Evaluation evaluateSequence(
    const MeshSequence& sequence, const EvaluationOptions& options,
    const std::function<void(const FrameEvaluation&, const Positions&)>& onFrame) {
    const int frameCount = static_cast<int>(sequence.frames.size());
    const int end = options.endFrame < 0 ? frameCount : std::min(options.endFrame, frameCount);
    if (options.firstFrame < 0 || options.firstFrame >= end)
        throw Error("frame range " + std::to_string(options.firstFrame) + ":" +
                    std::to_string(end) + " is empty (the sequence has " +
                    std::to_string(frameCount) + " frames)");
    const auto& markers = options.markers;
    const int K = static_cast<int>(markers.size());
    const double diagonal = boundingBoxDiagonal(sequence.rest.V);

    Reconstruction boneless, start;
    ArapDeformer arap;
    const bool useArap = options.method == EvaluationOptions::Method::Arap;
    const bool exact = options.solver.method == SolverOptions::Method::Exact;
    if (useArap) {
        arap.prepare(sequence.rest, markers, {options.arapIterations});
    } else {
        boneless.prepare(sequence.rest, markers, options.solver);
        // As a take is solved: the exact method refines each frame's local/global answer.
        if (exact) {
            SolverOptions o = options.solver;
            o.method = SolverOptions::Method::LocalGlobal;
            start.prepare(sequence.rest, markers, o);
        }
    }

    const int dropCount = options.droppedPerFrame();
    std::vector<int> order(K);
    // ARAP's chain starts at the rest pose at frame 0 whatever the range: the frames before it
    // are solved, unreported, so that a frame's figures do not depend on where --frames begins.
    Positions previous = sequence.rest.V;

    Evaluation evaluation;
    evaluation.bboxDiagonal = diagonal;
    for (int frame = useArap ? 0 : options.firstFrame; frame < end; ++frame) {
        const Positions& truth = truthOf(sequence, frame);
        Positions targets(K, 3);
        for (int k = 0; k < K; ++k) targets.row(k) = truth.row(markers[k]);
        if (dropCount > 0) {
            // Drawn from (seed, frame): a frame loses the same markers whatever --frames says.
            std::seed_seq frameSeed{options.seed, static_cast<unsigned>(frame)};
            std::mt19937 rng(frameSeed);
            std::iota(order.begin(), order.end(), 0);
            std::shuffle(order.begin(), order.end(), rng);
            for (int i = 0; i < dropCount; ++i)
                targets.row(order[i]).setConstant(std::numeric_limits<double>::quiet_NaN());
        }
        SolveResult result;
        if (useArap) {
            // ARAP as it is used: each frame from the previous one's answer.
            result = arap.solve(targets, &previous);
            if (frame < options.firstFrame) {
                previous = std::move(result.V);
                continue;
            }
        } else if (exact) {
            const SolveResult first = start.solve(targets);
            result = boneless.solve(targets, &first.V);
            result.report.iterations += first.report.iterations;
            result.report.milliseconds += first.report.milliseconds;
        } else {
            result = boneless.solve(targets);
        }

        FrameEvaluation f = measure(sequence, frame, result.V, truth, diagonal);
        f.iterations = result.report.iterations;
        f.milliseconds = result.report.milliseconds;
        f.markersUsed = K - dropCount;
        evaluation.frames.push_back(f);
        if (onFrame) onFrame(f, result.V);
        previous = std::move(result.V);
    }
    evaluation.summary = summarise(evaluation.frames);
    return evaluation;
}

}  // namespace boneless
