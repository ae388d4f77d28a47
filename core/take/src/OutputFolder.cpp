// The output folder of an export: which files are whose, who is writing there, what was written.
#include "boneless/OutputFolder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "OutputGuards.h"
#include "boneless/C3dParameters.h"
#include "boneless/Error.h"
#include "boneless/SpoolFile.h"
#include "boneless/Text.h"

namespace boneless {

using nlohmann::json;
namespace fs = std::filesystem;

std::string exportStem(const ExportRequest& request) {
    if (request.group.empty()) return fs::path(request.meshPath).stem().string();
    // A group is a name, not a path: Blender's "Body.001" and "Body.002" keep their dots (a stem
    // made both "Body"), and a separator cannot lead the files out of the folder. Windows' other
    // reserved characters go too: Maya's "pCube1|body" made files Windows cannot hold.
    std::string stem = request.group;
    for (char& c : stem)
        if (std::strchr("/\\:|<>\"?*", c) || static_cast<unsigned char>(c) < 32) c = '_';
    return stem == "." || stem == ".." ? std::string(stem.size(), '_') : stem;
}

std::string objFrameFile(const std::string& stem, int frame) {
    char number[16];
    std::snprintf(number, sizeof number, "_%04d.obj", frame);
    return stem + number;
}

namespace {

// The take frame whose OBJ (objFrameFile) `name` is, if it is one of `stem`'s.
std::optional<int> objFrameOf(const fs::path& name, const std::string& stem) {
    const std::string file = name.filename().string();
    if (file.size() < stem.size() + 9 || file.compare(0, stem.size() + 1, stem + "_") != 0 ||
        name.extension() != ".obj")
        return std::nullopt;
    const std::string digits = file.substr(stem.size() + 1, file.size() - stem.size() - 5);
    // At least the four digits objFrameFile writes; more than an int holds is no frame.
    if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos)
        return std::nullopt;
    return std::stoi(digits);
}

}  // namespace

std::vector<int> objFramesIn(const std::string& outDir, const std::string& stem) {
    std::vector<int> frames;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(outDir, ec))
        if (const std::optional<int> frame = objFrameOf(entry.path(), stem))
            frames.push_back(*frame);
    return frames;
}

std::vector<std::string> exportFilesIn(const std::string& outDir, const std::string& stem) {
    std::vector<std::string> names{stem + ".json", stem + "_calibrated_rest.obj"};
    for (const ExportFormatInfo& f : exportFormats())
        if (f.format != ExportFormat::Obj) names.push_back(stem + f.extension);
    std::error_code ec;
    names.erase(std::remove_if(names.begin(), names.end(),
                               [&](const std::string& n) {
                                   return !fs::is_regular_file(fs::path(outDir) / n, ec);
                               }),
                names.end());
    std::vector<int> frames = objFramesIn(outDir, stem);
    std::sort(frames.begin(), frames.end());
    for (int frame : frames) names.push_back(objFrameFile(stem, frame));
    return names;
}

bool objWrittenBySolve(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line(12, '\0');
    in.read(line.data(), static_cast<std::streamsize>(line.size()));
    return in && line == "# Boneless: ";
}

namespace {

// What `stem`'s Boneless sidecar in `outDir` says it wrote.
struct SidecarOutputs {
    std::string output;      // "pc2"; "" if it records none
    int first = 0, end = 0;  // its OBJ frames, [first, end)
    std::string rest;        // its calibrated rest's file name, "" if none
};

// What `stem`'s sidecar in `outDir` says it wrote, or nothing when there is no sidecar, or what is
// there is no Boneless sidecar.
std::optional<SidecarOutputs> sidecarOutputs(const fs::path& outDir, const std::string& stem) {
    std::ifstream in(outDir / (stem + ".json"));
    if (!in) return std::nullopt;
    try {
        const json s = json::parse(in);
        if (!s.is_object() || s.value("format", json()) != "boneless-solve") return std::nullopt;
        SidecarOutputs o;
        const json output = s.value("output", json());
        if (output.is_string()) o.output = output.get<std::string>();
        const json range = s.value("frame_range", json());
        if (range.is_array() && range.size() == 2 && range[0].is_number_integer() &&
            range[1].is_number_integer()) {
            o.first = range[0].get<int>();
            o.end = range[1].get<int>();
        }
        const json rest = s.value("calibration", json::object()).value("calibrated_rest", json());
        if (rest.is_string()) o.rest = rest.get<std::string>();
        return o;
    } catch (const json::exception&) {
    }
    return std::nullopt;
}

}  // namespace

