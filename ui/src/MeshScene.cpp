#include "MeshScene.h"

#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellPicker.h>
#include <vtkCoordinate.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkLookupTable.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkScalarsToColors.h>
#include <vtkSphereSource.h>
#include <vtkStaticCellLocator.h>
#include <vtkTextProperty.h>
#include <vtkTextRenderer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace boneless::ui {
namespace {

bool finiteRow(const Positions& P, Eigen::Index i) {
    return P.row(i).allFinite();
}

void copyPoints(const Positions& V, vtkPoints* points) {
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(V.rows());
    auto* array = vtkDoubleArray::SafeDownCast(points->GetData());
    std::copy(V.data(), V.data() + V.size(), array->GetPointer(0));
    points->Modified();
}

}  // namespace

QColor heatMapColour(double t) {
    // Viridis read off at eighths: its lightness rises evenly (L* about 15 to 91) and its hues
    // avoid the red-green axis, so no colour vision confuses two parts of the scale.
    static constexpr unsigned char stops[9][3] = {{68, 1, 84},    {71, 45, 123},  {59, 82, 139},
                                                  {44, 114, 142}, {33, 145, 140}, {40, 174, 128},
                                                  {94, 201, 98},  {173, 220, 48}, {253, 231, 37}};
    const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 8;
    const int i = std::min(7, int(x));
    const double f = x - i;
    const auto mix = [&](int c) {
        return int(std::lround(stops[i][c] * (1 - f) + stops[i + 1][c] * f));
    };
    return QColor(mix(0), mix(1), mix(2));
}

QColor markerColour(MarkerState state) {
    // Blue and orange, the pair most colour visions tell apart, and 25 L* apart as well;
    // the selected marker is lighter still, and larger.
    switch (state) {
        case MarkerState::Mapped:
            return QColor(40, 100, 210);
        case MarkerState::Selected:
            return QColor(255, 235, 40);
        case MarkerState::Unmapped:
            break;
    }
    return QColor(240, 150, 30);
}

MeshScene::MeshScene() {
    renderer_->SetBackground(0.20, 0.22, 0.26);
    // VTK clears to alpha 0 by default; Qt would compose the view with the window behind it.
    renderer_->SetBackgroundAlpha(1.0);
    renderer_->SetUseFXAA(false);

    meshMapper_->SetInputData(mesh_);
    meshMapper_->ScalarVisibilityOff();
    meshActor_->SetMapper(meshMapper_);
    meshActor_->GetProperty()->SetColor(0.86, 0.80, 0.70);
    meshActor_->GetProperty()->SetSpecular(0.15);
    meshActor_->GetProperty()->SetSpecularPower(20);
    meshActor_->VisibilityOff();
    renderer_->AddActor(meshActor_);

    sphere_->SetThetaResolution(16);
    sphere_->SetPhiResolution(12);
    sphere_->SetRadius(1.0);
    markerMapper_->SetInputData(markers_);
    markerMapper_->SetSourceConnection(sphere_->GetOutputPort());
    markerMapper_->SetScaleArray("radius");
    markerMapper_->SetScaleModeToScaleByMagnitude();
    markerMapper_->SetColorModeToDirectScalars();
    markerMapper_->SetScalarModeToUsePointFieldData();
    markerMapper_->SelectColorArray("colour");
    markerMapper_->ScalarVisibilityOn();
    markerActor_->SetMapper(markerMapper_);
    markerActor_->PickableOff();
    renderer_->AddActor(markerActor_);

    renderer_->AddActor2D(labels_.actor());
    renderer_->AddActor(floor_.actor());

    legend_->SetNumberOfLabels(5);
    // Its size and place are placeLegend()'s, before each render.
    // VTK sets a label a twentieth of its width from the bar: "23.5" touched it. The spaces
    // after the value keep it clear.
    legend_->SetLabelFormat("%.3g  ");
    legend_->SetTextPositionToPrecedeScalarBar();
    // The top value's label is kept clear of the title: placeLegend() sets the gap.
    legend_->UnconstrainedFontSizeOn();
    legend_->GetTitleTextProperty()->SetFontSize(13);
    legend_->GetLabelTextProperty()->SetFontSize(12);
    for (vtkTextProperty* text :
         {legend_->GetTitleTextProperty(), legend_->GetLabelTextProperty()}) {
        text->SetBold(false);
        text->SetItalic(false);
        text->SetShadow(false);
        text->SetColor(0.92, 0.92, 0.92);
    }
    legend_->VisibilityOff();
    renderer_->AddActor2D(legend_);

    trailMapper_->SetInputData(trails_);
    trailActor_->SetMapper(trailMapper_);
    trailActor_->GetProperty()->SetColor(0.45, 0.75, 1.0);
    trailActor_->GetProperty()->SetLineWidth(2.0);
    trailActor_->PickableOff();
    trailActor_->VisibilityOff();
    renderer_->AddActor(trailActor_);

    highlightMapper_->SetInputConnection(highlightSphere_->GetOutputPort());
    highlightActor_->SetMapper(highlightMapper_);
    highlightActor_->GetProperty()->SetColor(0.1, 0.9, 1.0);
    highlightActor_->PickableOff();
    highlightActor_->VisibilityOff();
    renderer_->AddActor(highlightActor_);

    locator_->SetDataSet(mesh_);
    picker_->AddLocator(locator_);
    picker_->PickFromListOn();
    picker_->AddPickList(meshActor_);
    picker_->SetTolerance(1e-6);
}

