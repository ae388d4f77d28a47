// boneless-cli eval: reconstruct a ground-truth sequence from K of its vertices and measure it.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "Commands.h"
#include "FrameRange.h"
#include "OptionFlags.h"
#include "boneless/Error.h"
#include "boneless/InputFile.h"
#include "boneless/MeshReader.h"
#include "boneless/ObjWriter.h"
#include "boneless/Sampling.h"
#include "boneless/SequenceEvaluation.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/Text.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

struct EvalArgs {
    std::string sequence;
    int markers = 0;
    std::string markersFile;
    std::string frames;
    std::string method = "boneless";
    double drop = 0;
    unsigned seed = 1;
    nlohmann::json options = nlohmann::json::object();  // the solver's options given
    std::string out;                                    // each method's answers go to out/<method>/
    std::string reconstruction;  // a folder of answers found elsewhere, judged instead
    bool json = false;
    bool quiet = false;
};

std::vector<int> readMarkerFile(const std::string& path, int vertexCount) {
    if (const std::string why = notARegularFile(path, "marker"); !why.empty())
        throw Error(path + ": " + why);
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open the marker file (" + std::strerror(errno) + ")");
    std::vector<int> ids;
    std::map<int, int> lineOf;  // each id's line, to name both lines of a repeated one
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        const std::string text = line;          // as written, for the message
        line = line.substr(0, line.find('#'));  // a comment runs to the end of its line
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos) continue;
        std::size_t used = 0;
        int id = -1;
        try {
            id = std::stoi(line.substr(first), &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || line.find_first_not_of(" \t\r", first + used) != std::string::npos)
            throw Error(path + ":" + std::to_string(lineNo) + ": expected one vertex id, got \"" +
                        text + "\"");
        if (id < 0 || id >= vertexCount)
            throw Error(path + ":" + std::to_string(lineNo) + ": vertex " + std::to_string(id) +
                        " is out of range (the mesh has " + std::to_string(vertexCount) +
                        " vertices)");
        // Else the reconstruction refuses it by marker index, naming neither file nor line.
        if (const auto [at, fresh] = lineOf.emplace(id, lineNo); !fresh)
            throw Error(path + ":" + std::to_string(lineNo) + ": vertex " + std::to_string(id) +
                        " is already a marker (line " + std::to_string(at->second) + ")");
        ids.push_back(id);
    }
    if (ids.empty()) throw Error(path + ": no vertex ids in the marker file");
    return ids;
}

// `timed` is false for answers found elsewhere: nothing of ours solved them, so no marker count,
// iteration or time pretends otherwise.
nlohmann::json summaryJson(const EvaluationSummary& s, bool timed = true) {
    nlohmann::json out = {{"frame_count", s.frames},
                          {"rms_pct_mean", s.rmsPctMean},
                          {"rms_pct_worst_frame", s.rmsPctWorstFrame},
                          {"max_pct_worst_frame", s.maxPctWorstFrame},
                          {"flipped_faces_worst_frame", s.flippedFacesWorstFrame},
                          {"flipped_faces_mean", s.flippedFacesMean},
                          {"folded_faces_worst_frame", s.foldedFacesWorstFrame},
                          {"truth_folded_faces_worst_frame", s.truthFoldedFacesWorstFrame}};
    if (timed) {
        out["markers_used"] = s.markersUsed;
        out["ms_per_frame_mean"] = s.msPerFrameMean;
        out["ms_per_frame_worst"] = s.msPerFrameWorst;
        out["ms_per_frame_median"] = s.msPerFrameMedian;
        out["iterations_mean"] = s.iterationsMean;
    }
    return out;
}

// Each frame names its OBJ: "frame" is its place in the folder from 0, not the number in its
// name (horse-gallop's frame 0 is 0001.obj), and a figure is recomputed from the file.
nlohmann::json perFrameJson(const std::vector<FrameEvaluation>& frames,
                            const std::vector<std::string>& files, bool timed = true) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& f : frames) {
        nlohmann::json item = {{"frame", f.frame},
                               {"file", validUtf8(fs::path(files.at(f.frame)).filename().string())},
                               {"rms_pct", f.rmsPct},
                               {"max_pct", f.maxPct},
                               {"flipped_faces", f.flippedFaces},
                               {"folded_faces", f.foldedFaces},
                               {"truth_folded_faces", f.truthFoldedFaces}};
        if (timed) {
            item["markers_used"] = f.markersUsed;
            item["iterations"] = f.iterations;
            item["ms"] = f.milliseconds;
        }
        list.push_back(item);
    }
    return list;
}

