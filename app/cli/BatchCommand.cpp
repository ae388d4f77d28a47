// boneless-cli batch: many takes from one manifest, resumable and shardable (docs/batch.md).
#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <tuple>
#include <vector>

#include "Commands.h"
#include "FrameRange.h"
#include "OptionFlags.h"
#include "TakeJob.h"
#include "boneless/C3dFrameReader.h"
#include "boneless/Error.h"
#include "boneless/ExportFormat.h"
#include "boneless/InputFile.h"
#include "boneless/MeshReader.h"
#include "boneless/OutputFolder.h"
#include "boneless/TakeExport.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/Text.h"

using namespace boneless;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct BatchArgs {
    // All of it unless given; given empty ("--shard \"$SHARD\"", unset) is refused, not all:
    // every task of a job array then ran every take.
    std::string manifest, shard = "1/1";
    bool quiet = false;
    bool force = false;  // each take's job.force
};

// A manifest key as written ("fill-gaps", from manifests of before) under its JSON name.
std::string underscored(std::string written) {
    std::replace(written.begin(), written.end(), '-', '_');
    return written;
}

// Where `written` stands among the names of `option`: today's key first, then its old keys in
// order, each written with '_' before its dashed spelling (the manifests of before).
int nameRank(const TakeOption& option, const std::string& written) {
    const std::string key = underscored(written);
    std::vector<std::string> names{option.key};
    names.insert(names.end(), option.oldKeys.begin(), option.oldKeys.end());
    const auto at = std::find(names.begin(), names.end(), key) - names.begin();
    return 2 * static_cast<int>(at) + (key != written ? 1 : 0);
}

// Whether `object` also names `option` by a name that comes before `written`: read in the keys'
// (alphabetical) order, "weight" overrode "marker_weight". As projects and sidecars read them
// (TakeOptionsJson's lookUp), today's name wins whatever the order.
bool outranked(const json& object, const TakeOption& option, const std::string& written) {
    for (const auto& [other, value] : object.items())
        if (findTakeOption(underscored(other)) == &option &&
            nameRank(option, other) < nameRank(option, written))
            return true;
    return false;
}

// The keys a manifest entry may hold: the names of `solve`'s options, each its flag's name with
// '_' for '-' (the options of core's table: their JSON keys). Dashed keys, which manifests held
// before, read the same.
void applyKeys(const json& object, const fs::path& base, const std::string& where, TakeJob& job) {
    if (!object.is_object()) throw Error(where + ": an entry is a JSON object");
    for (const auto& [written, value] : object.items()) {
        const std::string key = underscored(written);
        // As a path flag refuses "": it named the manifest's own folder ("out": "" solved into it).
        auto path = [&](const json& v) {
            const fs::path p(v.get<std::string>());
            if (p.empty()) throw Error(where + ": \"" + written + "\" must be a path, got \"\"");
            return (p.is_absolute() ? p : base / p).lexically_normal().string();
        };
        try {
            if (key == "mesh")
                job.mesh = path(value);
            else if (key == "c3d")
                job.c3d = path(value);
            else if (key == "map")
                job.map = path(value);
            else if (key == "out")
                job.out = path(value);
            else if (key == "group")
                job.group = value.get<std::string>();
            else if (key == "format") {
                // Checked as solve's flag is, here rather than when the entry's turn comes.
                job.format = value.get<std::string>();
                if (!findExportFormat(job.format)) {
                    std::vector<std::string> names;
                    for (const ExportFormatInfo& f : exportFormats()) names.push_back(f.name);
                    throw Error(where + ": unknown format \"" + job.format + "\" (expected " +
                                joined(names) + ")");
                }
            } else if (key == "frames") {
                job.frames = value.get<std::string>();
                parseFrameRange(job.frames, where + ": \"" + written + "\"");
            } else if (key == "write_calibrated_rest")
                job.writeCalibratedRest = value.get<bool>();
            else if (const TakeOption* option = findTakeOption(key)) {
                TakeSolveOptions check;  // names the key and what is wrong, before any solve
                fromJson(json{{key, value}}, check, where);
                if (outranked(object, *option, written)) continue;
                job.options[option->key] = value;
            } else
                throw Error(where + ": unknown key \"" + written + "\"");
        } catch (const json::exception&) {
            const char* wants = key == "write_calibrated_rest" ? "true or false" : "a string";
            throw Error(where + ": \"" + written + "\" has the wrong type (" + value.dump() +
                        "): it wants " + wants);
        }
    }
}

