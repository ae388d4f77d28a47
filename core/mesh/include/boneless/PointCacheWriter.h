#pragma once

#include <cstdio>
#include <string>

#include "boneless/TriMesh.h"

namespace boneless {

// Streams frames into a PC2 point cache (the format Blender's Mesh Cache modifier and 3ds Max
// read): a 32-byte header, "POINTCACHE2\0", version 1, point count, start frame, sample rate,
// sample count, then float32 x y z per point per frame, little-endian. The file is written under a
// temporary name and only renamed into place by finish(), so an interrupted export never leaves a
// cache that claims frames it does not hold.
class PointCacheWriter {
  public:
    PointCacheWriter(std::string path, int pointCount, double startFrame, double sampleRate = 1.0);
    ~PointCacheWriter();  // an unfinished cache is removed
    PointCacheWriter(const PointCacheWriter&) = delete;
    PointCacheWriter& operator=(const PointCacheWriter&) = delete;

    void append(const Positions& positions);  // #points by 3
    void finish();
    int frames() const { return frames_; }

  private:
    std::string path_, temporary_;
    std::FILE* file_ = nullptr;
    int points_ = 0, frames_ = 0;
};

// Reads a PC2 file back (for tests and for users' sanity checks): frames of #points by 3.
std::vector<Positions> readPointCache(const std::string& path, double* startFrame = nullptr);

}  // namespace boneless
