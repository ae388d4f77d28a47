#include "DemoWalker.h"

#include "boneless/TriMesh.h"  // Vec3

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <algorithm>
#include <array>
#include <cmath>

namespace boneless {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180;
constexpr double kStepSeconds = 0.5;  // one step; a gait cycle is two

enum Bone {
    kPelvis,
    kChest,
    kHead,
    kLUpperArm,
    kLForearm,
    kLHand,
    kRUpperArm,
    kRForearm,
    kRHand,
    kLThigh,
    kLShin,
    kLFoot,
    kRThigh,
    kRShin,
    kRFoot,
    kBoneCount
};

// The rest skeleton: each bone's parent and the joint it turns about. Left is +x.
struct Skeleton {
    std::array<int, kBoneCount> parent{};
    std::array<Vec3, kBoneCount> joint;
};

// The arm hangs 50° below the horizontal (an A pose, which keeps the hands off the thighs).
Vec3 armDirection(double side) {
    return Vec3(side * std::cos(50 * kDegree), 0, -std::sin(50 * kDegree));
}
Vec3 shoulder(double side) {
    return Vec3(side * 0.19, 0, 1.40);
}
Vec3 hip(double side) {
    return Vec3(side * 0.11, 0, 0.90);
}
constexpr double kElbowAt = 0.29, kWristAt = 0.56;  // along the arm from the shoulder

Skeleton restSkeleton() {
    Skeleton s;
    s.parent = {-1,        kPelvis, kChest,  kChest, kLUpperArm, kLForearm, kChest, kRUpperArm,
                kRForearm, kPelvis, kLThigh, kLShin, kPelvis,    kRThigh,   kRShin};
    s.joint[kPelvis] = {0, 0, 0.95};
    s.joint[kChest] = {0, 0, 1.08};
    s.joint[kHead] = {0, 0, 1.55};
    for (double side : {1.0, -1.0}) {
        const int arm = side > 0 ? kLUpperArm : kRUpperArm;
        const int leg = side > 0 ? kLThigh : kRThigh;
        s.joint[arm] = shoulder(side);
        s.joint[arm + 1] = shoulder(side) + kElbowAt * armDirection(side);
        s.joint[arm + 2] = shoulder(side) + kWristAt * armDirection(side);
        s.joint[leg] = hip(side);
        s.joint[leg + 1] = Vec3(side * 0.11, 0, 0.48);
        s.joint[leg + 2] = Vec3(side * 0.11, 0, 0.10);
    }
    return s;
}

// A control cage of quads, built box-modelling style: a torso box whose faces are extruded into
// limbs, ring by ring. Each cage vertex follows one bone, or two half and half at a joint.
struct CageVertex {
    Vec3 p;
    int bone, bone2;
    double w2;  // the share of bone2
};

class Cage {
  public:
    std::vector<CageVertex> vertices;
    std::vector<std::array<int, 4>> quads;

    Vec3 point(int v) const { return vertices[v].p; }
    Vec3 centroid(int q) const {
        Vec3 c = Vec3::Zero();
        for (int v : quads[q]) c += point(v);
        return c / 4;
    }
    Vec3 normal(int q) const {
        const auto& f = quads[q];
        return (point(f[2]) - point(f[0])).cross(point(f[3]) - point(f[1])).normalized();
    }
    int nearestQuad(const Vec3& p) const {
        int best = 0;
        for (int q = 1; q < static_cast<int>(quads.size()); ++q)
            if ((centroid(q) - p).norm() < (centroid(best) - p).norm()) best = q;
        return best;
    }
    // The side quad of the last extrusion whose normal is closest to `direction`.
    int lastSide(const Vec3& direction) const {
        int best = lastSides_[0];
        for (int q : lastSides_)
            if (normal(q).dot(direction) > normal(best).dot(direction)) best = q;
        return best;
    }

