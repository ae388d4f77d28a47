#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// Streams frames into an MDD point cache (LightWave's format, read by Cinema 4D, Houdini and
// Blender's Mesh Cache modifier): big-endian int32 frame count, int32 point count, float32 time in
// seconds per frame, then float32 x y z per point per frame. The count and times come before the
// points, so frames go to a spool file and finish() writes the cache under a temporary name and
// renames it: an interrupted export never leaves a cache claiming frames it does not hold.
class MddWriter {
  public:
    MddWriter(std::string path, int pointCount);
    ~MddWriter();  // an unfinished cache is removed
    MddWriter(const MddWriter&) = delete;
    MddWriter& operator=(const MddWriter&) = delete;

    void append(double seconds, const Positions& positions);  // #points by 3
    void finish();

  private:
    std::string path_;
    std::FILE* file_ = nullptr;
    int points_ = 0;
    std::vector<float> times_;
};

// Reads an MDD file back (for tests and users' checks): frames of #points by 3, and their times.
std::vector<Positions> readMdd(const std::string& path, std::vector<double>* seconds = nullptr);

}  // namespace boneless
