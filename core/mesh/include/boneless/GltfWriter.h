#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// Streams frames into a glTF 2.0 binary (.glb): the rest mesh (positions, area-weighted vertex
// normals and triangles; one glTF vertex per mesh vertex in the mesh's order, so importers keep the
// vertex count and order, unless the mesh's sourceFaces carry texture coordinates: then TEXCOORD_0
// too, and a vertex on a UV seam is one glTF vertex per side of it, as glTF has one coordinate per
// vertex), one morph target per frame holding that frame's position and normal offsets from the
// rest pose, and an animation on the morph weights keyed at each frame's time in the take (LINEAR:
// frame k has weight 1 at its time, and playback between two frames blends them). The weight keys
// are dense (frames² floats), as Unity's glTFast reads no sparse accessor; they bound a .glb to
// about 32,700 frames (4 GB), fewer on a larger mesh (checkGlbFits). An OBJ's materials become one
// primitive each, with their colour, opacity and PNG or JPEG texture (embedded). The accessors hold
// the mesh's own coordinates; the node places them in glTF's frame. Frames are spooled to a file;
// finish() writes the .glb under a temporary name and renames it. glTF's frame is +Y up in metres:
// the node turns the mesh's up onto +Y and scales its unit to metres, so that viewers show the body
// standing at its size whatever axes the mesh has.
struct GltfPlacement {
    Mat3 turn = Mat3::Identity();  // a rotation
    double metresPerUnit = 1.0;
};

struct GlbShape;

// Throws Error naming `path`, the frame count and how many frames fit when a .glb of `frames`
// frames of `mesh` would pass the 4 GB a GLB holds; checked before solving.
void checkGlbFits(const std::string& path, const TriMesh& mesh, int frames);

class GltfWriter {
  public:
    GltfWriter(std::string path, const TriMesh& rest, std::string name,
               GltfPlacement placement = {});
    ~GltfWriter();  // an unfinished file is removed
    GltfWriter(const GltfWriter&) = delete;
    GltfWriter& operator=(const GltfWriter&) = delete;

    // positions: #vertices by 3. frame: the 0-based frame index in the take (not the take's
    // own first number), which names the morph target (frame_0100), as it names the OBJ files.
    void append(int frame, double seconds, const Positions& positions);
    void finish();

  private:
    GlbShape shape() const;
    std::string path_, name_;
    const TriMesh& rest_;
    GltfPlacement placement_;
    Positions restNormals_;                   // per mesh vertex, area-weighted
    std::vector<int> meshVertexOf_;           // per glTF vertex, the mesh vertex it is
    std::vector<float> uv_;                   // 2 per glTF vertex (glTF's v runs down), or empty
    std::vector<std::uint32_t> triangles_;    // glTF vertex indices, 3 per mesh triangle
    std::vector<ObjMaterial> usedMaterials_;  // those the triangles use, in order of first use
    // (material, triangles) in triangles_'s order, a material's triangles together; −1: none.
    std::vector<std::pair<int, size_t>> groups_;
    std::uint64_t textureBytes_ = 0;  // the textures' files, padded, as the BIN chunk holds them
    std::FILE* file_ = nullptr;
    std::vector<float> times_;
    std::vector<int> frames_;                    // the 0-based frame indices, as appended
    std::vector<std::array<double, 6>> bounds_;  // per frame: min xyz, max xyz of the offsets
};

}  // namespace boneless