// An entry's options that the exact solver alone reads, refused without "solver": "exact" (flags
// and keys alike, OptionFlags' rule), each named as the entry or its defaults wrote it.
void refuseUnusedExactOptions(const TakeJob& job, const json& entry, const json& defaults,
                              const std::string& where) {
    const auto written = [&](const std::string& key, const std::string& value) {
        for (const json* object : {&entry, &defaults})
            for (const auto& item : object->items()) {
                const std::string& name = item.key();
                if (findTakeOption(underscored(name)) == findTakeOption(key) &&
                    !outranked(*object, *findTakeOption(key), name))
                    return "\"" + name + "\" " + value +
                           (object == &defaults ? " (from defaults)" : "");
            }
        return "\"" + key + "\" " + value;
    };
    ::refuseUnusedExactOptions(job.options, TakeSolveOptions{}.solver, where, written);
}

void requireKeys(const TakeJob& job, const std::string& where) {
    for (const auto& [key, value] : {std::pair<const char*, const std::string*>{"mesh", &job.mesh},
                                     {"c3d", &job.c3d},
                                     {"map", &job.map},
                                     {"out", &job.out}})
        if (value->empty()) throw Error(where + ": \"" + key + "\" is missing");
}

// Two entries that write one sidecar (sessA/walk.c3d and sessB/walk.c3d into one "out") would
// overwrite each other's files, both say solved, and both be solved again on every run.
// `entries` names each job as a message should ("takes[1] (/lib/sessB/walk.c3d)").
void refuseSharedOutputs(const std::string& file, const std::vector<TakeJob>& jobs,
                         const std::vector<std::string>& entries) {
    const auto canonical = [](const std::string& path) {
        std::error_code ec;
        return fs::weakly_canonical(path, ec).string();
    };
    std::map<std::string, std::size_t> writers;  // the sidecar, however spelled, and its entry
    for (std::size_t k = 0; k < jobs.size(); ++k) {
        const std::string sidecar = takeJobSidecar(jobs[k]);
        const auto [it, first] = writers.emplace(canonical(sidecar), k);
        if (!first)
            throw Error(file + ": " + entries[it->second] + " and " + entries[k] + " both write " +
                        sidecar + " and the outputs beside it; give each its own \"out\"");
    }
    // An entry's sidecar over another entry's input (its map kept as <stem>.json in that "out")
    // would destroy it before that entry is solved. A writer whose own inputs hold that file is
    // refused as it is solved and never writes, so it is left to that check.
    const auto inputs = [](const TakeJob& job) {
        return std::array<std::pair<const char*, std::string>, 3>{
            {{"mesh", job.mesh}, {"take", job.c3d}, {"map", job.map}}};
    };
    for (std::size_t j = 0; j < jobs.size(); ++j)
        for (const auto& [what, input] : inputs(jobs[j])) {
            const auto writer = writers.find(canonical(input));
            if (writer == writers.end() || writer->second == j) continue;
            bool refusedOnItsOwn = false;
            for (const auto& own : inputs(jobs[writer->second]))
                refusedOnItsOwn = refusedOnItsOwn || canonical(own.second) == writer->first;
            if (!refusedOnItsOwn)
                throw Error(file + ": the sidecar of " + entries[writer->second] + ", " + input +
                            ", would replace the " + what + " of " + entries[j] +
                            "; give it another \"out\"");
        }
}