MeshScene::~MeshScene() = default;

vtkRenderer* MeshScene::renderer() const {
    return renderer_.Get();
}

void MeshScene::setMesh(const TriMesh& mesh) {
    V_ = mesh.V;
    F_ = mesh.F;
    vtkNew<vtkPoints> points;
    copyPoints(V_, points);
    vtkNew<vtkCellArray> triangles;
    for (Eigen::Index f = 0; f < F_.rows(); ++f) {
        const vtkIdType ids[3] = {F_(f, 0), F_(f, 1), F_(f, 2)};
        triangles->InsertNextCell(3, ids);
    }
    mesh_->Initialize();
    mesh_->SetPoints(points);
    mesh_->SetPolys(triangles);
    updateNormals();
    setHeatMap({}, {});
    meshActor_->SetVisibility(V_.rows() > 0);
    const double r = markerRadius();
    sphere_->SetRadius(1.0);
    highlightSphere_->SetRadius(0.45 * r);
    highlighted_ = SurfacePoint();
    updateHighlight();
    locatorStale_ = true;
}

void MeshScene::clearMesh() {
    setMesh(TriMesh{});
    setMarkers(Positions(0, 3), {}, {});
    setTrails({});
    setFloor({});
}

void MeshScene::setPositions(const Positions& V) {
    if (V.rows() != V_.rows() || V_.rows() == 0) return;
    V_ = V;
    copyPoints(V_, mesh_->GetPoints());
    updateNormals();
    mesh_->Modified();
    updateHighlight();
    // The locator is rebuilt lazily at the next pick: scrubbing should not pay for it.
    locatorStale_ = true;
}

void MeshScene::updateNormals() {
    // Area-weighted vertex normals by hand: a vtkPolyDataNormals filter would also split
    // sharp edges and renumber points, which breaks picking by vertex id.
    Positions N = Positions::Zero(V_.rows(), 3);
    for (Eigen::Index f = 0; f < F_.rows(); ++f) {
        const Eigen::RowVector3d a = V_.row(F_(f, 0)), b = V_.row(F_(f, 1)), c = V_.row(F_(f, 2));
        const Eigen::RowVector3d n = (b - a).cross(c - a);
        for (int k = 0; k < 3; ++k) N.row(F_(f, k)) += n;
    }
    vtkNew<vtkFloatArray> normals;
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(N.rows());
    for (Eigen::Index i = 0; i < N.rows(); ++i) {
        const double len = N.row(i).norm();
        const Eigen::RowVector3d n =
            len > 0 ? Eigen::RowVector3d(N.row(i) / len) : Eigen::RowVector3d(0, 0, 1);
        normals->SetTuple3(i, n(0), n(1), n(2));
    }
    mesh_->GetPointData()->SetNormals(normals);
}

