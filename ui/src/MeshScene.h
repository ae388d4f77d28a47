#pragma once

#include <array>

#include <QStringList>
#include <vector>

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include "FloorGrid.h"
#include "MarkerLabels.h"
#include "boneless/Reconstruction.h"
#include "boneless/TriMesh.h"
#include "boneless/ui/MeshView.h"

class vtkActor;
class vtkActor2D;
class vtkCellPicker;
class vtkGlyph3DMapper;
class vtkPolyData;
class vtkPolyDataMapper;
class vtkRenderer;
class vtkScalarBarActor;
class vtkSphereSource;
class vtkStaticCellLocator;

namespace boneless::ui {

// The VTK scene of a MeshView: mesh, marker spheres, labels, trails, the highlighted vertex, the
// floor grid, the heat map's legend and vertex picking. Knows nothing of Qt's OpenGL; the widget
// owns the context and the renders.
class MeshScene {
  public:
    MeshScene();
    ~MeshScene();

    vtkRenderer* renderer() const;

    void setMesh(const TriMesh& mesh);
    void clearMesh();
    bool hasMesh() const { return V_.rows() > 0; }
    void setPositions(const Positions& V);
    const Positions& positions() const { return V_; }

    void setMarkers(const Positions& markers, const std::vector<MarkerState>& states,
                    const QStringList& labels);
    void setLabelsVisible(bool visible) { labels_.setVisible(visible); }
    bool labelsVisible() const { return labels_.visible(); }
    // Before each render: which labels fit (see MarkerLabels).
    void layoutLabels() { labels_.layout(renderer_); }
    const MarkerLabels& labels() const { return labels_; }
    void setTrails(const std::vector<Positions>& trails);
    bool trailsVisible() const;
    // `title` names the quantity and its units, for the legend.
    void setHeatMap(const std::vector<float>& values, const QString& title, double floor = 0);
    double legendTop() const { return legendTop_; }
    bool legendVisible() const;
    QString legendTitle() const;
    // Before each render: the legend sized from its title and values, in the top-right corner.
    void placeLegend();
    // The legend's box as placed at the last placeLegend(), display pixels (bottom-left origin):
    // x0, y0, x1, y1; all 0 while it is hidden.
    std::array<int, 4> legendBox() const;
    void setFloor(const Floor& floor) { floor_.set(floor); }
    const FloorGrid& floorGrid() const { return floor_; }
    void setHighlightedPoint(const SurfacePoint& point);

    // Fits the camera to the mesh, looking at its front with `up` pointing up on screen.
    void resetCamera(const Eigen::Vector3d& up);

    // Display coordinates are VTK's: device pixels, origin bottom-left.
    SurfacePoint pick(double x, double y);  // vertex −1: beside the mesh
    void project(const Eigen::Vector3d& point, double& x, double& y) const;

  private:
    void updateNormals();
    void updateHighlight();
    double markerRadius() const;

    Positions V_;
    Faces F_;
    bool locatorStale_ = true;
    SurfacePoint highlighted_;  // vertex −1: none
    double legendTop_ = 0;

    vtkNew<vtkRenderer> renderer_;
    vtkNew<vtkPolyData> mesh_;
    vtkNew<vtkPolyDataMapper> meshMapper_;
    vtkNew<vtkActor> meshActor_;
    vtkNew<vtkPolyData> markers_;
    vtkNew<vtkSphereSource> sphere_;
    vtkNew<vtkGlyph3DMapper> markerMapper_;
    vtkNew<vtkActor> markerActor_;
    MarkerLabels labels_;
    FloorGrid floor_;
    vtkNew<vtkScalarBarActor> legend_;
    vtkNew<vtkPolyData> trails_;
    vtkNew<vtkPolyDataMapper> trailMapper_;
    vtkNew<vtkActor> trailActor_;
    vtkNew<vtkSphereSource> highlightSphere_;
    vtkNew<vtkPolyDataMapper> highlightMapper_;
    vtkNew<vtkActor> highlightActor_;
    vtkNew<vtkStaticCellLocator> locator_;
    vtkNew<vtkCellPicker> picker_;
};

}  // namespace boneless::ui