    // Replaces quad q by four side quads and a cap centred on `center`, facing `direction`: the
    // old ring turned onto the new direction and stretched to half-extents (ru along uAxis, rv
    // across). Returns the cap.
    int extrude(int q, const Vec3& center, const Vec3& direction, const Vec3& uAxis, double ru,
                double rv, int bone, int bone2 = -1, double w2 = 0) {
        const std::array<int, 4> ring = quads[q];
        const Vec3 c = centroid(q), d = direction.normalized();
        const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(normal(q), d);
        const Vec3 u = (uAxis - uAxis.dot(d) * d).normalized(), v = d.cross(u);
        std::array<Vec3, 4> offset;
        double maxU = 0, maxV = 0;
        for (int i = 0; i < 4; ++i) {
            offset[i] = turn * (point(ring[i]) - c);
            maxU = std::max(maxU, std::abs(offset[i].dot(u)));
            maxV = std::max(maxV, std::abs(offset[i].dot(v)));
        }
        std::array<int, 4> cap;
        for (int i = 0; i < 4; ++i) {
            cap[i] = static_cast<int>(vertices.size());
            const Vec3 p =
                center + u * (offset[i].dot(u) / maxU * ru) + v * (offset[i].dot(v) / maxV * rv);
            vertices.push_back({p, bone, bone2 < 0 ? bone : bone2, w2});
        }
        lastSides_ = {q, 0, 0, 0};
        for (int i = 0; i < 4; ++i) {
            const int j = (i + 1) % 4;
            const std::array<int, 4> side = {ring[i], ring[j], cap[j], cap[i]};
            if (i == 0) {
                quads[q] = side;
            } else {
                lastSides_[i] = static_cast<int>(quads.size());
                quads.push_back(side);
            }
        }
        quads.push_back(cap);
        return static_cast<int>(quads.size()) - 1;
    }

  private:
    std::array<int, 4> lastSides_{};
};

// The torso: a box of 3 × 1 × 3 quads (width, depth, height), shaped level by level.
void addTorso(Cage& cage) {
    const double X[] = {-1, -1.0 / 3, 1.0 / 3, 1};
    const double z[] = {0.86, 1.06, 1.30, 1.48}, halfWidth[] = {0.19, 0.165, 0.21, 0.21},
                 halfDepth[] = {0.13, 0.12, 0.135, 0.11};
    const int levelBone[] = {kPelvis, kPelvis, kChest, kChest};
    auto index = [](int i, int j, int k) { return (k * 2 + j) * 4 + i; };
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 4; ++i)
                cage.vertices.push_back(
                    {Vec3(X[i] * halfWidth[k], (2 * j - 1) * halfDepth[k], z[k]), levelBone[k],
                     kChest, k == 1 ? 0.5 : 0.0});
    auto quad = [&](int a, int b, int c, int d, bool flip) {
        cage.quads.push_back(flip ? std::array<int, 4>{d, c, b, a}
                                  : std::array<int, 4>{a, b, c, d});
    };
    for (int k = 0; k < 3; ++k) {  // sides ±x, then front and back ∓y
        quad(index(3, 0, k), index(3, 1, k), index(3, 1, k + 1), index(3, 0, k + 1), false);
        quad(index(0, 0, k), index(0, 1, k), index(0, 1, k + 1), index(0, 0, k + 1), true);
        for (int i = 0; i < 3; ++i) {
            quad(index(i, 1, k), index(i, 1, k + 1), index(i + 1, 1, k + 1), index(i + 1, 1, k),
                 false);
            quad(index(i, 0, k), index(i, 0, k + 1), index(i + 1, 0, k + 1), index(i + 1, 0, k),
                 true);
        }
    }
    for (int i = 0; i < 3; ++i) {  // top and bottom
        quad(index(i, 0, 3), index(i + 1, 0, 3), index(i + 1, 1, 3), index(i, 1, 3), false);
        quad(index(i, 0, 0), index(i + 1, 0, 0), index(i + 1, 1, 0), index(i, 1, 0), true);
    }
}

