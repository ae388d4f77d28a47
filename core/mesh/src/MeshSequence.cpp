#include "boneless/MeshSequence.h"

#include <algorithm>
#include <filesystem>
#include <utility>
#include <vector>

#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/Text.h"

namespace boneless {

namespace {

// Polygons are triangulated by their posed shape, so frames of one quad mesh may split a quad
// differently: the file's own faces are what must match.
bool sameFaces(const TriMesh& a, const TriMesh& b) {
    if (a.sourceFaces && b.sourceFaces)
        return a.sourceFaces->start == b.sourceFaces->start &&
               a.sourceFaces->corners == b.sourceFaces->corners;
    return !a.sourceFaces && !b.sourceFaces && a.F == b.F;
}

// A file name's frame key: its digit runs as numbers, and the text around them as its pattern
// ("frame_#.obj"), so that frame_2.obj comes before frame_10.obj.
struct FrameName {
    std::string pattern;
    std::vector<std::string> numbers;  // leading zeros stripped, compared by length then digits
};

FrameName frameName(const std::string& name) {
    FrameName key;
    for (size_t i = 0; i < name.size();) {
        if (isAsciiDigit(name[i])) {
            size_t j = i;
            while (j < name.size() && isAsciiDigit(name[j])) ++j;
            const size_t nonZero = std::min(name.find_first_not_of('0', i), j);
            key.numbers.push_back(name.substr(nonZero, j - nonZero));
            key.pattern += '#';
            i = j;
        } else {
            key.pattern += name[i++];
        }
    }
    return key;
}

bool numbersBefore(const std::vector<std::string>& a, const std::vector<std::string>& b) {
    return std::lexicographical_compare(
        a.begin(), a.end(), b.begin(), b.end(), [](const std::string& x, const std::string& y) {
            return x.size() != y.size() ? x.size() < y.size() : x < y;
        });
}

// Sorts `files` by the numbers in their names. Names of different patterns, or two carrying the
// same numbers, give no evident order: refused, naming two of them, rather than guessed.
void sortFrames(const std::string& directory, std::vector<std::string>& files) {
    namespace fs = std::filesystem;
    std::sort(files.begin(), files.end());  // so that the two named are always the same
    std::vector<std::pair<FrameName, std::string>> keyed;
    for (const auto& file : files) keyed.emplace_back(frameName(fs::path(file).filename()), file);
    const auto why = [&](const std::string& a, const std::string& b, const std::string& what) {
        return MeshError(directory,
                         "no frame order in the file names: " + fs::path(a).filename().string() +
                             " and " + fs::path(b).filename().string() + " " + what +
                             " (name the frames alike, each with its number, e.g. "
                             "frame_1.obj … frame_12.obj)");
    };
    for (const auto& [key, file] : keyed)
        if (key.pattern != keyed.front().first.pattern)
            throw why(keyed.front().second, file, "are named differently");
    std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
        return numbersBefore(a.first.numbers, b.first.numbers);
    });
    for (size_t i = 1; i < keyed.size(); ++i)
        if (!numbersBefore(keyed[i - 1].first.numbers, keyed[i].first.numbers))
            throw why(keyed[i - 1].second, keyed[i].second, "carry the same frame number");
    for (size_t i = 0; i < keyed.size(); ++i) files[i] = keyed[i].second;
}

}  // namespace

std::vector<std::string> meshSequenceFiles(const std::string& directory) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_directory(directory, ec))
        throw MeshError(directory, "not a directory of mesh frames");
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(directory)) {
        const std::string ext = asciiLower(entry.path().extension().string());
        if (entry.is_regular_file() && ext == ".obj") files.push_back(entry.path().string());
    }
    if (files.empty()) throw MeshError(directory, "contains no .obj frames");
    sortFrames(directory, files);
    return files;
}

MeshSequence readMeshSequence(const std::string& directory,
                              const std::function<bool(int frame)>& wanted) {
    MeshSequence sequence;
    sequence.files = meshSequenceFiles(directory);
    for (const auto& file : sequence.files) {
        const int frame = static_cast<int>(sequence.frames.size());
        if (frame > 0 && wanted && !wanted(frame)) {
            sequence.frames.emplace_back();  // not read
            continue;
        }
        TriMesh mesh = readMesh(file).mesh;
        if (sequence.frames.empty()) {
            sequence.rest = mesh;
        } else if (mesh.vertexCount() != sequence.rest.vertexCount()) {
            throw MeshError(file, "has " + std::to_string(mesh.vertexCount()) +
                                      " vertices, the first frame " +
                                      std::to_string(sequence.rest.vertexCount()));
        } else if (!sameFaces(mesh, sequence.rest)) {
            throw MeshError(file,
                            "has other faces than the first frame (" + sequence.files[0] + ")");
        }
        sequence.frames.push_back(std::move(mesh.V));
    }
    return sequence;
}

}  // namespace boneless
