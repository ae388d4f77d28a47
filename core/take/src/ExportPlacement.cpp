// Where an export puts the take: the mesh units and up axis it guesses, and a glb's placement.
#include <cmath>

#include "boneless/Axis.h"
#include "boneless/TakeExport.h"
#include "boneless/Text.h"

namespace boneless {

namespace {

struct MeshUnit {
    const char* name;
    double perMm;
};

// Heights a body of the take may have, mm: a small animal's to a horse's.
constexpr double kBodyMm[2] = {300, 4000};

MeshUnit nearestUnit(double meshUnitsPerMm) {
    const auto gap = [&](const MeshUnit& u) {
        return std::abs(std::log(meshUnitsPerMm / u.perMm));
    };
    const MeshUnit metric[] = {{"mm", 1.0}, {"cm", 0.1}, {"dm", 0.01}, {"m", 0.001}};
    MeshUnit best = metric[0];
    for (const auto& u : metric)
        if (gap(u) < gap(best)) best = u;
    // Inches and feet, 3ds Max's default and many game assets' (an inch mesh read as cm made a
    // glb 2.54 times too small), only within a factor 1.2 of one:
    // between metric units they would take a child's body in cm, driven by an adult, for inches.
    for (const MeshUnit u : {MeshUnit{"in", 1.0 / 25.4}, MeshUnit{"ft", 1.0 / 304.8}})
        if (gap(u) < std::log(1.2) && gap(u) < gap(best)) best = u;
    return best;
}

// The signed mesh axis nearest where the take's vertical goes.
Vec3 meshUp(const Similarity& s, const Vec3& takeUp) {
    const Vec3 up = s.R * takeUp;
    int axis = 0;
    up.cwiseAbs().maxCoeff(&axis);
    return (up[axis] < 0 ? -1.0 : 1.0) * Vec3::Unit(axis);
}

}  // namespace

const char* guessMeshUnits(double meshUnitsPerMm) {
    return nearestUnit(meshUnitsPerMm).name;
}

std::string meshScaleWarning(const TriMesh& rest, const Similarity& takeToMesh, double takeUnitToMm,
                             const Vec3& takeUp) {
    const double meshUnitsPerMm = takeToMesh.scale / takeUnitToMm;
    const MeshUnit unit = nearestUnit(meshUnitsPerMm);
    // Neighbouring metric units are 10 apart, so the nearest is within √10 of any mesh sized
    // between mm and m: only a mesh beyond them (a body 0.01 times its size) gets this far.
    if (std::abs(std::log(meshUnitsPerMm / unit.perMm)) < std::log(4.0) || rest.F.size() == 0)
        return "";
    const Vec3 up = meshUp(takeToMesh, takeUp);
    double low = INFINITY, high = -INFINITY;
    for (Eigen::Index i = 0; i < rest.F.size(); ++i) {
        const double h = rest.V.row(rest.F.data()[i]).dot(up);
        low = std::min(low, h), high = std::max(high, h);
    }
    const auto length = [](double mm) {
        return mm >= 1000 ? shortNumber(mm / 1000, 2) + " m"
               : mm >= 10 ? shortNumber(mm / 10, 2) + " cm"
                          : shortNumber(mm, 2) + " mm";
    };
    const double mm = (high - low) / unit.perMm;
    // A body's size in that unit: the mesh is right, and the take's markers are ten or a hundred
    // times its size (a take in mm given as cm), where "check its scale" blamed the mesh.
    if (mm >= kBodyMm[0] && mm <= kBodyMm[1])
        return "the take's markers make the body " + length((high - low) / meshUnitsPerMm) +
               " tall, where the mesh is " + length(mm) + " tall in " + unit.name +
               ": check the take's units";
    return std::string("mesh units look like ") + unit.name + ", but the body would be " +
           length(mm) + " tall: check the mesh's scale (a .glb export places it by that unit)";
}

std::string guessUpAxis(const Similarity& s, const Vec3& takeUp) {
    return axisName(meshUp(s, takeUp));
}

GltfPlacement gltfPlacement(const Similarity& takeToMesh, double takeUnitToMm, const Vec3& takeUp) {
    GltfPlacement p;
    p.turn = Eigen::Quaterniond::FromTwoVectors(meshUp(takeToMesh, takeUp), Vec3::UnitY())
                 .toRotationMatrix();
    p.metresPerUnit = 0.001 / nearestUnit(takeToMesh.scale / takeUnitToMm).perMm;
    return p;
}

}  // namespace boneless
