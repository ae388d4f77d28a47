#include "FloorGrid.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>

#include <cmath>
#include <limits>

#include "boneless/ui/Document.h"

namespace boneless::ui {
namespace {

// 1, 2 or 5 times a power of ten, near `x`: grid steps a user can read off.
double roundStep(double x) {
    const double power = std::pow(10.0, std::floor(std::log10(x)));
    const double m = x / power;
    return power * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
}

}  // namespace

Floor floorOf(const Document& document, const Eigen::Vector3d& up) {
    Floor floor;
    floor.up = up.normalized();
    if (!document.hasMesh()) return floor;
    Eigen::AlignedBox3d box;
    const Positions& rest = document.mesh().V;
    for (Eigen::Index i = 0; i < rest.rows(); ++i) box.extend(rest.row(i).transpose());
    double lowest = std::numeric_limits<double>::infinity();
    for (int f = 0; f < document.frameCount(); ++f) {
        const Positions P = document.markerPositions(f);
        for (Eigen::Index k = 0; k < P.rows(); ++k) {
            if (!P.row(k).allFinite()) continue;
            lowest = std::min(lowest, P.row(k).dot(floor.up.transpose()));
            box.extend(P.row(k).transpose());
        }
    }
    if (!std::isfinite(lowest))  // no take, or no marker ever seen: the rest mesh stands on it
        for (Eigen::Index i = 0; i < rest.rows(); ++i)
            lowest = std::min(lowest, rest.row(i).dot(floor.up.transpose()));
    if (box.isEmpty() || !std::isfinite(lowest)) return floor;
    floor.height = lowest;
    floor.centre = box.center();
    // Room around the subject's whole path, so the grid's edge is not where the feet are.
    floor.size = 1.5 * box.diagonal().norm();
    return floor;
}

FloorGrid::FloorGrid() {
    mapper_->SetInputData(lines_);
    actor_->SetMapper(mapper_);
    actor_->GetProperty()->SetColor(0.42, 0.45, 0.50);
    actor_->GetProperty()->SetLighting(false);
    actor_->PickableOff();
    actor_->VisibilityOff();
}

FloorGrid::~FloorGrid() = default;

vtkActor* FloorGrid::actor() const {
    return actor_.Get();
}

void FloorGrid::set(const Floor& floor) {
    floor_ = floor;
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();  // the grid's height is read back to the digit
    vtkNew<vtkCellArray> cells;
    if (floor.size > 0 && std::isfinite(floor.size) && floor.up.norm() > 0) {
        const Eigen::Vector3d up = floor.up.normalized();
        // Two directions across the floor.
        const Eigen::Vector3d a = up.unitOrthogonal(), b = up.cross(a);
        const Eigen::Vector3d origin = floor.centre + (floor.height - floor.centre.dot(up)) * up;
        const double step = roundStep(floor.size / 12);
        const int half = int(std::ceil(0.5 * floor.size / step));
        const double reach = half * step;
        for (int i = -half; i <= half; ++i)
            for (const auto& [along, across] : {std::pair{a, b}, std::pair{b, a}}) {
                const Eigen::Vector3d p = origin + i * step * across - reach * along;
                const Eigen::Vector3d q = origin + i * step * across + reach * along;
                const vtkIdType ids[2] = {points->InsertNextPoint(p.data()),
                                          points->InsertNextPoint(q.data())};
                cells->InsertNextCell(2, ids);
            }
    }
    lines_->Initialize();
    lines_->SetPoints(points);
    lines_->SetLines(cells);
    lines_->Modified();
    actor_->SetVisibility(cells->GetNumberOfCells() > 0);
}

double FloorGrid::drawnHeight() const {
    vtkPoints* points = lines_->GetPoints();
    if (!points || points->GetNumberOfPoints() == 0)
        return std::numeric_limits<double>::quiet_NaN();
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) {
        double p[3];
        points->GetPoint(i, p);
        const double h = Eigen::Vector3d(p[0], p[1], p[2]).dot(floor_.up.normalized());
        low = std::min(low, h), high = std::max(high, h);
    }
    // Lines off the plane would be a tilted grid, not a floor.
    if (high - low > 1e-9 * std::max(1.0, floor_.size))
        return std::numeric_limits<double>::quiet_NaN();
    return low;
}

}  // namespace boneless::ui