// Entries in manifest order: "takes" first, then each of "folders" expanded in file-name order.
std::vector<TakeJob> readManifest(const std::string& file) {
    if (const std::string why = notARegularFile(file, "batch manifest"); !why.empty())
        throw Error(file + ": " + why);
    std::ifstream in(file);
    if (!in) throw Error(file + ": cannot open the batch manifest (" + std::strerror(errno) + ")");
    json m;
    try {
        m = json::parse(in);
    } catch (const json::exception& e) {
        throw Error(file + ": not valid JSON (" + e.what() + ")");
    }
    if (!m.is_object()) throw Error(file + ": a batch manifest is a JSON object");
    // Absolute, so that the sidecars name the same files however the manifest was named and from
    // whichever folder: `batch m.json` in its folder and `batch /lib/m.json` skip the same takes.
    const fs::path base = fs::absolute(file).parent_path();
    TakeJob defaults;
    for (const auto& [key, value] : m.items())
        if (key != "defaults" && key != "takes" && key != "folders")
            throw Error(file + ": unknown key \"" + key + "\" (expected defaults, takes, folders)");
    // Checked before they are indexed: json's own type_error would be an "internal error".
    for (const char* key : {"takes", "folders"})
        if (m.contains(key) && !m[key].is_array()) {
            const std::string type = m[key].type_name();
            throw Error(file + ": \"" + key + "\" is an array of entries, not " +
                        (type == "null"     ? ""
                         : type == "object" ? "an "
                                            : "a ") +
                        type);
        }
    if (m.contains("defaults")) applyKeys(m["defaults"], base, file + ": defaults", defaults);
    std::vector<TakeJob> jobs;
    std::vector<std::string> entries;  // what messages call each job
    std::vector<std::string> empty;    // folders that hold no take, as messages call them
    const json takes = m.value("takes", json::array()), folders = m.value("folders", json::array());
    for (std::size_t i = 0; i < takes.size(); ++i) {
        const std::string where = file + ": takes[" + std::to_string(i) + "]";
        TakeJob job = defaults;
        applyKeys(takes[i], base, where, job);
        requireKeys(job, where);
        refuseUnusedExactOptions(job, takes[i], m.value("defaults", json::object()), where);
        jobs.push_back(job);
        entries.push_back("takes[" + std::to_string(i) + "] (" + job.c3d + ")");
    }
    for (std::size_t i = 0; i < folders.size(); ++i) {
        const std::string where = file + ": folders[" + std::to_string(i) + "]";
        TakeJob pattern = defaults;
        applyKeys(folders[i], base, where, pattern);
        requireKeys(pattern, where);
        refuseUnusedExactOptions(pattern, folders[i], m.value("defaults", json::object()), where);
        std::error_code ec;
        std::vector<fs::path> found;
        for (const auto& e : fs::directory_iterator(pattern.c3d, ec)) {
            // Hidden, or another tool's: macOS's ._take.c3d holds Finder's metadata, not a take.
            if (e.path().filename().string().front() == '.') continue;
            const std::string ext = asciiLower(e.path().extension().string());
            if (ext != ".c3d") continue;
            // A link whose take is gone (or a loop of links) was meant as a take: its entry
            // fails, naming it. Asked with an error_code: a loop anywhere in the folder threw,
            // and stopped the whole run before its first take.
            std::error_code status;
            const bool regular = e.is_regular_file(status);
            const bool broken = e.is_symlink(status) && !e.exists(status);
            if (regular || broken) found.push_back(e.path());
        }
        if (ec) throw Error(where + ": cannot list " + pattern.c3d + " (" + ec.message() + ")");
        std::sort(found.begin(), found.end());
        if (found.empty()) empty.push_back(where + " (" + pattern.c3d + ")");
        for (const fs::path& take : found) {
            TakeJob job = pattern;
            job.c3d = take.string();
            job.out = (fs::path(pattern.out) / take.stem()).string();
            jobs.push_back(job);
            entries.push_back("folders[" + std::to_string(i) + "] (" + job.c3d + ")");
        }
    }
    // A folder without a take is a slip (a wrong path, an unmounted disk): named, not skipped.
    const std::string none = " holds no .c3d take";
    if (jobs.empty())
        throw Error(empty.empty() ? file + ": the manifest lists no take"
                                  : joined(empty, "; ") + none);
    for (const std::string& folder : empty)
        std::fprintf(stderr, "warning: %s%s\n", folder.c_str(), none.c_str());
    refuseSharedOutputs(file, jobs, entries);
    return jobs;
}

