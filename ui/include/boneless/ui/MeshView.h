#pragma once

#include <QColor>
#include <QImage>
#include <QList>
#include <QOpenGLWidget>
#include <QPoint>
#include <QRect>
#include <QString>
#include <QStringList>
#include <QVariantMap>
#include <memory>
#include <vector>

#include "boneless/Reconstruction.h"
#include "boneless/TriMesh.h"

namespace boneless::ui {

// How a marker sphere is drawn. Missing markers (NaN rows) are not drawn at all.
enum class MarkerState { Unmapped, Mapped, Selected };

// Where the floor is and how much of it to draw, in mesh coordinates.
struct Floor {
    Eigen::Vector3d up = Eigen::Vector3d::UnitY();
    double height = 0;  // along up
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double size = 0;  // side of the square grid; 0 = no floor
};

// The 3D view: a vtkGenericOpenGLRenderWindow hosted in a Qt6 QOpenGLWidget (Debian's VTK Qt
// widget is Qt5-only). All VTK work happens on the GUI thread; renders only in paintGL.
class MeshView : public QOpenGLWidget {
    Q_OBJECT
  public:
    explicit MeshView(QWidget* parent = nullptr);
    ~MeshView() override;

    // Replaces the mesh; up is the mesh axis that points up (e.g. (0,1,0)). Resets the camera.
    void setMesh(const TriMesh& mesh, const Eigen::Vector3d& up = Eigen::Vector3d::UnitY());
    void clearMesh();
    bool hasMesh() const;
    // New vertex positions for the current connectivity (a solved frame).
    void setPositions(const Positions& V);
    const Positions& positions() const;
    void setUpAxis(const Eigen::Vector3d& up);
    Eigen::Vector3d upAxis() const;

    // K by 3 in mesh coordinates, NaN rows = missing; states and labels have K entries.
    void setMarkers(const Positions& markers, const std::vector<MarkerState>& states,
                    const QStringList& labels = {});
    void setLabelsVisible(bool visible);
    bool labelsVisible() const;
    // One polyline per marker (NaN rows break it); empty = no trails.
    void setTrails(const std::vector<Positions>& trails);
    // Whether a trail is drawn (one of two points or more).
    bool trailsVisible() const;
    // Per-vertex scalars coloured by heatMapColour from 0 to the values' 98th percentile, or
    // `floor` if that is higher (noise at rest must not read as error), with a colour legend
    // titled with the quantity and its units ("Shape error (mm)"); empty = plain shading.
    void setHeatMap(const std::vector<float>& values, const QString& title = {}, double floor = 0);
    // The value at the top of the heat map's scale, 0 without one.
    double legendTop() const;
    bool legendVisible() const;
    QString legendTitle() const;
    // Where the legend was drawn at the last render (logical pixels, top-left origin); empty
    // while it is hidden.
    QRect legendRect() const;
    // A grid on the floor; a Floor of size 0 hides it.
    void setFloor(const Floor& floor);
    // The height along the floor's up of the grid drawn, NaN when there is none.
    double floorHeight() const;
    // The corner gizmo showing the mesh axes (x red, y green, z blue) as the camera turns.
    bool axesVisible() const;
    // Labels that would overlap one of higher priority are not drawn; these are the boxes of
    // those drawn at the last render (logical pixels, top-left origin), and how many were not.
    QList<QRect> labelBoxes() const;
    int hiddenLabelCount() const;
    // The point of the surface drawn as a small dot (the selected marker's), vertex −1 for none.
    void setHighlightedPoint(const SurfacePoint& point);

    void setMultiSampling(int samples);  // 0 = off (tests, software GL)
    void resetCamera();
    // Camera follow (see CameraFollow), on by default: while playing, the camera tracks the mesh
    // smoothly; paused, it moves only to keep the mesh from leaving the screen.
    void setCameraFollow(bool on);
    bool cameraFollow() const;
    void setPlaying(bool playing);
    // Turns the camera to look at `point` from closer, keeping its direction.
    void frame(const Eigen::Vector3d& point);
    Eigen::Vector3d focalPoint() const;
    QImage grabImage();

    // The point of the surface under the widget position (logical pixels, top-left origin):
    // its face, barycentric coordinates and nearest corner; vertex −1 beside the mesh. Does not
    // emit pointPicked.
    SurfacePoint pickPoint(const QPoint& position);
    // Where a point (mesh coordinates) or vertex v appears in the widget (logical pixels,
    // top-left origin); (−1, −1) for a vertex not on the mesh.
    QPoint projectPoint(const Eigen::Vector3d& point);
    QPoint projectVertex(int vertex);
    // The camera's position in mesh coordinates (the vertex nearest to it is never occluded).
    Eigen::Vector3d cameraPosition() const;
    // The camera as {"position": [x,y,z], "focal_point": [...], "view_up": [...],
    // "view_angle": degrees}, what a project stores; setCameraState() returns false (and keeps
    // the camera) for anything else, such as non-finite numbers or a zero view direction.
    QVariantMap cameraState() const;
    bool setCameraState(const QVariantMap& state);

  signals:
    // A click (press and release without a drag) landed on the mesh at this point.
    void pointPicked(const boneless::SurfacePoint& point);
    // A click landed beside the mesh.
    void pickMissed();
    // Emitted after each render, with how long it took.
    void rendered(double milliseconds);

  protected:
    void initializeGL() override;
    void resizeGL(int w, int h) override;
    void paintGL() override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseDoubleClickEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void keyReleaseEvent(QKeyEvent* event) override;
    void enterEvent(QEnterEvent* event) override;
    void leaveEvent(QEvent* event) override;

  private:
    struct Impl;
    std::unique_ptr<Impl> d_;
};

// The view's colours. A heat map's at t in [0, 1] of its scale: violet through blue and green to
// yellow, lighter all along, so that its order reads by lightness alone (a colour-blind reader).
QColor heatMapColour(double t);
// A marker sphere's: unmapped, mapped and selected differ in lightness as well as in hue.
QColor markerColour(MarkerState state);

// "+y", "-z", ... → unit vector; anything else gives +y.
Eigen::Vector3d upAxisVector(const QString& axis);

}  // namespace boneless::ui

Q_DECLARE_METATYPE(boneless::SurfacePoint)