void addArm(Cage& cage, double side) {
    const int upper = side > 0 ? kLUpperArm : kRUpperArm, fore = upper + 1, hand = upper + 2;
    const Vec3 a = armDirection(side), s = shoulder(side), y = Vec3::UnitY();
    int q = cage.nearestQuad(Vec3(side * 0.21, 0, 1.39));
    struct Ring {
        double at, ru, rv;
        int bone, bone2;
    };
    const Ring rings[] = {{0.06, 0.075, 0.07, kChest, upper}, {0.16, 0.068, 0.064, upper, -1},
                          {0.25, 0.06, 0.058, upper, -1},     {kElbowAt, 0.056, 0.054, upper, fore},
                          {0.33, 0.058, 0.055, fore, -1},     {0.43, 0.055, 0.05, fore, -1},
                          {0.52, 0.042, 0.034, fore, -1},     {kWristAt, 0.04, 0.03, fore, hand},
                          {0.63, 0.062, 0.026, hand, -1},     {0.72, 0.06, 0.022, hand, -1},
                          {0.77, 0.04, 0.016, hand, -1}};
    for (const Ring& r : rings)
        q = cage.extrude(q, s + r.at * a, a, y, r.ru, r.rv, r.bone, r.bone2, r.bone2 < 0 ? 0 : 0.5);
}

void addLeg(Cage& cage, double side) {
    const int thigh = side > 0 ? kLThigh : kRThigh, shin = thigh + 1, foot = thigh + 2;
    const Vec3 down = -Vec3::UnitZ(), x = Vec3::UnitX();
    int q = cage.nearestQuad(Vec3(side * 0.127, 0, 0.86));
    struct Ring {
        double z, ru, rv;
        int bone, bone2;
    };
    const Ring rings[] = {{0.74, 0.10, 0.105, thigh, -1},   {0.58, 0.08, 0.085, thigh, -1},
                          {0.48, 0.066, 0.07, thigh, shin}, {0.40, 0.064, 0.07, shin, -1},
                          {0.28, 0.06, 0.072, shin, -1},    {0.11, 0.042, 0.048, shin, foot},
                          {0.03, 0.046, 0.062, foot, -1}};
    for (const Ring& r : rings)
        q = cage.extrude(q, Vec3(side * 0.11, 0, r.z), down, x, r.ru, r.rv, r.bone, r.bone2,
                         r.bone2 < 0 ? 0 : 0.5);
    // The foot grows forward (−y) out of the front of the heel.
    const Vec3 forward = -Vec3::UnitY();
    q = cage.lastSide(forward);
    q = cage.extrude(q, Vec3(side * 0.11, -0.10, 0.045), forward, x, 0.05, 0.04, foot);
    cage.extrude(q, Vec3(side * 0.11, -0.19, 0.03), forward, x, 0.046, 0.024, foot);
}

void addHead(Cage& cage) {
    const Vec3 up = Vec3::UnitZ(), x = Vec3::UnitX();
    int q = cage.nearestQuad(Vec3(0, 0, 1.48));
    struct Ring {
        double y, z, ru, rv;
        int bone, bone2;
    };
    const Ring rings[] = {
        {0.01, 1.54, 0.06, 0.06, kChest, kHead}, {0.01, 1.58, 0.062, 0.062, kHead, -1},
        {-0.01, 1.63, 0.10, 0.115, kHead, -1},   {0, 1.73, 0.115, 0.13, kHead, -1},
        {0.005, 1.83, 0.09, 0.10, kHead, -1},    {0, 1.88, 0.04, 0.04, kHead, -1}};
    for (const Ring& r : rings)
        q = cage.extrude(q, Vec3(0, r.y, r.z), up, x, r.ru, r.rv, r.bone, r.bone2,
                         r.bone2 < 0 ? 0 : 0.5);
}

Cage makeCage() {
    Cage cage;
    addTorso(cage);
    addHead(cage);
    for (double side : {1.0, -1.0}) {
        addArm(cage, side);
        addLeg(cage, side);
    }
    return cage;
}

using Pose = std::array<Eigen::Isometry3d, kBoneCount>;

Eigen::Matrix3d turn(double angle, const Vec3& axis) {
    return Eigen::AngleAxisd(angle, axis.normalized()).matrix();
}