// The first of the solver options given whose value, as read, is not its default: "" when each
// is at its default ("--fold-guard 0.010" as 0.01).
std::string firstChangedSolverOption(const nlohmann::json& given) {
    const SolverOptions defaults = EvaluationOptions{}.solver;
    SolverOptions read = defaults;
    fromJson(given, read, "eval");
    const nlohmann::json now = toJson(read), before = toJson(defaults);
    for (const auto& item : given.items())
        if (now.at(item.key()) != before.at(item.key())) return item.key();
    return {};
}

// The per-frame table: the method's name heads its first column, which the rows leave blank.
void printFrameHeader(const char* name, bool timed) {
    std::printf("%-9s %6s %9s %9s %8s %7s %13s", name, "frame", "RMS %", "max %", "flipped",
                "folded", "truth folded");
    if (timed) std::printf(" %6s %9s", "iters", "ms");
    std::printf("\n");
}

void printFrameRow(const char* name, const FrameEvaluation& f, bool timed) {
    const int width = std::max<int>(9, static_cast<int>(std::strlen(name)));
    std::printf("%-*s %6d %9.4f %9.4f %8d %7d %13d", width, "", f.frame, f.rmsPct, f.maxPct,
                f.flippedFaces, f.foldedFaces, f.truthFoldedFaces);
    if (timed) std::printf(" %6d %9.1f", f.iterations, f.milliseconds);
    std::printf("\n");
}

void printSummary(const char* name, const EvaluationSummary& s, bool timed = true) {
    std::printf("%-9s frames %d  ", name, s.frames);
    if (timed) std::printf("markers used %d  ", s.markersUsed);
    std::printf(
        "RMS %% mean %.3f  RMS %% worst frame %.3f  max %% worst frame %.3f  flipped max %d (mean "
        "%.1f)  folded max %d (truth folded max %d)",
        s.rmsPctMean, s.rmsPctWorstFrame, s.maxPctWorstFrame, s.flippedFacesWorstFrame,
        s.flippedFacesMean, s.foldedFacesWorstFrame, s.truthFoldedFacesWorstFrame);
    if (timed)
        std::printf("  ms/frame mean %.1f worst %.1f median %.1f", s.msPerFrameMean,
                    s.msPerFrameWorst, s.msPerFrameMedian);
    std::printf("\n");
}

// Where --out writes a method's answer for `frame`: out/<method>/ under the truth's file name, so
// that the folder is what --reconstruction reads back.
fs::path answerPath(const std::string& out, const char* method, const MeshSequence& sequence,
                    int frame) {
    return fs::path(out) / method / fs::path(sequence.files.at(frame)).filename();
}

// Refuses before any solve an --out that would write over a file already there: nothing a user
// made is replaced.
void refuseAnswersThere(const std::string& out, const std::vector<const char*>& methods,
                        const MeshSequence& sequence, int first, int end) {
    for (const char* method : methods)
        for (int frame = first; frame < end; ++frame)
            if (const fs::path path = answerPath(out, method, sequence, frame); fs::exists(path))
                throw Error(path.string() +
                            " already exists: --out writes each frame's answer into a new "
                            "folder, never over a file");
}