namespace {

// Whether `name`, one of exportFilesIn's, is an export's by what the folder shows: `sidecar` (its
// Boneless sidecar, if any) names it, however it reads now (a frame or a rest cut short or
// overwritten since is the tool's own to replace), or it is an OBJ starting with the line a solve
// writes.
bool writtenByExport(const fs::path& out, const std::string& stem, const std::string& name,
                     const std::optional<SidecarOutputs>& sidecar) {
    if (name == stem + ".json") return sidecar.has_value();
    const fs::path path = out / name;
    if (name == stem + "_calibrated_rest.obj")
        return (sidecar && name == sidecar->rest) || objWrittenBySolve(path.string());
    if (const std::optional<int> frame = objFrameOf(path, stem))
        return (sidecar && sidecar->output == exportFormatInfo(ExportFormat::Obj).name &&
                *frame >= sidecar->first && *frame < sidecar->end) ||
               objWrittenBySolve(path.string());
    for (const ExportFormatInfo& f : exportFormats())
        if (f.format != ExportFormat::Obj && name == stem + f.extension)
            return sidecar && sidecar->output == f.name;
    return false;
}

}  // namespace

std::vector<std::string> exportFilesWrittenIn(const std::string& outDir, const std::string& stem) {
    const std::optional<SidecarOutputs> sidecar = sidecarOutputs(outDir, stem);
    std::vector<std::string> names = exportFilesIn(outDir, stem);
    names.erase(std::remove_if(names.begin(), names.end(),
                               [&](const std::string& name) {
                                   return !writtenByExport(outDir, stem, name, sidecar);
                               }),
                names.end());
    return names;
}

std::vector<std::string> filesNoExportWrote(const ExportRequest& request, int end) {
    const fs::path out(request.outDir);
    const std::string stem = exportStem(request);
    std::error_code ec;
    if (!fs::is_directory(out, ec)) return {};
    const std::optional<SidecarOutputs> sidecar = sidecarOutputs(out, stem);
    std::vector<std::string> foreign;
    for (const std::string& name : exportFilesIn(request.outDir, stem)) {
        const fs::path path = out / name;
        // An input there (a map kept as <stem>.json) is exportTake's to refuse, naming both.
        if (sameFile(path.string(), request.meshPath) || sameFile(path.string(), request.c3dPath) ||
            sameFile(path.string(), request.mapPath) || writtenByExport(out, stem, name, sidecar))
            continue;
        const std::optional<int> frame = objFrameOf(path, stem);
        const bool replaced =
            name == stem + ".json" ||
            (name == stem + "_calibrated_rest.obj" && request.writeCalibratedRest) ||
            (frame && request.format == ExportFormat::Obj && *frame >= request.first &&
             *frame < end) ||
            name == stem + exportFormatInfo(request.format).extension;
        if (replaced) foreign.push_back(name);
    }
    return foreign;
}

bool sameFile(const std::string& a, const std::string& b) {
    std::error_code ec;
    if (fs::equivalent(a, b, ec)) return true;
    std::error_code ea, eb;
    const fs::path x = fs::weakly_canonical(a, ea), y = fs::weakly_canonical(b, eb);
    return !ea && !eb && x == y;
}

namespace {

// Whether a sidecar's "subjects" name the same actors as `now`, as labels compare (case aside).
bool sameSubjects(const json& earlier, const std::vector<std::string>& now) {
    if (!earlier.is_array() || earlier.size() != now.size()) return false;
    for (const json& s : earlier)
        if (!s.is_string() || std::none_of(now.begin(), now.end(), [&](const std::string& n) {
                return c3dNameEquals(s.get<std::string>(), n);
            }))
            return false;
    return true;
}

}  // namespace

std::string subjectsText(const std::vector<std::string>& subjects) {
    return (subjects.size() == 1 ? "subject " : "subjects ") + joined(subjects);
}