double MeshScene::markerRadius() const {
    const double diagonal = boundingBoxDiagonal(V_);
    return diagonal > 0 ? 0.008 * diagonal : 0.01;
}

void MeshScene::setMarkers(const Positions& markers, const std::vector<MarkerState>& states,
                           const QStringList& labels) {
    vtkNew<vtkPoints> points;
    vtkNew<vtkFloatArray> radius;
    radius->SetName("radius");
    vtkNew<vtkUnsignedCharArray> colour;
    colour->SetName("colour");
    colour->SetNumberOfComponents(3);
    Positions shown(markers.rows(), 3);
    std::vector<std::string> texts;
    std::vector<int> priorities;
    const double r = markerRadius();
    for (Eigen::Index k = 0; k < markers.rows(); ++k) {
        // A missing marker has no position this frame; drawing it anywhere would mislead.
        if (!finiteRow(markers, k)) continue;
        const MarkerState state =
            k < static_cast<Eigen::Index>(states.size()) ? states[k] : MarkerState::Unmapped;
        points->InsertNextPoint(markers(k, 0), markers(k, 1), markers(k, 2));
        const QColor c = markerColour(state);
        const unsigned char rgb[3] = {static_cast<unsigned char>(c.red()),
                                      static_cast<unsigned char>(c.green()),
                                      static_cast<unsigned char>(c.blue())};
        const double scale = state == MarkerState::Selected ? 1.7 * r : r;
        radius->InsertNextValue(static_cast<float>(scale));
        colour->InsertNextTypedTuple(rgb);
        shown.row(Eigen::Index(texts.size())) = markers.row(k);
        texts.push_back(k < labels.size() ? labels[k].toStdString() : std::to_string(k));
        // The selected marker's name always shows; then the ones still to map.
        priorities.push_back(state == MarkerState::Selected   ? 0
                             : state == MarkerState::Unmapped ? 1
                                                              : 2);
    }
    markers_->Initialize();
    markers_->SetPoints(points);
    markers_->GetPointData()->AddArray(radius);
    markers_->GetPointData()->AddArray(colour);
    markers_->Modified();
    markerActor_->SetVisibility(points->GetNumberOfPoints() > 0);
    labels_.set(shown.topRows(Eigen::Index(texts.size())), texts, priorities);
}

void MeshScene::setTrails(const std::vector<Positions>& trails) {
    vtkNew<vtkPoints> points;
    vtkNew<vtkCellArray> lines;
    for (const Positions& trail : trails) {
        std::vector<vtkIdType> run;
        auto flush = [&] {
            if (run.size() >= 2)
                lines->InsertNextCell(static_cast<vtkIdType>(run.size()), run.data());
            run.clear();
        };
        for (Eigen::Index i = 0; i < trail.rows(); ++i) {
            if (!finiteRow(trail, i)) {
                flush();
                continue;
            }
            run.push_back(points->InsertNextPoint(trail(i, 0), trail(i, 1), trail(i, 2)));
        }
        flush();
    }
    trails_->Initialize();
    trails_->SetPoints(points);
    trails_->SetLines(lines);
    trails_->Modified();
    trailActor_->SetVisibility(lines->GetNumberOfCells() > 0);
}

bool MeshScene::trailsVisible() const {
    return trailActor_->GetVisibility();
}

