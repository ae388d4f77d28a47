#include "boneless/DemoFiles.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <string>

#include "DemoCapture.h"
#include "DemoCreature.h"
#include "DemoTake.h"
#include "DemoWalker.h"
#include "boneless/C3dWriter.h"
#include "boneless/Error.h"
#include "boneless/ObjWriter.h"
#include "boneless/OutputFolder.h"
#include "boneless/TakeExport.h"
#include "boneless/Text.h"

namespace boneless {

namespace {

// About what one OBJ of a mesh this size takes: a line a vertex ("v" and three coordinates of
// some 19 shortest round-trip digits; the walker's frames average 60 bytes) and a line a
// triangle (three indices of up to the vertex count's digits), and the comment.
std::uintmax_t objBytes(const TriMesh& mesh) {
    const std::uintmax_t digits = std::to_string(mesh.vertexCount()).size();
    return 100 + 62 * std::uintmax_t(mesh.vertexCount()) +
           (2 + 3 * (1 + digits)) * std::uintmax_t(mesh.faceCount());
}

std::string gigabytes(std::uintmax_t bytes) {
    return fixedNumber(double(bytes) / (1024.0 * 1024 * 1024), 1) + " GB";
}

// Refuses, before anything is made or written, a demo the folder's file system has no room for:
// 100,000 frames of truth wrote 31 GB without a word, until the disk was full.
void checkRoom(const std::string& folder, std::uintmax_t needed, int frames, bool withTruth) {
    namespace fs = std::filesystem;
    std::error_code ec;
    // The folder may not be there yet: its nearest existing parent's file system will hold it.
    fs::path there = fs::absolute(folder, ec);
    while (!ec && !fs::exists(there, ec) && there.has_relative_path()) there = there.parent_path();
    const fs::space_info space = fs::space(there, ec);
    if (ec || needed <= space.available) return;  // no figure: a failing write says why
    throw Error(folder + ": the demo needs about " + gigabytes(needed) + " (" +
                plural(frames, "frame") + (withTruth ? ", each with its true pose as an OBJ" : "") +
                "), and its file system has " + gigabytes(space.available) + " free");
}

}  // namespace

namespace {

// Where each of the demo's files goes as it is made: its name in the folder ("walker.obj",
// "truth/walker_0003.obj") and its bytes.
using DemoFileSink = std::function<void(const std::string& name, const std::string& contents)>;

void checkDetail(int detail, DemoSubject subject) {
    if (detail < 1)
        throw Error("demo detail must be at least 1 (got " + std::to_string(detail) + ")");
    if (subject == DemoSubject::Walker && detail > 4)
        throw Error("the walker's detail is at most 4 (got " + std::to_string(detail) + ")");
}

std::string subjectName(DemoSubject subject) {
    return subject == DemoSubject::Walker ? "walker" : "creature";
}

std::string truthName(const std::string& name, int frame) {
    char file[64];
    std::snprintf(file, sizeof file, "truth/%s_%04d.obj", name.c_str(), frame);
    return file;
}

// Makes the demo's files, each handed to `sink`, frame by frame: each frame's truth goes as it
// is made, and only the take's samples are held (a 100,000-frame demo held 8 GB of frames).
// The counts it returns name no files.
DemoFiles makeDemoFiles(int frames, double offsetMm, bool withTruth, int detail,
                        DemoSubject subject, const DemoFileSink& sink) {
    const std::string name = subjectName(subject);
    TriMesh rest;
    std::unique_ptr<DemoRecorder> recorder;
    std::function<void(const std::function<void(int, const Positions&)>&)> makeFrames;
    std::string units;
    if (subject == DemoSubject::Walker) {
        const DemoWalker walker = makeDemoWalker(0, 1 + detail);
        rest = walker.rest;
        recorder =
            std::make_unique<DemoRecorder>(rest, demoWalkerCapture(walker), frames, offsetMm);
        makeFrames = [&](const auto& onFrame) { makeDemoWalker(frames, 1 + detail, onFrame); };
        units = "metres";
    } else {
        const DemoCreature creature = makeDemoCreature(0, 48 * detail, 24 * detail);
        rest = creature.rest;
        recorder = std::make_unique<DemoRecorder>(rest, demoCreatureCapture(creature, 30), frames,
                                                  offsetMm);
        makeFrames = [&](const auto& onFrame) {
            makeDemoCreature(frames, 48 * detail, 24 * detail, onFrame);
        };
        units = "decimetres";
    }
    sink(name + ".obj",
         objText(name + ".obj", rest.V, rest.F,
                 "Boneless generated demo " + name + ", rest pose (" + units + ", z up)"));
    sink(name + ".map.json", recorder->take.map.toJson());
    makeFrames([&](int t, const Positions& pose) {
        recorder->record(t, pose);
        if (withTruth)
            sink(truthName(name, t), objText(truthName(name, t), pose, rest.F,
                                             "Boneless generated demo " + name +
                                                 ", true pose of frame " + std::to_string(t)));
    });
    const C3dTake& take = recorder->take.take;
    const std::vector<std::uint8_t> c3d = encodeC3d(take);
    sink(name + ".c3d", std::string(c3d.begin(), c3d.end()));
    DemoFiles files;
    files.vertices = rest.vertexCount();
    files.faces = rest.faceCount();
    files.markers = static_cast<int>(take.points.size());
    files.frames = static_cast<int>(take.frameCount());
    files.rate = take.rate;
    return files;
}

}  // namespace

DemoFiles writeDemoFiles(const std::string& folder, int frames, double offsetMm, bool withTruth,
                         int detail, DemoSubject subject) {
    namespace fs = std::filesystem;
    const fs::path out(folder), truth = out / "truth";
    checkDetail(detail, subject);
    // The rest mesh alone first: an OBJ of it for the rest and for each frame of truth, and the
    // take's few bytes a marker a frame.
    const TriMesh shape = subject == DemoSubject::Walker
                              ? makeDemoWalker(0, 1 + detail).rest
                              : makeDemoCreature(0, 48 * detail, 24 * detail).rest;
    checkRoom(folder,
              objBytes(shape) * (1 + (withTruth ? std::uintmax_t(frames) : 0)) +
                  1024 * std::uintmax_t(frames) + 64 * 1024,
              frames, withTruth);
    std::error_code ec;
    fs::create_directories(withTruth ? truth : out, ec);
    if (ec) throw Error(folder + ": cannot create the folder (" + ec.message() + ")");
    DemoFiles files = makeDemoFiles(frames, offsetMm, withTruth, detail, subject,
                                    [&](const std::string& name, const std::string& contents) {
                                        writeFileAtomically((out / name).string(), contents);
                                    });
    const std::string name = subjectName(subject);
    // A demo of fewer frames than the one it replaces (--force) leaves none of that one's truth
    // past its count, which a tool reading truth/ by pattern would play as this take's. Only the
    // files this demo names so are removed.
    for (int frame : withTruth ? objFramesIn(truth.string(), name) : std::vector<int>())
        if (frame >= files.frames) fs::remove(truth / objFrameFile(name, frame), ec);
    files.folder = folder;
    files.mesh = (out / (name + ".obj")).string();
    files.take = (out / (name + ".c3d")).string();
    files.map = (out / (name + ".map.json")).string();
    if (withTruth) files.truthFolder = truth.string();
    return files;
}

std::vector<std::string> demoFilesThatDiffer(const std::string& folder, int frames, double offsetMm,
                                             bool withTruth, int detail, DemoSubject subject) {
    namespace fs = std::filesystem;
    checkDetail(detail, subject);
    // Made only when the folder holds one of the files: a new folder costs nothing.
    const std::string name = subjectName(subject);
    std::vector<std::string> names = {name + ".obj", name + ".c3d", name + ".map.json"};
    for (int t = 0; withTruth && t < frames; ++t) names.push_back(truthName(name, t));
    // Frames of truth past the count are removed by the write: the user's own, or a longer demo's
    // (until 2 December 2026 removed without --force).
    std::vector<std::string> pastCount;
    for (int t :
         withTruth ? objFramesIn((fs::path(folder) / "truth").string(), name) : std::vector<int>())
        if (t >= frames) pastCount.push_back(truthName(name, t));
    std::sort(pastCount.begin(), pastCount.end());
    std::error_code ec;
    if (pastCount.empty() && std::none_of(names.begin(), names.end(), [&](const std::string& n) {
            return fs::exists(fs::path(folder) / n, ec);
        }))
        return {};
    std::vector<std::string> differ;
    makeDemoFiles(frames, offsetMm, withTruth, detail, subject,
                  [&](const std::string& n, const std::string& contents) {
                      const fs::path path = fs::path(folder) / n;
                      if (!fs::exists(path, ec)) return;  // made anew: nothing to lose
                      std::ifstream in(path, std::ios::binary);
                      const std::string there{std::istreambuf_iterator<char>(in), {}};
                      if (there != contents) differ.push_back(n);
                  });
    // The take, made last, named with the map and the mesh before the frames of truth.
    std::stable_partition(differ.begin(), differ.end(),
                          [](const std::string& n) { return n.find('/') == std::string::npos; });
    differ.insert(differ.end(), pastCount.begin(), pastCount.end());
    return differ;
}

}  // namespace boneless