// The walk at time t (seconds), its amplitude eased from 0 (the rest pose): every bone's
// transform from the rest skeleton to the world.
Pose walkPose(const Skeleton& s, double t, double amplitude) {
    const double phase = kPi * t / kStepSeconds;  // 2π a cycle
    std::array<Eigen::Matrix3d, kBoneCount> local;
    local.fill(Eigen::Matrix3d::Identity());
    const Vec3 X = Vec3::UnitX(), Z = Vec3::UnitZ();
    Vec3 lift(0.015 * std::sin(phase), 0, 0.02 * std::cos(2 * phase) - 0.02);
    lift *= amplitude;
    local[kPelvis] = turn(amplitude * 5 * kDegree * std::sin(phase), Z);
    local[kChest] =
        turn(amplitude * -8 * kDegree * std::sin(phase), Z) * turn(amplitude * -4 * kDegree, X);
    local[kHead] = turn(amplitude * 3 * kDegree * std::sin(phase), Z);
    for (double side : {1.0, -1.0}) {
        const double p = side > 0 ? phase : phase + kPi;
        const int thigh = side > 0 ? kLThigh : kRThigh;
        const int arm = side > 0 ? kLUpperArm : kRUpperArm;
        // Hip flexion swings the leg forward (−y); the knee bends most early in the swing.
        const double hipFlex = amplitude * 22 * kDegree * std::sin(p);
        const double swing = std::max(0.0, std::cos(p + kPi / 4));
        const double knee = amplitude * (5 + 55 * swing * swing) * kDegree;
        local[thigh] = turn(-hipFlex, X);
        local[thigh + 1] = turn(knee, X);
        local[thigh + 2] = turn(0.7 * (hipFlex - knee), X);
        // The arm swings against the leg on its side; the elbow bends as it comes forward.
        const double armFlex = amplitude * -18 * kDegree * std::sin(p);
        const Vec3 hinge = armDirection(side).cross(-Vec3::UnitY());
        local[arm] = turn(-armFlex, X);
        local[arm + 1] = turn(amplitude * (15 * kDegree) + 0.5 * std::max(0.0, armFlex), hinge);
        local[arm + 2] = turn(amplitude * 10 * kDegree, hinge);
    }
    Pose pose;
    for (int b = 0; b < kBoneCount; ++b) {
        Eigen::Isometry3d about = Eigen::Isometry3d::Identity();
        about.translate(s.joint[b]).rotate(local[b]).translate(-s.joint[b]);
        if (s.parent[b] < 0) {
            pose[b] = Eigen::Translation3d(lift) * about;
        } else {
            pose[b] = pose[s.parent[b]] * about;
        }
    }
    return pose;
}

struct PolyTraits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
    using Normal = OpenMesh::Vec3d;
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<PolyTraits>;

// The Catmull–Clark surface of the cage at `points`, triangulated. The same cage always gives
// the same vertex order, so every pose's surface shares the rest surface's connectivity.
TriMesh subdivide(const Cage& cage, const std::vector<Vec3>& points, int steps) {
    PolyMesh mesh;
    std::vector<PolyMesh::VertexHandle> handles;
    for (const Vec3& p : points) handles.push_back(mesh.add_vertex({p.x(), p.y(), p.z()}));
    for (const auto& q : cage.quads)
        mesh.add_face({handles[q[0]], handles[q[1]], handles[q[2]], handles[q[3]]});
    OpenMesh::Subdivider::Uniform::CatmullClarkT<PolyMesh> catmullClark;
    catmullClark.attach(mesh);
    catmullClark(static_cast<size_t>(steps));
    catmullClark.detach();
    mesh.triangulate();
    TriMesh out;
    out.V.resize(static_cast<int>(mesh.n_vertices()), 3);
    for (auto v : mesh.vertices()) {
        const auto& p = mesh.point(v);
        out.V.row(v.idx()) << p[0], p[1], p[2];
    }
    out.F.resize(static_cast<int>(mesh.n_faces()), 3);
    for (auto f : mesh.faces()) {
        int i = 0;
        for (auto v : f.vertices()) out.F(f.idx(), i++) = v.idx();
    }
    return out;
}

