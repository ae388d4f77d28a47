#include "DemoCreature.h"

#include <algorithm>
#include <cmath>

namespace boneless {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLength = 6.0;  // body length along x, in metres-like units

// Body radius along the axis (u in [0, 1], head at 1): a bulging head and a tapered tail.
double radiusAt(double u) {
    const double head = 0.55 * std::exp(-std::pow((u - 0.85) / 0.12, 2));
    return 0.35 + 0.25 * std::sin(kPi * u) + head - 0.2 * (1 - u) * (1 - u);
}

// The spine of the swimming pose at time t: a travelling wave whose amplitude grows towards the
// tail, plus a slow turn of the head. Returns the spine point and its unit tangent for arclength s.
void spine(double s, double t, double amplitude, Eigen::Vector3d& point, Eigen::Matrix3d& frame) {
    // Integrate the heading angle along the body so that the spine keeps its length.
    const int steps = 64;
    double x = 0, y = 0, heading = 0;
    auto curvature = [&](double a) {
        const double u = a / kLength;
        return amplitude * 0.9 * (1.2 - u) * std::sin(2 * kPi * (u * 1.3 - t)) +
               0.15 * std::sin(2 * kPi * t);
    };
    const double ds = s / steps;
    for (int i = 0; i < steps; ++i) {
        const double a = (i + 0.5) * ds;
        heading += curvature(a) * ds * 0.5;
        x += std::cos(heading) * ds;
        y += std::sin(heading) * ds;
        heading += curvature(a) * ds * 0.5;
    }
    point = {x, y, amplitude * 0.2 * std::sin(2 * kPi * t) * s / kLength};
    const Eigen::Vector3d tangent(std::cos(heading), std::sin(heading), 0);
    const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    frame.col(0) = tangent;
    frame.col(1) = up.cross(tangent).normalized();
    frame.col(2) = up;
}

}  // namespace

DemoCreature makeDemoCreature(int frameCount, int rings, int segments,
                              const std::function<void(int, const Positions&)>& onFrame) {
    DemoCreature demo;
    const int capRings = segments / 4;
    // Axial coordinate (arclength along x) and radius of every ring, caps included.
    std::vector<double> ringS, ringR;
    const double r0 = radiusAt(0), r1 = radiusAt(1);
    for (int i = capRings; i >= 1; --i) {  // tail cap
        const double a = 0.5 * kPi * i / capRings;
        ringS.push_back(-r0 * std::sin(a) * 0.6);
        ringR.push_back(r0 * std::cos(a));
    }
    for (int i = 0; i < rings; ++i) {
        const double u = static_cast<double>(i) / (rings - 1);
        ringS.push_back(u * kLength);
        ringR.push_back(radiusAt(u));
    }
    for (int i = 1; i <= capRings; ++i) {  // head cap
        const double a = 0.5 * kPi * i / capRings;
        ringS.push_back(kLength + r1 * std::sin(a) * 0.8);
        ringR.push_back(r1 * std::cos(a));
    }
    // The caps end in a ring of radius 0; replace those by single pole vertices.
    const int ringCount = static_cast<int>(ringS.size()) - 2;
    const int vertexCount = ringCount * segments + 2;
    // Body coordinates of each vertex: arclength s, angle, radius (for posing along the spine).
    std::vector<Eigen::Vector3d> body(vertexCount);
    for (int i = 0; i < ringCount; ++i)
        for (int j = 0; j < segments; ++j) {
            const double angle = 2 * kPi * j / segments;
            body[i * segments + j] = {ringS[i + 1], ringR[i + 1] * std::cos(angle),
                                      ringR[i + 1] * std::sin(angle) * 0.8};
        }
    body[vertexCount - 2] = {ringS.front(), 0, 0};
    body[vertexCount - 1] = {ringS.back(), 0, 0};

    std::vector<Eigen::Vector3i> faces;
    for (int i = 0; i + 1 < ringCount; ++i)
        for (int j = 0; j < segments; ++j) {
            const int a = i * segments + j, b = i * segments + (j + 1) % segments;
            const int c = a + segments, d = b + segments;
            // Counter-clockwise seen from outside: normals, and so marker offsets, point out.
            faces.push_back({a, d, c});
            faces.push_back({a, b, d});
        }
    const int tail = vertexCount - 2, head = vertexCount - 1, last = (ringCount - 1) * segments;
    for (int j = 0; j < segments; ++j) {
        faces.push_back({tail, (j + 1) % segments, j});
        faces.push_back({head, last + j, last + (j + 1) % segments});
    }

    auto pose = [&](double t, double amplitude) {
        Positions P(vertexCount, 3);
        for (int v = 0; v < vertexCount; ++v) {
            const double s = std::clamp(body[v].x(), 0.0, kLength);
            Eigen::Vector3d point;
            Eigen::Matrix3d frame;
            spine(s, t, amplitude, point, frame);
            const double beyond = body[v].x() - s;  // the caps extend past the spine's ends
            const Eigen::Vector3d p = point + frame.col(0) * beyond + frame.col(1) * body[v].y() +
                                      frame.col(2) * body[v].z();
            P.row(v) = p.transpose();
        }
        return P;
    };
    demo.rest.F.resize(static_cast<int>(faces.size()), 3);
    for (size_t f = 0; f < faces.size(); ++f) demo.rest.F.row(f) = faces[f].transpose();
    // The rest pose is the straight body (amplitude 0); the swimming eases in over ten frames.
    demo.rest.V = pose(0.0, 0.0);
    for (int t = 0; t < frameCount; ++t) {
        Positions frame = pose(t / demo.framesPerSecond, std::min(1.0, t / 10.0));
        if (onFrame)
            onFrame(t, frame);
        else
            demo.frames.push_back(std::move(frame));
    }
    return demo;
}

}  // namespace boneless