// --reconstruction DIR: judges the answers another program wrote, one OBJ per frame evaluated,
// named as the truth's frame (as --out writes them); the rest pose's is optional.
void judge(const EvalArgs& args, const MeshSequence& sequence, const FrameRange& range,
           int frameCount) {
    if (!fs::is_directory(args.reconstruction))
        throw Error(args.reconstruction + ": not a folder (--reconstruction names a folder of " +
                    "one OBJ per frame, named as the sequence's)");
    std::vector<FrameEvaluation> frames;
    for (int frame = range.first; frame < range.end; ++frame) {
        const std::string name = fs::path(sequence.files.at(frame)).filename().string();
        const fs::path path = fs::path(args.reconstruction) / name;
        if (!fs::exists(path)) {
            if (frame == 0) continue;  // the rest pose is not summarised
            throw Error(path.string() + ": no answer for frame " + std::to_string(frame) +
                        " (--reconstruction needs one OBJ per frame evaluated, named as the "
                        "sequence's " +
                        name + ")");
        }
        const TriMesh answer = readMesh(path.string()).mesh;
        if (answer.vertexCount() != sequence.rest.vertexCount() || answer.F != sequence.rest.F)
            throw Error(path.string() + ": " + std::to_string(answer.vertexCount()) +
                        " vertices and " + std::to_string(answer.faceCount()) +
                        " faces, not the sequence's " +
                        std::to_string(sequence.rest.vertexCount()) + " and " +
                        std::to_string(sequence.rest.faceCount()) +
                        (answer.vertexCount() == sequence.rest.vertexCount() &&
                                 answer.faceCount() == sequence.rest.faceCount()
                             ? " (its faces differ)"
                             : ""));
        frames.push_back(measureFrame(sequence, frame, answer.V));
    }
    const EvaluationSummary summary = summarise(frames);
    if (args.json) {
        nlohmann::json out = summaryJson(summary, false);
        out["method"] = "reconstruction";
        out["reconstruction"] = validUtf8(args.reconstruction);
        out["sequence"] = validUtf8(args.sequence);
        out["vertices"] = sequence.rest.vertexCount();
        out["faces"] = sequence.rest.faceCount();
        out["bbox_diagonal"] = boundingBoxDiagonal(sequence.rest.V);
        out["frame_range"] = {range.first, range.end};
        out["per_frame"] = perFrameJson(frames, sequence.files, false);
        std::cout << out.dump(2) << "\n";
        return;
    }
    std::printf("%s: frames %d:%d of %d, %d vertices, %d faces, the answers in %s\n",
                args.sequence.c_str(), range.first, range.end, frameCount,
                sequence.rest.vertexCount(), sequence.rest.faceCount(),
                args.reconstruction.c_str());
    if (!args.quiet) {
        printFrameHeader("reconstruction", false);
        for (const auto& f : frames) printFrameRow("reconstruction", f, false);
    }
    std::printf("summary over the frames after the rest pose:\n");
    printSummary("reconstruction", summary, false);
}