// "I/N", 1-based: entry k (0-based) belongs to shard k mod N + 1.
std::pair<int, int> parseShard(const std::string& text) {
    int i = 0, n = 0;
    const auto slash = text.find('/');
    if (slash == std::string::npos || !readWholeNumber(text.substr(0, slash), i) ||
        !readWholeNumber(text.substr(slash + 1), n) || n < 1 || i < 1 || i > n)
        throw Error("--shard expects I/N with 1 <= I <= N, got \"" + text + "\"");
    return {i, n};
}

enum class Sidecar { Missing, Complete, Stale };

// One file however it is spelled: a path that is not UTF-8 is recorded as validUtf8 reads it.
// Sidecars written before solve recorded paths in full name them as typed, relative to a folder
// unknown here, and are solved once more: a take is fingerprinted by size and time only, so
// sessA/walk.c3d could pass for sessB/walk.c3d.
bool sameFile(const json& recorded, const std::string& path) {
    return recorded.is_string() && (recorded.get<std::string>() == validUtf8(path) ||
                                    boneless::sameFile(recorded.get<std::string>(), path));
}

// Fingerprints of the files this run has read so far: a library's takes share a few meshes and
// maps, each read once however many takes name it.
using Fingerprints = std::map<std::pair<std::string, bool>, std::string>;

// Why the job's input files are not those its sidecar's fingerprints describe, or "" if they are:
// a map corrected since, a mesh edited, a take recaptured, a glb's texture repainted. A sidecar
// that records none (an older Boneless wrote it) cannot vouch for its inputs either.
std::string changedInputs(const json& recorded, const TakeJob& job, Fingerprints& known) {
    if (!recorded.is_object()) return "its sidecar does not record what its inputs held";
    const bool glb = job.format == exportFormatInfo(ExportFormat::Glb).name;
    // Sidecars written before the glb's materials were fingerprinted: it may hold old ones.
    if (glb && !recorded.value("materials", json()).is_object())
        return "its sidecar does not record what the glb's material files held";
    std::vector<std::string> changed;
    const auto compare = [&](const std::string& path, bool contents, const json& then) {
        auto it = known.find({path, contents});
        if (it == known.end())
            it = known.emplace(std::pair{path, contents}, fileFingerprint(path, contents)).first;
        if (then != it->second) changed.push_back(fs::path(path).filename().string());
    };
    for (const auto& [key, path, contents] :
         {std::tuple{"mesh", &job.mesh, true}, {"c3d", &job.c3d, false}, {"map", &job.map, true}})
        compare(*path, contents, recorded.value(key, json()));
    // The libraries and textures as the sidecar names them: which ones the glb reads can only
    // change with the mesh or a library, whose own fingerprints would differ. A name that is not
    // UTF-8 is recorded as read in Latin-1, names no file, and is solved again each run.
    if (glb)
        for (const auto& [file, then] : recorded.at("materials").items()) compare(file, true, then);
    if (changed.empty()) return "";
    std::string names;
    for (std::size_t i = 0; i < changed.size(); ++i)
        names += (i == 0 ? "" : i + 1 == changed.size() ? " and " : ", ") + changed[i];
    return names + (changed.size() == 1 ? " changed since it was" : " changed since they were") +
           " solved";
}

// The 32-bit unsigned integer at `offset` of `file`, little- or big-endian; nothing when the file
// is shorter.
std::optional<std::uint32_t> headerWord(const fs::path& file, std::streamoff offset, bool big) {
    std::ifstream in(file, std::ios::binary);
    unsigned char b[4];
    if (!in.seekg(offset) || !in.read(reinterpret_cast<char*>(b), 4)) return std::nullopt;
    return big ? std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 |
                     b[3]
               : std::uint32_t(b[3]) << 24 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[1]) << 8 |
                     b[0];
}

// A point count a cache must hold, and who says so: the mesh's vertices, the sidecar's record.
struct PointCount {
    int points;
    std::string said;  // "walker.obj has 3426 vertices", "its sidecar says 3426"
};

