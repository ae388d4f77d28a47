#pragma once

#include <functional>
#include <memory>
#include <string>

#include "boneless/ExportFormat.h"
#include "boneless/GltfWriter.h"
#include "boneless/TriMesh.h"

namespace boneless {

// Where exportTake's frames go, whatever the format: append() takes the frames in order, finish()
// makes the result appear (a cache or glb file is only renamed into place then; OBJ frames each
// appear as they are written). Dropping an unfinished output removes its partial file.
struct FrameOutput {
    std::function<void(int frame, const Positions& V)> append;
    std::function<void()> finish;
    std::shared_ptr<void> writer;  // keeps the format's writer alive
};

// `first` is the first take frame to be written; `rate` the take's frames per second; `glb` where
// a glb's node puts the mesh; `objFaces` the faces OBJ frames are written with (the mesh's, its
// libraries as the output folder names them: withLibraryCopies).
FrameOutput openFrameOutput(ExportFormat format, const std::string& outDir, const std::string& stem,
                            const TriMesh& mesh, int first, double rate,
                            const std::string& objComment, const GltfPlacement& glb,
                            std::shared_ptr<const SourceFaces> objFaces);

}  // namespace boneless
