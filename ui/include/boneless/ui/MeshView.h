#pragma once

#include <QImage>
#include <QOpenGLWidget>
#include <QPoint>
#include <QString>
#include <QStringList>
#include <QVariantMap>
#include <memory>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless::ui {

// How a marker sphere is drawn. Missing markers (NaN rows) are not drawn at all.
enum class MarkerState { Unmapped, Mapped, Selected };

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

    // K by 3 in mesh coordinates, NaN rows = missing; states and labels have K entries.
    void setMarkers(const Positions& markers, const std::vector<MarkerState>& states,
                    const QStringList& labels = {});
    void setLabelsVisible(bool visible);
    bool labelsVisible() const;
    // One polyline per marker (NaN rows break it); empty = no trails.
    void setTrails(const std::vector<Positions>& trails);
    // Per-vertex scalars coloured from blue (0) to red (max); empty = plain shading.
    void setHeatMap(const std::vector<float>& values);
    // The mesh vertex drawn as a small dot (the selected marker's vertex), -1 for none.
    void setHighlightedVertex(int vertex);

    void setMultiSampling(int samples);  // 0 = off (tests, software GL)
    void resetCamera();
    QImage grabImage();

    // Nearest vertex of the triangle under the widget position (logical pixels, top-left
    // origin), or -1. Does not emit vertexPicked.
    int pickVertex(const QPoint& position);
    // Where vertex v appears in the widget (logical pixels, top-left origin).
    QPoint projectVertex(int vertex);
    // The camera's position in mesh coordinates (the vertex nearest to it is never occluded).
    Eigen::Vector3d cameraPosition() const;
    // The camera as {"position": [x,y,z], "focal_point": [...], "view_up": [...],
    // "view_angle": degrees}, what a project stores; setCameraState() returns false (and keeps
    // the camera) for anything else, such as non-finite numbers or a zero view direction.
    QVariantMap cameraState() const;
    bool setCameraState(const QVariantMap& state);

  signals:
    // A click (press and release without a drag) landed on the mesh near this vertex.
    void vertexPicked(int vertex);
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

// "+y", "-z", ... → unit vector; anything else gives +y.
Eigen::Vector3d upAxisVector(const QString& axis);

}  // namespace boneless::ui