// The marker set, Plug-in Gait style: each marker goes on the skin vertex nearest a probe point
// placed just outside the body where the marker is worn.
std::vector<std::pair<std::string, Vec3>> markerProbes() {
    std::vector<std::pair<std::string, Vec3>> probes = {{"C7", {0, 0.12, 1.53}},
                                                        {"T10", {0, 0.2, 1.2}},
                                                        {"CLAV", {0, -0.15, 1.47}},
                                                        {"STRN", {0, -0.22, 1.28}},
                                                        {"RBAK", {-0.11, 0.22, 1.34}}};
    for (double side : {1.0, -1.0}) {
        const std::string L = side > 0 ? "L" : "R";
        const Vec3 a = armDirection(side), s = shoulder(side);
        const Vec3 out = Vec3(side * std::sin(50 * kDegree), 0, std::cos(50 * kDegree));
        const Vec3 back = Vec3::UnitY();
        const std::pair<std::string, Vec3> more[] = {
            {L + "FHD", {side * 0.06, -0.2, 1.8}},       {L + "BHD", {side * 0.06, 0.2, 1.8}},
            {L + "SHO", s + Vec3(0.01 * side, 0, 0.12)}, {L + "UPA", s + 0.16 * a + 0.12 * out},
            {L + "ELB", s + kElbowAt * a + 0.12 * back}, {L + "FRM", s + 0.42 * a + 0.12 * out},
            {L + "WRA", s + kWristAt * a - 0.1 * back},  {L + "WRB", s + kWristAt * a + 0.1 * back},
            {L + "FIN", s + 0.7 * a + 0.1 * out},        {L + "ASI", {side * 0.11, -0.2, 0.98}},
            {L + "PSI", {side * 0.06, 0.2, 1.0}},        {L + "THI", {side * 0.26, -0.02, 0.68}},
            {L + "KNE", {side * 0.24, 0, 0.48}},         {L + "TIB", {side * 0.24, -0.03, 0.28}},
            {L + "ANK", {side * 0.22, 0, 0.1}},          {L + "HEE", {side * 0.11, 0.2, 0.05}},
            {L + "TOE", {side * 0.11, -0.22, 0.1}},
        };
        probes.insert(probes.end(), std::begin(more), std::end(more));
    }
    return probes;
}

}  // namespace

DemoWalker makeDemoWalker(int frameCount, int subdivisions,
                          const std::function<void(int, const Positions&)>& onFrame) {
    const Skeleton skeleton = restSkeleton();
    const Cage cage = makeCage();
    std::vector<Vec3> points;
    for (const CageVertex& v : cage.vertices) points.push_back(v.p);

    DemoWalker walker;
    walker.rest = subdivide(cage, points, subdivisions);
    for (int t = 0; t < frameCount; ++t) {
        // The walk eases in over a third of a second from the rest pose.
        const double seconds = t / walker.framesPerSecond;
        const Pose pose = walkPose(skeleton, seconds, std::min(1.0, seconds / 0.33));
        std::vector<Vec3> posed(points.size());
        for (size_t i = 0; i < points.size(); ++i) {
            const CageVertex& v = cage.vertices[i];
            posed[i] = (1 - v.w2) * (pose[v.bone] * v.p) + v.w2 * (pose[v.bone2] * v.p);
        }
        Positions frame = t == 0 ? walker.rest.V : subdivide(cage, posed, subdivisions).V;
        if (onFrame)
            onFrame(t, frame);
        else
            walker.frames.push_back(std::move(frame));
    }
    for (const auto& [label, probe] : markerProbes()) {
        Eigen::Index nearest = 0;
        (walker.rest.V.rowwise() - probe.transpose()).rowwise().squaredNorm().minCoeff(&nearest);
        walker.markerVertices.emplace_back(label, static_cast<int>(nearest));
    }
    return walker;
}

}  // namespace boneless