// Why `file`, an output of `frames` frames, is not what the export wrote, or "" if it may be: what
// its size and first bytes tell, without reading it (a PC2's or MDD's size is fixed by its point
// and frame counts, a glb's header says its length, an OBJ a solve wrote starts with its line).
// A cache's header must give each of `points`: a PC2 of another mesh is the right size for its
// own header.
std::string outputFault(const fs::path& file, ExportFormat format, int frames,
                        const std::vector<PointCount>& points) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec || size == 0) return "is missing or empty";
    const auto otherPoints = [&](std::uint32_t header) {
        for (const PointCount& p : points)
            if (std::int64_t(header) != p.points)
                return "holds " + std::to_string(header) + " points where " + p.said;
        return std::string();
    };
    const auto need = [&](std::uintmax_t bytes) {
        return bytes == size
                   ? std::string()
                   : "holds " + std::to_string(size) + " bytes where " + plural(frames, "frame") +
                         (frames == 1 ? " needs " : " need ") + std::to_string(bytes);
    };
    switch (format) {
        case ExportFormat::Obj:
            return objWrittenBySolve(file.string())
                       ? ""
                       : "does not start with the \"# Boneless: \" line a solve writes";
        case ExportFormat::Pc2: {  // 32 bytes of header, the point count at 16
            const std::optional<std::uint32_t> points = headerWord(file, 16, false);
            if (!points || size < 32)
                return "holds " + std::to_string(size) + " bytes, less than a PC2 header";
            if (const std::string other = otherPoints(*points); !other.empty()) return other;
            return need(32 + std::uintmax_t(12) * *points * frames);
        }
        case ExportFormat::Mdd: {  // the frame and point counts, a time per frame, the points
            const std::optional<std::uint32_t> points = headerWord(file, 4, true);
            if (!points) return "holds " + std::to_string(size) + " bytes, less than an MDD header";
            if (const std::string other = otherPoints(*points); !other.empty()) return other;
            return need(8 + std::uintmax_t(4) * frames + std::uintmax_t(12) * *points * frames);
        }
        case ExportFormat::Glb: {  // "glTF", the version, the file's length
            const std::optional<std::uint32_t> length = headerWord(file, 8, false);
            if (!length) return "holds " + std::to_string(size) + " bytes, less than a glb header";
            return size >= *length ? ""
                                   : "holds " + std::to_string(size) +
                                         " bytes where its header says " + std::to_string(*length);
        }
    }
    return "";
}

// Why the files a complete sidecar vouches for are not all there as written, or "" if they are:
// an output deleted, cut short or overwritten (a copy, a full disk) since. Named as exportTake
// names them, not as recorded (a name that is not UTF-8 is recorded otherwise): the frames of
// `range`, or the cache or glb, and the calibrated rest when the entry asks for it. A cache holds
// `points` points a frame.
std::string damagedOutputs(const TakeJob& job, const json& range,
                           const std::vector<PointCount>& points) {
    const fs::path sidecar = takeJobSidecar(job), out = sidecar.parent_path();
    const std::string stem = sidecar.stem().string();
    const ExportFormat format = findExportFormat(job.format).value_or(ExportFormat::Obj);
    const int first = range.at(0).get<int>(), end = range.at(1).get<int>();
    std::vector<std::pair<fs::path, ExportFormat>> files;
    if (format == ExportFormat::Obj)
        for (int f = first; f < end; ++f) files.emplace_back(out / objFrameFile(stem, f), format);
    else
        files.emplace_back(out / (stem + exportFormatInfo(format).extension), format);
    if (job.writeCalibratedRest)
        files.emplace_back(out / (stem + "_calibrated_rest.obj"), ExportFormat::Obj);
    std::vector<std::string> bad;
    std::string fault;
    bool gone = true;  // every one missing or empty
    for (const auto& [file, kind] : files)
        if (const std::string why = outputFault(file, kind, end - first, points); !why.empty()) {
            bad.push_back(file.filename().string());
            if (fault.empty()) fault = why;
            gone = gone && why == "is missing or empty";
        }
    if (bad.empty()) return "";
    if (bad.size() == 1) return bad.front() + " " + fault;
    const std::size_t named = std::min<std::size_t>(bad.size(), 3);
    return std::to_string(bad.size()) + " of its files are missing or " +
           (gone ? "empty" : "damaged") + " (" + joined({bad.begin(), bad.begin() + named}) +
           (bad.size() > named ? " and " + std::to_string(bad.size() - named) + " more" : "") + ")";
}

