#pragma once

#include <memory>
#include <vector>

#include "boneless/Reconstruction.h"

namespace boneless {

// As-rigid-as-possible surface deformation (Sorkine & Alexa 2007), spokes-and-rims energy with
// cotangent weights, marker vertices as hard constraints. It is the baseline Boneless is measured
// against (`boneless-cli eval --method arap`), with the same prepare/solve shape as Reconstruction.
class ArapDeformer {
  public:
    struct Options {
        int iterations = 10;  // local/global iterations per frame
    };

    ArapDeformer();
    ~ArapDeformer();

    void prepare(const TriMesh& rest, std::vector<int> markerVertices, Options options);
    // targets: K by 3, NaN rows are missing markers; guess: #V by 3 or none (rest, rigidly
    // aligned).
    SolveResult solve(const Positions& targets, const Positions* guess = nullptr);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace boneless