void run(const EvalArgs& args) {
    const int frameCount = static_cast<int>(meshSequenceFiles(args.sequence).size());
    // The summaries run over the frames after the rest pose: with none, they are all zeros.
    if (frameCount < 2)
        throw Error(args.sequence +
                    ": no frame after the rest pose to evaluate (it holds one OBJ)");
    FrameRange range = withinFrames(parseFrameRange(args.frames), args.frames, frameCount,
                                    args.sequence, "evaluating");
    if (range.end < 0) range.end = frameCount;
    if (range.first == 0 && range.end == 1)
        throw Error("frames " + args.frames + " select only the rest pose of " + args.sequence +
                    ": no frame after it to evaluate");
    // Only the frames evaluated are read (and, for ARAP's chain, those before them), not the
    // whole folder: 2 frames of samba's 175 read 3 files.
    const bool arapRuns = args.reconstruction.empty() && args.method != "boneless";
    const MeshSequence sequence = readMeshSequence(args.sequence, [&](int frame) {
        return frame < range.end && (frame >= range.first || arapRuns);
    });
    if (!args.reconstruction.empty()) return judge(args, sequence, range, frameCount);
    const int vertices = sequence.rest.vertexCount();
    if (args.markersFile.empty() && args.markers >= vertices)
        throw Error("--markers " + std::to_string(args.markers) +
                    " leaves no vertex to reconstruct: " + args.sequence + " has " +
                    std::to_string(vertices) + " vertices");
    EvaluationOptions options;
    options.markers = args.markersFile.empty()
                          ? geodesicFarthestPoints(sequence.rest, args.markers, 0)
                          : readMarkerFile(args.markersFile, vertices);
    std::vector<int> distinct = options.markers;
    std::sort(distinct.begin(), distinct.end());
    if (std::unique(distinct.begin(), distinct.end()) - distinct.begin() >= vertices)
        throw Error(args.markersFile + " makes every one of the " + std::to_string(vertices) +
                    " vertices a marker: none is left to reconstruct");
    // Every marker missing in every frame: nothing to reconstruct from, and the summary would
    // read as a reconstruction.
    options.dropPercent = args.drop;
    char drop[32];  // as typed: "94", not to_string's "94.000000"
    std::snprintf(drop, sizeof drop, "%g", args.drop);
    if (options.droppedPerFrame() >= static_cast<int>(options.markers.size())) {
        throw Error(std::string("--drop ") + drop + " leaves none of the " +
                    std::to_string(options.markers.size()) +
                    " markers in any frame: there is nothing to reconstruct from");
    }
    options.firstFrame = range.first;
    options.endFrame = range.end;
    options.seed = args.seed;
    fromJson(args.options, options.solver, "eval");

    std::vector<EvaluationOptions::Method> methods;
    if (args.method == "boneless" || args.method == "both")
        methods.push_back(EvaluationOptions::Method::Boneless);
    if (args.method == "arap" || args.method == "both")
        methods.push_back(EvaluationOptions::Method::Arap);

    // What a frame is reconstructed from: a drop that rounds to no marker drops none, and says so.
    const int used = static_cast<int>(options.markers.size()) - options.droppedPerFrame();
    std::string dropped;
    if (args.drop > 0)
        dropped = ", " + std::string(drop) + " % dropped per frame" +
                  (options.droppedPerFrame() == 0 ? " rounds to none" : "") + ": " +
                  std::to_string(used) + " used per frame";
    // Before the header: a folder that cannot be made fails the run before it says it starts.
    if (!args.out.empty()) {
        std::vector<const char*> names;
        for (auto method : methods) names.push_back(methodName(method));
        refuseAnswersThere(args.out, names, sequence, range.first, range.end);
        for (const char* name : names) {
            std::error_code ec;
            fs::create_directories(fs::path(args.out) / name, ec);
            if (ec)
                throw Error((fs::path(args.out) / name).string() + ": cannot create the folder (" +
                            ec.message() + ")");
        }
    }
    if (!args.json)
        std::printf("%s: frames %d:%d of %d, %d vertices, %d faces, %zu markers%s, %s\n",
                    args.sequence.c_str(), range.first, range.end, frameCount,
                    sequence.rest.vertexCount(), sequence.rest.faceCount(), options.markers.size(),
                    dropped.c_str(),
                    methods[0] == EvaluationOptions::Method::Boneless
                        ? (std::string(methodName(options.solver.method)) + " solver").c_str()
                        : "ARAP alone");
    // The truth's own polygons, UVs and materials, so that an answer opens as the truth does.
    const SourceFaces* source = sequence.rest.sourceFaces.get();
    std::vector<Evaluation> results;
    for (auto method : methods) {
        options.method = method;
        const bool perFrame = !args.json && !args.quiet;
        if (perFrame) printFrameHeader(methodName(method), true);
        results.push_back(
            evaluateSequence(sequence, options, [&](const FrameEvaluation& f, const Positions& V) {
                if (!args.out.empty())
                    writeObj(answerPath(args.out, methodName(method), sequence, f.frame).string(),
                             V, sequence.rest.F,
                             std::string("boneless-cli eval, ") + methodName(method) + ", frame " +
                                 std::to_string(f.frame),
                             source);
                if (perFrame) printFrameRow(methodName(method), f, true);
            }));
    }
    if (args.json) {
        nlohmann::json out = summaryJson(results[0].summary);
        out["method"] = args.method;                 // boneless, arap or both
        out["sequence"] = validUtf8(args.sequence);  // JSON holds only UTF-8
        out["vertices"] = sequence.rest.vertexCount();
        out["faces"] = sequence.rest.faceCount();
        out["markers"] = options.markers.size();
        out["marker_vertices"] = options.markers;  // to give another method: --markers-file
        out["drop_pct"] = args.drop;
        if (args.drop > 0) out["seed"] = args.seed;
        out["bbox_diagonal"] = results[0].bboxDiagonal;
        out["frame_range"] = {range.first, range.end};  // [first, end), as the sidecar's
        // ARAP alone uses none of Boneless's solver options.
        if (methods[0] == EvaluationOptions::Method::Boneless)
            out["options"] = toJson(options.solver);
        out["per_frame"] = perFrameJson(results[0].frames, sequence.files);
        // With both, the top level is Boneless's and ARAP's figures are under its name.
        for (size_t i = 1; i < results.size(); ++i) {
            nlohmann::json other = summaryJson(results[i].summary);
            other["per_frame"] = perFrameJson(results[i].frames, sequence.files);
            out[methodName(methods[i])] = other;
        }
        std::cout << out.dump(2) << "\n";
    } else {
        std::printf("summary over the frames after the rest pose:\n");
        for (size_t i = 0; i < results.size(); ++i)
            printSummary(methodName(methods[i]), results[i].summary);
        // Measured in the same run, so that a busy machine slows both alike.
        if (results.size() == 2 && results[1].summary.msPerFrameMean > 0)
            std::printf("boneless / arap time per frame: mean %.2f  worst %.2f\n",
                        results[0].summary.msPerFrameMean / results[1].summary.msPerFrameMean,
                        results[0].summary.msPerFrameWorst / results[1].summary.msPerFrameWorst);
    }
}

}  // namespace