// The vertices of each mesh (and group) this run has read, by its path and group: a cache's point
// count must match them, and a library's takes share a few meshes.
using VertexCounts = std::map<std::pair<std::string, std::string>, int>;

// The point counts the job's cache must hold: its mesh's vertices, and the sidecar's record of
// them when it has one (sidecars before 30 November 2026 have none). None for OBJ frames and glb.
std::vector<PointCount> cachePoints(const TakeJob& job, const json& sidecar, VertexCounts& known) {
    const ExportFormat format = findExportFormat(job.format).value_or(ExportFormat::Obj);
    if (format != ExportFormat::Pc2 && format != ExportFormat::Mdd) return {};
    auto it = known.find({job.mesh, job.group});
    if (it == known.end()) {
        MeshReadOptions options;
        options.group = job.group;
        it = known
                 .emplace(std::pair{job.mesh, job.group},
                          readMesh(job.mesh, options).mesh.vertexCount())
                 .first;
    }
    std::string mesh = fs::path(job.mesh).filename().string();
    if (!job.group.empty()) mesh += " (group " + job.group + ")";
    std::vector<PointCount> points{
        {it->second, mesh + " has " + plural(it->second, "vertex", "vertices")}};
    if (const json v = sidecar.value("vertices", json()); v.is_number_integer())
        points.push_back({v.get<int>(), "its sidecar says " + std::to_string(v.get<int>())});
    return points;
}

// A take is done when its sidecar says it completed from the same sources into the same format,
// over the frames and with the options the manifest asks for now, the files it wrote are still
// there, and its input files are as they were then. Otherwise it is solved again, `why` saying
// why: other frames or options (the manifest changed), an output gone, or other file contents.
Sidecar sidecarState(const TakeJob& job, Fingerprints& known, VertexCounts& meshes,
                     std::string& why) {
    std::ifstream in(takeJobSidecar(job));
    if (!in) return Sidecar::Missing;
    try {
        const json s = json::parse(in);
        // Another program's file of the sidecar's name is no sidecar of a solve to repeat: the
        // solve says it is not replaced unasked ("cannot be read, solving again" said otherwise).
        if (!s.is_object() || s.value("format", json()) != "boneless-solve")
            return Sidecar::Missing;
        const json& src = s.at("source");
        // Said, as every reason to solve again is: a take re-solved in silence looks like a bug.
        const auto other = [](const char* what, const json& recorded) {
            const std::string named = recorded.is_string() ? recorded.get<std::string>() : "";
            return std::string("its sidecar is from another ") + what + " (" +
                   (named.empty() ? "none" : named) + ")";
        };
        if (!s.at("complete").get<bool>())
            why = "its sidecar says its run did not finish";
        else if (s.at("output") != job.format)
            why = other("format", s.at("output"));
        else if (!sameFile(src.at("mesh"), job.mesh))
            why = other("mesh", src.at("mesh"));
        else if (src.at("group") != validUtf8(job.group))
            why = other("group", src.at("group"));
        else if (!sameFile(src.at("c3d"), job.c3d))
            why = other("take", src.at("c3d"));
        else if (!sameFile(src.at("map"), job.map))
            why = other("map", src.at("map"));
        if (!why.empty()) return Sidecar::Stale;
        TakeSolveOptions options;
        fromJson(job.options, options, "options");
        const FrameRange range = parseFrameRange(job.frames);
        const int frames = static_cast<int>(C3dFrameReader(job.c3d).frameCount());
        const int end = range.end < 0 ? frames : std::min(range.end, frames);
        const bool sameFrames = s.at("frame_range") == json::array({range.first, end});
        // Every sidecar of a calibrated take has "calibrated_rest", null when none was written.
        const bool sameRest = !job.writeCalibratedRest ||
                              s.at("calibration").value("calibrated_rest", json()).is_string();
        // Sidecars from before mesh_up solved with the up guessed, as "auto" does, and those from
        // before take_units in the file's units, as "file" does: without this, every take of a
        // library was solved again "from other options". (Other keys missing from older
        // sidecars had other defaults then, and stay a difference.)
        json recorded = s.at("options");
        if (recorded.is_object() && !recorded.contains("mesh_up")) recorded["mesh_up"] = "auto";
        if (recorded.is_object() && !recorded.contains("take_units"))
            recorded["take_units"] = "file";
        // Each difference named: a library solved again after an edit of its defaults said only
        // "other frames or options" of every take, which left the user to guess what changed.
        std::vector<std::string> changed;
        const auto asRange = [](const json& r) {
            return r.is_array() && r.size() == 2 ? r[0].dump() + ":" + r[1].dump() : r.dump();
        };
        if (!sameFrames)
            changed.push_back("frames " + asRange(s.at("frame_range")) + ", now " +
                              std::to_string(range.first) + ":" + std::to_string(end));
        if (!sameRest) changed.push_back("write_calibrated_rest false, now true");
        const json asked = toJson(options);
        for (const auto& [key, value] : asked.items())
            if (!recorded.contains(key) || recorded.at(key) != value)
                changed.push_back(key + " " +
                                  (recorded.contains(key) ? recorded.at(key).dump() : "unset") +
                                  ", now " + value.dump());
        for (const auto& [key, value] : recorded.items())
            if (!asked.contains(key)) changed.push_back(key + " " + value.dump() + ", now unset");
        if (!changed.empty())
            why = "its sidecar is from other frames or options (" + joined(changed, "; ") + ")";
        if (why.empty())
            why = damagedOutputs(job, s.at("frame_range"), cachePoints(job, s, meshes));
        if (why.empty()) why = changedInputs(s.value("source_fingerprints", json()), job, known);
        return why.empty() ? Sidecar::Complete : Sidecar::Stale;
    } catch (const json::parse_error&) {
        return Sidecar::Missing;  // no JSON: the solve says whose it is
    } catch (const json::exception&) {
        why = "its sidecar cannot be read (from an older Boneless)";
        return Sidecar::Stale;
    } catch (const Error&) {
        return Sidecar::Missing;  // the take is unreadable now: solving says why
    }
}

