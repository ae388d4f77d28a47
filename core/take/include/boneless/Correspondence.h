#pragma once

#include <string>
#include <vector>

namespace boneless {

struct C3dTake;

// One marker of a take mapped to one mesh vertex.
struct MarkerMapping {
    std::string label;  // matched against a take's labels ignoring subject prefixes
    int vertex = -1;    // 0-based, in the mesh file's vertex order (an OBJ group: its own order)
    double offsetMm = 0.0;  // how far the marker sits off the skin, along the normal
    std::string extraJson;  // keys this version does not know, kept on rewrite ("{}" if none)
};

// The user's marker-to-vertex map, stored as a versioned JSON file:
//   {"format": "boneless-correspondence", "version": 1,
//    "mesh": {"file": "body.obj", "vertices": 13380},
//    "markers": [{"label": "LFHD", "vertex": 1234, "offset_mm": 9.5}, ...]}
// Keys this version does not know, at any level, survive a read and a rewrite.
class Correspondence {
  public:
    std::string meshFile;
    int meshVertices = 0;
    std::vector<MarkerMapping> markers;

    // Throws Error naming the file and the entry for malformed JSON, a wrong format or version,
    // missing keys, negative ids, duplicate labels or duplicate vertices.
    static Correspondence read(const std::string& path);
    // The same from JSON text (a project file embeds it); `source` names it in messages.
    static Correspondence fromJson(const std::string& text, const std::string& source);
    // Atomic (temporary file, then rename).
    void write(const std::string& path) const;
    std::string toJson() const;

    // Checks against a mesh: vertex count as recorded, every id in range. Throws Error.
    void checkMesh(int vertexCount, const std::string& meshPath) const;
    // The take's point index for each marker, in order; throws Error listing unknown labels.
    std::vector<std::size_t> resolve(const C3dTake& take) const;

    const MarkerMapping* find(const std::string& label) const;

  private:
    std::string extraJson_ = "{}";  // top-level and "mesh" keys this version does not know
    std::string source_;            // the file it was read from, for messages
};

}  // namespace boneless