void MeshScene::setHeatMap(const std::vector<float>& values, const QString& title, double floor) {
    legendTop_ = 0;
    if (values.empty() || static_cast<Eigen::Index>(values.size()) != V_.rows()) {
        mesh_->GetPointData()->SetScalars(nullptr);
        meshMapper_->ScalarVisibilityOff();
        legend_->VisibilityOff();
        return;
    }
    vtkNew<vtkFloatArray> scalars;
    scalars->SetName(title.toStdString().c_str());
    scalars->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
    std::copy(values.begin(), values.end(), scalars->GetPointer(0));
    mesh_->GetPointData()->SetScalars(scalars);
    // Scale to a high percentile, not the maximum: a few strained vertices would wash out the rest.
    std::vector<float> sorted = values;
    const std::size_t p = std::min(sorted.size() - 1, sorted.size() * 98 / 100);
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(p), sorted.end());
    // The floor: noise on a frame at rest (1e-6 mm) filled the whole scale and read as error.
    const double top = std::max({1e-12, floor, static_cast<double>(sorted[p])});
    legendTop_ = top;
    vtkNew<vtkLookupTable> table;
    constexpr int kColours = 256;
    table->SetNumberOfTableValues(kColours);
    for (int i = 0; i < kColours; ++i) {
        const QColor c = heatMapColour(double(i) / (kColours - 1));
        table->SetTableValue(i, c.redF(), c.greenF(), c.blueF(), 1.0);
    }
    table->SetTableRange(0.0, top);
    meshMapper_->SetLookupTable(table);
    meshMapper_->SetScalarRange(0.0, top);
    meshMapper_->SetScalarModeToUsePointData();
    meshMapper_->ScalarVisibilityOn();
    // The legend reads the same table, so its colours are the mesh's.
    legend_->SetLookupTable(table);
    legend_->SetTitle(title.toStdString().c_str());
    legend_->VisibilityOn();
}

void MeshScene::placeLegend() {
    // Sized in pixels from its text, in the view's top-right corner. At 65 % of the view's
    // height by its right edge it lay over the body's arm in a 1024x600 window, and its values
    // had only the room the bar left them: the top one, "23.5", touched the bar.
    const int* size = renderer_->GetSize();
    vtkTextRenderer* measure = vtkTextRenderer::GetInstance();
    vtkRenderWindow* window = renderer_->GetRenderWindow();
    vtkScalarsToColors* table = legend_->GetLookupTable();
    if (!legend_->GetVisibility() || !table || size[0] <= 0 || size[1] <= 0 || !measure || !window)
        return;
    // Pixels at a DPI of 72 (a scale of 1), scaled with the text on a high-DPI screen.
    const double scale = window->GetDPI() / 72.0;
    const auto px = [scale](int pixels) { return int(std::lround(pixels * scale)); };
    const int kMargin = px(10), kBar = px(14);  // from the view's edges, the bar's width
    legend_->SetVerticalTitleSeparation(px(8));
    const auto widthOf = [&](vtkTextProperty* text, const char* s) {
        int box[4];
        return measure->GetBoundingBox(text, s, box, window->GetDPI()) ? box[1] - box[0] + 1 : 0;
    };
    const int title =
        legend_->GetTitle() ? widthOf(legend_->GetTitleTextProperty(), legend_->GetTitle()) : 0;
    // The values' labels as the legend prints them, evenly spaced, with their spaces.
    const double* range = table->GetRange();
    const int labels = legend_->GetNumberOfLabels();
    int label = 0;
    for (int i = 0; i < labels; ++i) {
        char text[64];
        const double value = range[0] + (range[1] - range[0]) * i / std::max(1, labels - 1);
        std::snprintf(text, sizeof text, legend_->GetLabelFormat(), value);
        label = std::max(label, widthOf(legend_->GetLabelTextProperty(), text));
    }
    const int width =
        std::max(1, std::min(size[0] - 2 * kMargin, std::max(title, label + kBar + px(2))));
    // Two fifths of the view's height, and room for five labels in a small view.
    const int height =
        std::max(1, std::min(size[1] - 2 * kMargin, std::clamp(size[1] * 2 / 5, px(130), px(280))));
    legend_->SetBarRatio(std::min(1.0, double(kBar) / width));
    legend_->SetWidth(double(width) / size[0]);
    legend_->SetHeight(double(height) / size[1]);
    legend_->SetPosition(double(size[0] - kMargin - width) / size[0],
                         double(size[1] - kMargin - height) / size[1]);
}