void registerEvalCommand(CLI::App& app) {
    auto args = std::make_shared<EvalArgs>();
    CLI::App* cmd = app.add_subcommand(
        "eval",
        "Reconstruct a ground-truth mesh sequence from K of its vertices and measure the error");
    cmd->add_option("--sequence", args->sequence,
                    "Folder with one OBJ per frame (first = rest pose)")
        ->required()
        ->check(aPath());
    auto* k = cmd->add_option("--markers", args->markers,
                              "Number of marker vertices (farthest-point sampled from vertex 0)")
                  ->check(numberFrom(1, 1e9, true));
    auto* file = cmd->add_option("--markers-file", args->markersFile,
                                 "File with one marker vertex id per line (instead of --markers)")
                     ->check(aPath());
    k->excludes(file);
    cmd->add_option("--frames", args->frames, "Frame range A:B (0-based, B excluded; A: or :B)");
    cmd->add_option("--method", args->method,
                    withDefault("boneless, arap, or both (side by side)", args->method))
        ->check(CLI::IsMember({"boneless", "arap", "both"}));
    cmd->add_option("--drop", args->drop,
                    withDefault("Percentage of markers missing in each frame (seeded)", args->drop))
        ->check(numberFrom(0, 100));
    cmd->add_option("--seed", args->seed, withDefault("Seed for --drop", args->seed))
        ->check(numberFrom(0, 4294967295.0, true))  // CLI11 read 010 as octal 8, 0x10 as 16
        ->needs("--drop");
    addOptionFlags(cmd, args->options, toJson(EvaluationOptions{}.solver), true);
    auto* out = cmd->add_option("--out", args->out,
                                "Also write each frame's answer: DIR/<method>/ one OBJ per frame, "
                                "named as the sequence's")
                    ->check(aPath());
    auto* given = cmd->add_option("--reconstruction", args->reconstruction,
                                  "Judge the answers in this folder (one OBJ per frame, named as "
                                  "the sequence's) instead of reconstructing")
                      ->check(aPath());
    given->excludes(k)->excludes(file)->excludes(out);
    cmd->add_flag("--json", args->json, "Print one JSON object");
    cmd->add_flag("--quiet", args->quiet, "No per-frame lines");
    cmd->callback([args, k, file, given, cmd] {
        if (given->count() > 0) {
            // Answers found elsewhere: nothing here solves, so nothing sets how.
            for (const char* flag : {"--method", "--drop", "--seed"})
                if (cmd->count(flag) > 0)
                    throw CLI::ValidationError(flag,
                                               "sets how eval reconstructs, and "
                                               "--reconstruction judges answers found "
                                               "elsewhere");
            if (!args->options.empty())
                throw CLI::ValidationError(optionFlag(*findTakeOption(args->options.begin().key())),
                                           "sets how Boneless solves, and --reconstruction "
                                           "judges answers found elsewhere");
            run(*args);
            return;
        }
        if (k->count() == 0 && file->count() == 0)
            throw CLI::RequiredError("--markers or --markers-file");
        // The solver flags set how Boneless solves: on ARAP alone they would change nothing.
        // At their defaults they change nothing anywhere, so that one command line serves every
        // --method (a value the local/global solver does not read is taken so too).
        if (args->method == "arap")
            if (const std::string key = firstChangedSolverOption(args->options); !key.empty())
                throw CLI::ValidationError(optionFlag(*findTakeOption(key)),
                                           "sets how Boneless solves, and --method arap runs "
                                           "ARAP alone");
        refuseUnusedExactOptions(args->options, EvaluationOptions{}.solver);
        run(*args);
    });
}