std::string OtherSolve::whose() const {
    return sameTake ? subjectsText(subjects) + " of " + c3d : c3d + ", another take";
}

std::optional<OtherSolve> otherSolveIn(const ExportRequest& request,
                                       const std::vector<std::string>& subjects) {
    const fs::path sidecar = fs::path(request.outDir) / (exportStem(request) + ".json");
    std::ifstream in(sidecar);
    if (!in) return std::nullopt;
    // No Boneless sidecar, or one damaged (a "source" that is no object): filesNoExportWrote
    // names the first, and the app's Export must not end on the second.
    try {
        const json s = json::parse(in);
        if (!s.is_object() || s.value("format", json()) != "boneless-solve") return std::nullopt;
        const json source = s.value("source", json::object());
        const json c3d = source.is_object() ? source.value("c3d", json()) : json();
        if (!c3d.is_string()) return std::nullopt;
        OtherSolve other;
        other.sidecar = sidecar.string();
        other.c3d = c3d.get<std::string>();
        other.sameTake = sameFile(other.c3d, request.c3dPath);
        if (!other.sameTake) return other;
        const json earlier = s.value("subjects", json());
        if (!earlier.is_array() || earlier.empty() || subjects.empty() ||
            sameSubjects(earlier, subjects))
            return std::nullopt;
        for (const json& e : earlier)
            other.subjects.push_back(e.is_string() ? e.get<std::string>() : e.dump());
        return other;
    } catch (const json::exception&) {
        return std::nullopt;
    }
}

namespace {

// Whether `name` is one of the files an export of `stem` writes (its temporaries aside).
bool isOutputOf(const std::string& name, const std::string& stem) {
    if (name == stem + ".json" || name == stem + "_calibrated_rest.obj" || objFrameOf(name, stem))
        return true;
    // Not <stem>.obj: an OBJ export writes frames, and that name is the mesh's (the demo's).
    for (const ExportFormatInfo& f : exportFormats())
        if (f.format != ExportFormat::Obj && name == stem + f.extension) return true;
    return false;
}

}  // namespace

OutputLock::OutputLock(const ExportRequest& request) : outDir_(request.outDir) {
    std::error_code ec;
    // The first missing folder of the path, so that all it made can go again.
    for (fs::path p = fs::path(outDir_).lexically_normal(); !p.empty() && !fs::exists(p, ec);
         p = p.parent_path()) {
        made_ = p;
        if (p == p.parent_path()) break;
    }
    fs::create_directories(outDir_, ec);
    if (ec) throw Error(outDir_ + ": cannot create the folder (" + ec.message() + ")");
    const std::string stem = exportStem(request);
    path_ = (fs::path(outDir_) / ("." + stem + ".lock")).string();
    for (;;) {
        fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        // A folder that takes no new file fails as the outputs are written, naming them.
        if (fd_ < 0) return;
        if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
            const int error = errno;
            ::close(fd_);
            fd_ = -1;
            if (error == EWOULDBLOCK)
                throw Error((fs::path(outDir_) / (stem + ".json")).string() +
                            ": another run is solving into this take's files now; nothing "
                            "was written: let it finish (a run after it skips or solves the "
                            "take as its sidecar says), or solve into another folder");
            return;  // a file system without locks: solved as before
        }
        // The holder before us removes the file as it lets go: a lock on that removed file
        // would exclude no one, so lock the file of that name now.
        struct stat held = {};
        struct stat named = {};
        if (::fstat(fd_, &held) == 0 && ::stat(path_.c_str(), &named) == 0 &&
            held.st_dev == named.st_dev && held.st_ino == named.st_ino)
            break;
        ::close(fd_);
    }
    // Held, so no other run writes this take's outputs now: the temporaries of gone writers
    // (kill -9 of a pc2 run leaves its cache of hundreds of MB) were removed only when that
    // very output was written again, and a take solved again in another format kept them.
    removeStaleTemporariesIn(outDir_,
                             [&](const std::string& output) { return isOutputOf(output, stem); });
}