std::array<int, 4> MeshScene::legendBox() const {
    if (!legendVisible()) return {0, 0, 0, 0};
    vtkRenderer* renderer = renderer_.GetPointer();
    const int* low = legend_->GetPositionCoordinate()->GetComputedDisplayValue(renderer);
    const int* high = legend_->GetPosition2Coordinate()->GetComputedDisplayValue(renderer);
    return {low[0], low[1], high[0], high[1]};
}

bool MeshScene::legendVisible() const {
    return legend_->GetVisibility() && legend_->GetLookupTable();
}

QString MeshScene::legendTitle() const {
    return legend_->GetTitle() ? QString::fromStdString(legend_->GetTitle()) : QString();
}

void MeshScene::setHighlightedPoint(const SurfacePoint& point) {
    highlighted_ = point;
    updateHighlight();
}

void MeshScene::updateHighlight() {
    const SurfacePoint& p = highlighted_;
    if (p.vertex < 0 || p.vertex >= V_.rows() || p.face >= F_.rows()) {
        highlightActor_->VisibilityOff();
        return;
    }
    const Vec3 x = surfacePosition(F_, V_, p);
    highlightSphere_->SetCenter(x[0], x[1], x[2]);
    highlightSphere_->SetRadius(0.45 * markerRadius());
    highlightActor_->VisibilityOn();
}

void MeshScene::resetCamera(const Eigen::Vector3d& up) {
    vtkCamera* camera = renderer_->GetActiveCamera();
    // Look at the mesh's front: along a horizontal axis, so the up axis stays vertical on screen.
    Eigen::Vector3d front = Eigen::Vector3d::UnitZ();
    if (std::abs(up.z()) > 0.5) front = -Eigen::Vector3d::UnitY();
    if (std::abs(up.x()) > 0.5) front = Eigen::Vector3d::UnitZ();
    camera->SetFocalPoint(0, 0, 0);
    camera->SetPosition(front.x(), front.y(), front.z());
    camera->SetViewUp(up.x(), up.y(), up.z());
    camera->Azimuth(25);
    camera->Elevation(15);
    camera->OrthogonalizeViewUp();
    if (hasMesh()) {
        double bounds[6];
        mesh_->GetBounds(bounds);
        renderer_->ResetCamera(bounds);
    } else {
        renderer_->ResetCamera();
    }
}

SurfacePoint MeshScene::pick(double x, double y) {
    if (!hasMesh()) return {};
    if (locatorStale_) {
        locator_->SetDataSet(mesh_);
        locator_->BuildLocator();
        locatorStale_ = false;
    }
    if (!picker_->Pick(x, y, 0.0, renderer_)) return {};
    const vtkIdType cell = picker_->GetCellId();
    if (cell < 0 || cell >= F_.rows()) return {};
    double hit[3];
    picker_->GetPickPosition(hit);
    // The hit's place in its triangle; GetPointId() often names a neighbour, not its corner.
    return surfacePointAt(F_, V_, static_cast<int>(cell), Vec3(hit[0], hit[1], hit[2]));
}

void MeshScene::project(const Eigen::Vector3d& point, double& x, double& y) const {
    renderer_->SetWorldPoint(point[0], point[1], point[2], 1.0);
    renderer_->WorldToDisplay();
    double display[3];
    renderer_->GetDisplayPoint(display);
    x = display[0];
    y = display[1];
}

}  // namespace boneless::ui
