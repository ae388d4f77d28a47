#pragma once

#include <array>
#include <string>
#include <vector>

namespace boneless {

struct C3dTake;
struct TriMesh;

// One marker of a take mapped to a point of the mesh surface: a vertex, or (version 2) a point
// of a face, of which `vertex` is then the corner nearest the point.
struct MarkerMapping {
    std::string label;  // matched against a take's labels ignoring subject prefixes
    int vertex = -1;    // 0-based, in the mesh file's vertex order (an OBJ group: its own order)
    double offsetMm = 0.0;  // how far the marker sits off the skin, along the normal
    std::string extraJson;  // keys this version does not know, kept on rewrite ("{}" if none)
    // 0-based in the triangulated mesh (polygons split as the reader splits them), or −1: the
    // marker sits on `vertex` itself.
    int face = -1;
    std::array<double, 3> barycentric{1.0, 0.0, 0.0};  // of the face's corners, summing to 1
};

// The user's marker-to-vertex map, stored as a versioned JSON file:
//   {"format": "boneless-correspondence", "version": 1,
//    "mesh": {"file": "body.obj", "group": "body", "vertices": 13380},
//    "markers": [{"label": "LFHD", "vertex": 1234, "offset_mm": 9.5}, ...]}
// Version 2 lets an entry name a point of a face: "face": 2310, "barycentric": [0.6, 0.3, 0.1]
// ("vertex" stays, the corner nearest the point). A map without such a point is written as
// version 1, so older readers keep reading it. Keys this version does not know, at any level,
// survive a read and a rewrite.
class Correspondence {
  public:
    std::string meshFile;
    std::string meshGroup;  // the OBJ group it was made on; "" = the whole file, or not recorded
    int meshVertices = 0;
    std::vector<MarkerMapping> markers;
    // What the file says that this read leaves unused, for the caller to say (not written back):
    // a version 1 file's entries whose "face" is a face number, which version 2 alone reads
    // ("map.json: marker T10 has \"face\": 12, which only \"version\": 2 reads; ...").
    std::vector<std::string> warnings;

    // Markers sit 0 to 30 mm off the skin (a sphere on its base, a bulky suit); a little below
    // zero fits a mesh whose surface is clothing, and 200 mm leaves room for a standoff or a
    // headband. Beyond, the value is a slip (metres, a sign), which the solve would only report
    // as a marker the mesh cannot reach.
    static constexpr double kMinOffsetMm = -50.0, kMaxOffsetMm = 200.0;

    // Throws Error naming the file and the entry for malformed JSON, a wrong format or version,
    // missing keys, negative ids, duplicate labels or duplicate vertices, or an offset_mm outside
    // -50 to 200.
    static Correspondence read(const std::string& path);
    // The same from JSON text (a project file embeds it); `source` names it in messages.
    static Correspondence fromJson(const std::string& text, const std::string& source);
    // Atomic (temporary file, then rename).
    void write(const std::string& path) const;
    std::string toJson() const;

    // Checks against a mesh: vertex count as recorded, every id in range, each face point's
    // vertex one of its corners (faces: the triangulated mesh's, when given). Throws Error.
    void checkMesh(int vertexCount, const std::string& meshPath,
                   const TriMesh* mesh = nullptr) const;
    // The take's point index for each marker, in order; throws Error listing unknown labels, or
    // naming a label whose point is no marker (an angle, a force, a virtual point).
    std::vector<std::size_t> resolve(const C3dTake& take) const;
    // The subject prefixes of the points resolve finds ("other" of a take two actors wear), each
    // once, in the order of their first points; empty when their labels carry none. The sidecar
    // records them: another actor's solve of the same take is not the one it replaces.
    std::vector<std::string> subjects(const C3dTake& take) const;
    // Why `label` names no one marker of `take`, in resolve's words without the map's file name:
    // two points share its full label, two subjects wear it ("marker LFHD is worn by more than
    // one subject in pair.c3d (A:LFHD, B:LFHD); write the subject prefix"), or it names a model
    // output. "" when it names one marker, or no point (resolve lists those together).
    static std::string labelProblem(const C3dTake& take, const std::string& label);

    const MarkerMapping* find(const std::string& label) const;
    const std::string& source() const { return source_; }  // the file read, or "" if none

  private:
    std::string extraJson_ = "{}";  // top-level and "mesh" keys this version does not know
    std::string source_;            // the file it was read from, for messages
};

}  // namespace boneless