void run(const BatchArgs& args) {
    const auto [shard, shards] = parseShard(args.shard);
    // For the whole run: a signal while a take's files were read, or between takes, killed it
    // with no last line.
    const StopSignals stop;
    std::vector<TakeJob> jobs = readManifest(args.manifest);
    for (TakeJob& job : jobs) {
        job.force = args.force;
        job.replacesOtherTakes = true;  // readManifest refuses two entries into one out
    }
    int mine = 0, solved = 0, skipped = 0, failed = 0;
    std::vector<std::string> failedTakes;  // named on the last line, so no one searches the log
    for (std::size_t k = 0; k < jobs.size(); ++k)
        if (static_cast<int>(k % shards) == shard - 1) ++mine;
    int done = 0;
    std::set<std::string> notedMeshes;  // mesh, group and note
    std::set<std::string> notedMaps;
    Fingerprints fingerprints;
    VertexCounts vertexCounts;
    // The last line sums up however the run ends: a log cut by a time limit said nothing of the
    // takes solved, skipped or failed before the stop.
    const auto sumUpStopped = [&](int interrupted) {
        std::printf(
            "batch: %d of %zu takes in shard %d/%d: %d solved, %d skipped, %d failed, "
            "%d interrupted, %d not reached\n",
            mine, jobs.size(), shard, shards, solved, skipped, failed, interrupted, mine - done);
        std::fflush(stdout);
    };
    for (std::size_t k = 0; k < jobs.size(); ++k) {
        if (static_cast<int>(k % shards) != shard - 1) continue;
        if (StopSignals::received()) {  // between takes: none begun
            sumUpStopped(0);
            StopSignals::throwIfReceived("between takes: the line above says what was done");
        }
        const TakeJob& job = jobs[k];
        std::printf("[%d/%d] %s -> %s: ", ++done, mine, job.c3d.c_str(), job.out.c_str());
        std::string why;
        const Sidecar sidecar = sidecarState(job, fingerprints, vertexCounts, why);
        if (sidecar == Sidecar::Complete) {
            std::printf("skipped (its sidecar says it is complete)\n");
            ++skipped;
            continue;
        }
        if (sidecar == Sidecar::Stale) std::printf("%s, solving again: ", why.c_str());
        std::fflush(stdout);
        const auto start = std::chrono::steady_clock::now();
        std::vector<std::string> meshWarnings;  // filled once the mesh is read
        std::vector<std::string> takeWarnings;  // and the take's once it is opened
        std::vector<std::string> mapWarnings;   // and the map's once it is read
        std::vector<std::string> takeNotes;     // a note on its "frames", on earlier exports
        // Under the take's line, solved or not: a truncated take solves the frames it holds.
        // Every note and warning on stderr, each take's line (its result) on stdout: the Unix
        // rule, so `batch m.json > results.txt` keeps a take's diagnostics in one place.
        const auto underTheLine = [&] {
            std::fflush(stdout);
            for (const std::string& w : takeWarnings)
                std::fprintf(stderr, "  warning: %s: %s\n", job.c3d.c_str(), w.c_str());
            // As solve says it, a note: "frames" 2:100 is cut to the take, not a fault of it.
            for (const std::string& n : takeNotes) std::fprintf(stderr, "  note: %s\n", n.c_str());
            // Said once per map, as the mesh's notes: a library's takes share a few maps.
            if (!mapWarnings.empty() && notedMaps.insert(job.map).second)
                for (const std::string& w : mapWarnings)
                    std::fprintf(stderr, "  warning: %s\n", w.c_str());
            // A library of takes shares a few meshes: what one lacks is said once, solved or not.
            // Each note once, not each mesh's: a second map leaves other parts without a marker.
            for (const std::string& w : meshWarnings)
                if (notedMeshes.insert(job.mesh + "\n" + job.group + "\n" + w).second)
                    std::fprintf(stderr, "  note: %s: %s\n", job.mesh.c_str(), w.c_str());
            std::fflush(stdout);
        };
        try {
            const ExportResult r =
                runTakeJob(job, true, &meshWarnings, &takeWarnings, &mapWarnings, &takeNotes);
            std::printf(
                "%s in %.1f s\n", plural(r.framesWritten, "frame").c_str(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
            ++solved;
        } catch (const TakeJobInterrupted& e) {
            std::printf("interrupted\n");
            underTheLine();  // an earlier run's frames past the stop, named as after a finished one
            sumUpStopped(1);
            throw;
        } catch (const Error& e) {
            std::printf("FAILED: %s\n", e.what());
            ++failed;
            failedTakes.push_back(job.c3d);
        } catch (const std::exception& e) {
            // Whatever went wrong with one take (a bug included), the others are still to solve.
            std::printf("FAILED: internal error: %s\n", e.what());
            ++failed;
            failedTakes.push_back(job.c3d);
        }
        underTheLine();
    }
    std::printf("batch: %d of %zu takes in shard %d/%d: %d solved, %d skipped, %d failed\n", mine,
                jobs.size(), shard, shards, solved, skipped, failed);
    std::fflush(stdout);
    if (failed) {
        // A library's worth would drown the line: the first ten, then how many more.
        constexpr std::size_t kNamed = 10;
        std::vector<std::string> named(failedTakes.begin(),
                                       failedTakes.begin() + std::min(kNamed, failedTakes.size()));
        if (failedTakes.size() > kNamed)
            named.push_back("and " + std::to_string(failedTakes.size() - kNamed) + " more");
        throw Error(std::to_string(failed) + " of " + std::to_string(mine) +
                    " takes failed: " + joined(named));
    }
}

}  // namespace

void registerBatchCommand(CLI::App& app) {
    auto args = std::make_shared<BatchArgs>();
    CLI::App* cmd = app.add_subcommand(
        "batch", "Solve every take a manifest lists, skipping those already complete");
    cmd->add_option("MANIFEST", args->manifest, "Batch manifest (JSON; see docs/batch.md)")
        ->check(aPath())
        ->required();
    cmd->add_option("--shard", args->shard,
                    "I/N: only every N-th entry, starting at the I-th (for job arrays)");
    cmd->add_flag("--force", args->force,
                  "Let a take replace files in its \"out\" of its outputs' names that no Boneless "
                  "export wrote (another tool's OBJ frames); complete takes are still skipped");
    cmd->callback([args] { run(*args); });
}
