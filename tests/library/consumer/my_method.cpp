// A reconstruction method of one's own, on Boneless's core (docs/library.md): reads a
// ground-truth sequence, drives K farthest-point marker vertices with their true positions, and
// writes each frame's answer as an OBJ named as the truth's frame, for
// `boneless-cli eval --sequence SEQ --reconstruction OUT` to judge.
// Usage: my-method SEQUENCE_DIR K OUT_DIR
#include <boneless/Error.h>
#include <boneless/MeshSequence.h>
#include <boneless/ObjWriter.h>
#include <boneless/Reconstruction.h>
#include <boneless/Sampling.h>

#include <cstdio>
#include <filesystem>
#include <string>

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: my-method SEQUENCE_DIR K OUT_DIR\n");
        return 2;
    }
    namespace fs = std::filesystem;
    try {
        const boneless::MeshSequence sequence = boneless::readMeshSequence(argv[1]);
        const std::vector<int> markers =
            boneless::geodesicFarthestPoints(sequence.rest, std::stoi(argv[2]));  // as eval's
        // The expensive part, once: encoding, coarse level, factorisation.
        boneless::Reconstruction solver;
        solver.prepare(sequence.rest, markers);
        fs::create_directories(argv[3]);
        for (size_t f = 1; f < sequence.frames.size(); ++f) {
            const boneless::Positions& truth = sequence.frames[f];
            boneless::Positions targets(markers.size(), 3);  // K by 3, mesh units
            for (size_t k = 0; k < markers.size(); ++k) targets.row(k) = truth.row(markers[k]);
            // Here one's own method would find the frame; this one asks Boneless's.
            const boneless::SolveResult result = solver.solve(targets);
            const fs::path out = fs::path(argv[3]) / fs::path(sequence.files[f]).filename();
            boneless::writeObj(out.string(), result.V, sequence.rest.F);
        }
    } catch (const boneless::Error& e) {
        std::fprintf(stderr, "my-method: %s\n", e.what());
        return 1;
    }
    return 0;
}