OutputLock::~OutputLock() {
    if (fd_ >= 0) {
        // While still held: a run that opens it now finds it locked, or once we let go,
        // removed.
        ::unlink(path_.c_str());
        ::close(fd_);
    }
    // Only folders still empty go: anything a solve wrote keeps them.
    std::error_code ec;
    if (!made_.empty())
        for (fs::path p = fs::path(outDir_).lexically_normal(); fs::remove(p, ec) && p != made_;
             p = p.parent_path()) {
        }
}

// A file written over an input would destroy it: the map clob/walker.json beside clob/walker.obj
// was replaced by the sidecar of a solve into clob. `frames`: the take's frame count.
void refuseOutputsOverInputs(const ExportRequest& request, int frames) {
    const fs::path out(request.outDir);
    const std::string stem = exportStem(request);
    const int end = request.end < 0 ? frames : std::min(request.end, frames);
    for (const auto& [input, path] :
         {std::pair<const char*, const std::string*>{"mesh", &request.meshPath},
          {"take", &request.c3dPath},
          {"map", &request.mapPath}}) {
        if (path->empty()) continue;  // the app's map may not be saved anywhere yet
        std::vector<std::pair<std::string, fs::path>> outputs = {
            {"sidecar", out / (stem + ".json")}};
        if (request.format != ExportFormat::Obj)
            outputs.push_back({std::string(exportFormatInfo(request.format).name) + " file",
                               out / (stem + exportFormatInfo(request.format).extension)});
        else if (const std::optional<int> f = objFrameOf(*path, stem);
                 f && *f >= request.first && *f < end)
            outputs.push_back({"OBJ frame", out / objFrameFile(stem, *f)});
        if (request.writeCalibratedRest)
            outputs.push_back({"calibrated rest", out / (stem + "_calibrated_rest.obj")});
        for (const auto& [what, output] : outputs)
            if (sameFile(output.string(), *path))
                throw Error(output.string() + ": the " + what +
                            " this solve writes would replace the " + input + " " + *path +
                            "; write to another output folder");
    }
}

// Removes the files a failed take wrote (its OBJ frames, its calibrated rest: "" for none) and
// says so, for the take's error: "the 9 OBJ frames this run wrote were removed", or "".
std::string removeWritten(const std::vector<fs::path>& frames, const fs::path& rest) {
    std::error_code ec;
    for (const fs::path& file : frames) fs::remove(file, ec);
    if (!rest.empty()) fs::remove(rest, ec);
    std::vector<std::string> what;
    if (!frames.empty()) what.push_back("the " + plural(long(frames.size()), "OBJ frame"));
    if (!rest.empty()) what.push_back("the calibrated rest");
    if (what.empty()) return "";
    const bool one = frames.size() + (rest.empty() ? 0 : 1) == 1;
    return joined(what, " and ") + " this run wrote " + (one ? "was" : "were") + " removed";
}

std::string fileFingerprint(const std::string& path, bool contents) {
    std::error_code ec;
    const std::uintmax_t bytes = fs::file_size(path, ec);
    if (ec) return "unreadable";
    if (!contents) {
        // stat's time, not filesystem's: C++17 cannot say a file_time_type in calendar time.
        struct stat st {};
        if (::stat(path.c_str(), &st) != 0) return "unreadable";
        std::tm utc{};
        gmtime_r(&st.st_mtim.tv_sec, &utc);
        char modified[64];
        std::strftime(modified, sizeof modified, "%Y-%m-%d %H:%M:%S", &utc);
        char nanoseconds[16];
        std::snprintf(nanoseconds, sizeof nanoseconds, ".%09ld", st.st_mtim.tv_nsec);
        return std::to_string(bytes) + " bytes, modified " + modified + nanoseconds + " UTC";
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) return "unreadable";
    std::uint64_t hash = 14695981039346656037ull;  // FNV-1a: a few ms for a mesh of megabytes
    std::vector<char> buffer(1 << 16);
    while (in.read(buffer.data(), buffer.size()) || in.gcount() > 0) {
        const std::streamsize got = in.gcount();
        for (std::streamsize i = 0; i < got; ++i) {
            hash ^= static_cast<unsigned char>(buffer[i]);
            hash *= 1099511628211ull;
        }
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
    return std::to_string(bytes) + " bytes, FNV-1a " + hex;
}

}  // namespace boneless
