// Qt's GL headers only in this file: VTK's GL loader must not meet them (qt6-vtk.md).
#include "boneless/ui/MeshView.h"

#include <QElapsedTimer>
#include <QEnterEvent>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QWheelEvent>

#include <vtkAxesActor.h>
#include <vtkCamera.h>
#include <vtkCaptionActor2D.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGenericRenderWindowInteractor.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkOpenGLState.h>
#include <vtkOrientationMarkerWidget.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkTextProperty.h>

#include <cmath>

#include "CameraFollow.h"
#include "MeshScene.h"

namespace boneless::ui {

struct MeshView::Impl {
    MeshView* q;
    MeshScene scene;
    vtkNew<vtkGenericOpenGLRenderWindow> window;
    vtkNew<vtkGenericRenderWindowInteractor> interactor;
    vtkNew<vtkInteractorStyleTrackballCamera> style;
    vtkNew<vtkAxesActor> axes;
    vtkNew<vtkOrientationMarkerWidget> gizmo;
    CameraFollow follow;
    Eigen::Vector3d up = Eigen::Vector3d::UnitY();
    bool initialized = false;
    bool painting = false;
    bool cameraPending = true;  // reset the camera once the widget has its real size
    QMetaObject::Connection contextConnection;
    QPoint pressPosition;
    bool leftDown = false, dragged = false;

    explicit Impl(MeshView* view) : q(view) {
        window->SetMultiSamples(0);
        window->SetFrameBlitModeToNoBlit();
        window->SetReadyForRendering(false);
        window->AddRenderer(scene.renderer());
        window->AddObserver(vtkCommand::WindowMakeCurrentEvent, this, &Impl::onMakeCurrent);
        window->AddObserver(vtkCommand::WindowIsCurrentEvent, this, &Impl::onIsCurrent);
        window->AddObserver(vtkCommand::WindowFrameEvent, this, &Impl::onFrame);
        interactor->SetRenderWindow(window);
        interactor->SetInteractorStyle(style);
        // The style asks for renders; they become update() so all GL work happens in paintGL.
        interactor->EnableRenderOff();
        interactor->AddObserver(vtkCommand::RenderEvent, this, &Impl::onRenderRequest);
        setUpGizmo();
    }

    // The widget draws the axes in its own renderer in a corner, turned with the main camera.
    void setUpGizmo() {
        const double colours[3][3] = {{0.9, 0.2, 0.2}, {0.3, 0.85, 0.3}, {0.3, 0.45, 1.0}};
        vtkProperty* shafts[3] = {axes->GetXAxisShaftProperty(), axes->GetYAxisShaftProperty(),
                                  axes->GetZAxisShaftProperty()};
        vtkProperty* tips[3] = {axes->GetXAxisTipProperty(), axes->GetYAxisTipProperty(),
                                axes->GetZAxisTipProperty()};
        vtkCaptionActor2D* captions[3] = {axes->GetXAxisCaptionActor2D(),
                                          axes->GetYAxisCaptionActor2D(),
                                          axes->GetZAxisCaptionActor2D()};
        for (int k = 0; k < 3; ++k) {
            shafts[k]->SetColor(colours[k][0], colours[k][1], colours[k][2]);
            tips[k]->SetColor(colours[k][0], colours[k][1], colours[k][2]);
            vtkTextProperty* text = captions[k]->GetCaptionTextProperty();
            text->SetColor(colours[k][0], colours[k][1], colours[k][2]);
            text->ShadowOff();
            text->ItalicOff();
        }
        gizmo->SetOrientationMarker(axes);
        gizmo->SetInteractor(interactor);
        gizmo->SetDefaultRenderer(scene.renderer());
        gizmo->SetViewport(0.0, 0.0, 0.16, 0.2);
        gizmo->SetZoom(1.5);
        gizmo->SetEnabled(1);
        // A gizmo that can be dragged about would take the clicks that map markers.
        gizmo->InteractiveOff();
    }

    void onMakeCurrent(vtkObject*, unsigned long, void*) {
        // The black-frame trap: re-making the context current in the middle of VTK's render
        // rebinds Qt's framebuffer and VTK draws into the wrong one.
        if (QOpenGLContext::currentContext() != q->context()) q->makeCurrent();
    }
    void onIsCurrent(vtkObject*, unsigned long, void* callData) {
        *static_cast<bool*>(callData) =
            q->context() && QOpenGLContext::currentContext() == q->context();
    }
    void onFrame(vtkObject*, unsigned long, void*) {
        if (!painting) q->update();
    }
    void onRenderRequest(vtkObject*, unsigned long, void*) { q->update(); }

    QPoint deviceSize() const {
        const double ratio = q->devicePixelRatioF();
        return {std::max(1, int(std::lround(q->width() * ratio))),
                std::max(1, int(std::lround(q->height() * ratio)))};
    }

    // Qt logical position → VTK display position (device pixels, bottom-left origin).
    void toDisplay(const QPointF& p, double& x, double& y) const {
        const double ratio = q->devicePixelRatioF();
        x = p.x() * ratio;
        y = deviceSize().y() - 1 - p.y() * ratio;
    }

    void syncSize() {
        // VTK sizes text in points at this DPI, 72 = a point a pixel. Scaled as Qt scales the
        // widgets' text (device pixels per pixel, the screen's font DPI over 96), the labels and
        // legend read as large as the window's; at 72 on a scale of 2 they were half as large.
        const int dpi =
            std::max(1, int(std::lround(72.0 * q->devicePixelRatioF() * q->logicalDpiY() / 96.0)));
        if (window->GetDPI() != dpi) window->SetDPI(dpi);
        const QPoint size = deviceSize();
        interactor->UpdateSize(size.x(), size.y());
        window->SetSize(size.x(), size.y());
        if (cameraPending && scene.hasMesh()) {
            scene.resetCamera(up);
            cameraPending = false;
        }
    }

    void forwardMouse(QMouseEvent* event, unsigned long vtkEvent, int repeat = 0) {
        const double ratio = q->devicePixelRatioF();
        const Qt::KeyboardModifiers mods = event->modifiers();
        interactor->SetEventInformationFlipY(
            int(event->position().x() * ratio), int(event->position().y() * ratio),
            (mods & Qt::ControlModifier) ? 1 : 0, (mods & Qt::ShiftModifier) ? 1 : 0, 0, repeat);
        interactor->SetAltKey((mods & Qt::AltModifier) ? 1 : 0);
        interactor->InvokeEvent(vtkEvent);
    }
};

MeshView::MeshView(QWidget* parent) : QOpenGLWidget(parent), d_(std::make_unique<Impl>(this)) {
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(200, 150);
    // It takes the focus first: a screen reader must say what it is.
    setAccessibleName(tr("3D view"));
    setAccessibleDescription(
        tr("The mesh and the take's markers; click the mesh to pick a vertex"));
}

MeshView::~MeshView() {
    // QOpenGLWidget's destructor destroys the context after Impl is gone.
    disconnect(d_->contextConnection);
    // Release VTK's GL resources while the context still exists.
    if (d_->initialized && context()) {
        makeCurrent();
        d_->window->Finalize();
        doneCurrent();
    }
}

void MeshView::initializeGL() {
    // Called again with a new context after the widget changes top-level window.
    disconnect(d_->contextConnection);
    d_->contextConnection = connect(
        context(), &QOpenGLContext::aboutToBeDestroyed, this,
        [this] {
            makeCurrent();
            d_->window->Finalize();
            d_->initialized = false;
            doneCurrent();
        },
        Qt::DirectConnection);
    d_->window->SetOwnContext(0);
    d_->window->OpenGLInitContext();
    d_->window->GetState()->Reset();
    d_->window->SetReadyForRendering(true);
    d_->window->SetMapped(1);
    d_->syncSize();
    if (!d_->interactor->GetInitialized()) d_->interactor->Initialize();
    d_->initialized = true;
}

void MeshView::resizeGL(int, int) {
    d_->syncSize();
    update();
}

void MeshView::paintGL() {
    if (!d_->initialized) return;
    QElapsedTimer timer;
    timer.start();
    d_->syncSize();
    d_->painting = true;
    d_->scene.renderer()->ResetCameraClippingRange();
    d_->scene.layoutLabels();
    d_->scene.placeLegend();
    vtkOpenGLState* state = d_->window->GetState();
    // Qt changed GL state since the last frame; VTK's cache must not trust its old values.
    state->Reset();
    state->Push();
    d_->window->Render();
    state->Pop();
    const QPoint size = d_->deviceSize();
    context()->functions()->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, defaultFramebufferObject());
    state->ResetFramebufferBindings();
    d_->window->BlitDisplayFramebuffer(0, 0, 0, size.x(), size.y(), 0, 0, size.x(), size.y(),
                                       GL_COLOR_BUFFER_BIT, GL_NEAREST);
    d_->painting = false;
    emit rendered(timer.nsecsElapsed() / 1e6);
}

void MeshView::setMesh(const TriMesh& mesh, const Eigen::Vector3d& up) {
    d_->up = up.norm() > 0 ? up.normalized() : Eigen::Vector3d::UnitY();
    d_->scene.setMesh(mesh);
    d_->scene.resetCamera(d_->up);
    d_->follow.restart(mesh.V);
    // The first real size arrives with resizeGL; fit again then.
    d_->cameraPending = !d_->initialized;
    update();
}

void MeshView::clearMesh() {
    d_->scene.clearMesh();
    update();
}

bool MeshView::hasMesh() const {
    return d_->scene.hasMesh();
}

void MeshView::setPositions(const Positions& V) {
    d_->scene.setPositions(V);
    // Before the first paint the widget has no real size to keep the mesh inside.
    if (d_->initialized && V.rows() == d_->scene.positions().rows() && hasMesh()) {
        d_->syncSize();
        d_->follow.follow(d_->scene.renderer(), V, d_->up);
    }
    update();
}

const Positions& MeshView::positions() const {
    return d_->scene.positions();
}

void MeshView::setUpAxis(const Eigen::Vector3d& up) {
    if (up.norm() == 0) return;
    d_->up = up.normalized();
    resetCamera();
}

Eigen::Vector3d MeshView::upAxis() const {
    return d_->up;
}

void MeshView::setMarkers(const Positions& markers, const std::vector<MarkerState>& states,
                          const QStringList& labels) {
    d_->scene.setMarkers(markers, states, labels);
    update();
}

void MeshView::setLabelsVisible(bool visible) {
    d_->scene.setLabelsVisible(visible);
    update();
}

bool MeshView::labelsVisible() const {
    return d_->scene.labelsVisible();
}

void MeshView::setTrails(const std::vector<Positions>& trails) {
    d_->scene.setTrails(trails);
    update();
}

bool MeshView::trailsVisible() const {
    return d_->scene.trailsVisible();
}

void MeshView::setHeatMap(const std::vector<float>& values, const QString& title, double floor) {
    d_->scene.setHeatMap(values, title, floor);
    update();
}

double MeshView::legendTop() const {
    return d_->scene.legendTop();
}

bool MeshView::legendVisible() const {
    return d_->scene.legendVisible();
}

QString MeshView::legendTitle() const {
    return d_->scene.legendTitle();
}

void MeshView::setFloor(const Floor& floor) {
    d_->scene.setFloor(floor);
    update();
}

double MeshView::floorHeight() const {
    return d_->scene.floorGrid().drawnHeight();
}

bool MeshView::axesVisible() const {
    return d_->gizmo->GetEnabled() && d_->axes->GetVisibility();
}

QRect MeshView::legendRect() const {
    const std::array<int, 4> b = d_->scene.legendBox();
    if (b[2] <= b[0] || b[3] <= b[1]) return {};
    const double ratio = devicePixelRatioF();
    const int height = d_->deviceSize().y();
    return QRect(QPoint(int(b[0] / ratio), int((height - b[3]) / ratio)),
                 QPoint(int((b[2] - 1) / ratio), int((height - 1 - b[1]) / ratio)));
}

QList<QRect> MeshView::labelBoxes() const {
    QList<QRect> boxes;
    const double ratio = devicePixelRatioF();
    const int height = d_->deviceSize().y();
    for (const LabelBox& b : d_->scene.labels().drawnBoxes())
        boxes << QRect(QPoint(int(b.x0 / ratio), int((height - b.y1) / ratio)),
                       QPoint(int((b.x1 - 1) / ratio), int((height - 1 - b.y0) / ratio)));
    return boxes;
}

int MeshView::hiddenLabelCount() const {
    return d_->scene.labels().hiddenCount();
}

void MeshView::setHighlightedPoint(const SurfacePoint& point) {
    d_->scene.setHighlightedPoint(point);
    update();
}

void MeshView::setMultiSampling(int samples) {
    d_->window->SetMultiSamples(std::max(0, samples));
    update();
}

void MeshView::resetCamera() {
    d_->scene.resetCamera(d_->up);
    d_->follow.restart(d_->scene.positions());
    update();
}

void MeshView::setCameraFollow(bool on) {
    d_->follow.setEnabled(on);
    d_->follow.restart(d_->scene.positions());
}

bool MeshView::cameraFollow() const {
    return d_->follow.enabled();
}

void MeshView::setPlaying(bool playing) {
    d_->follow.setPlaying(playing);
}

void MeshView::frame(const Eigen::Vector3d& point) {
    if (!point.allFinite()) return;
    vtkCamera* camera = d_->scene.renderer()->GetActiveCamera();
    double p[3], f[3];
    camera->GetPosition(p);
    camera->GetFocalPoint(f);
    Eigen::Vector3d direction =
        Eigen::Vector3d(f[0], f[1], f[2]) - Eigen::Vector3d(p[0], p[1], p[2]);
    const double current = direction.norm();
    if (current <= 0) return;
    direction /= current;
    // Close enough that a tenth of the mesh around the point fills the view, never farther.
    const double radius = 0.1 * std::max(boundingBoxDiagonal(d_->scene.positions()), 1e-9);
    const double fit = radius / std::tan(0.5 * camera->GetViewAngle() * M_PI / 180.0);
    const double distance = std::min(current, fit);
    const Eigen::Vector3d eye = point - distance * direction;
    camera->SetFocalPoint(point.data());
    camera->SetPosition(eye.data());
    update();
}

Eigen::Vector3d MeshView::focalPoint() const {
    double f[3];
    d_->scene.renderer()->GetActiveCamera()->GetFocalPoint(f);
    return {f[0], f[1], f[2]};
}

QImage MeshView::grabImage() {
    return grabFramebuffer();
}

SurfacePoint MeshView::pickPoint(const QPoint& position) {
    if (!hasMesh()) return {};
    d_->syncSize();
    // The mesh may have moved since the last render; a stale clipping range would cut the ray.
    d_->scene.renderer()->ResetCameraClippingRange();
    double x, y;
    d_->toDisplay(position, x, y);
    return d_->scene.pick(x, y);
}

QPoint MeshView::projectVertex(int vertex) {
    if (vertex < 0 || vertex >= positions().rows()) return {-1, -1};
    return projectPoint(positions().row(vertex).transpose());
}

QPoint MeshView::projectPoint(const Eigen::Vector3d& point) {
    d_->syncSize();
    double x, y;
    d_->scene.project(point, x, y);
    const double ratio = devicePixelRatioF();
    return QPoint(int(std::lround(x / ratio)),
                  int(std::lround((d_->deviceSize().y() - 1 - y) / ratio)));
}

Eigen::Vector3d MeshView::cameraPosition() const {
    double p[3];
    d_->scene.renderer()->GetActiveCamera()->GetPosition(p);
    return {p[0], p[1], p[2]};
}

namespace {

QVariantList listOf(const double v[3]) {
    return {v[0], v[1], v[2]};
}

bool vectorOf(const QVariant& value, Eigen::Vector3d& v) {
    const QVariantList list = value.toList();
    if (list.size() != 3) return false;
    for (int k = 0; k < 3; ++k) {
        bool ok = false;
        v[k] = list[k].toDouble(&ok);
        if (!ok || !std::isfinite(v[k]) || std::abs(v[k]) > 1e12) return false;
    }
    return true;
}

}  // namespace

QVariantMap MeshView::cameraState() const {
    vtkCamera* camera = d_->scene.renderer()->GetActiveCamera();
    double p[3], f[3], up[3];
    camera->GetPosition(p);
    camera->GetFocalPoint(f);
    camera->GetViewUp(up);
    return {{"position", listOf(p)},
            {"focal_point", listOf(f)},
            {"view_up", listOf(up)},
            {"view_angle", camera->GetViewAngle()}};
}

bool MeshView::setCameraState(const QVariantMap& state) {
    Eigen::Vector3d p, f, up;
    bool ok = false;
    const double angle = state.value("view_angle").toDouble(&ok);
    if (!vectorOf(state.value("position"), p) || !vectorOf(state.value("focal_point"), f) ||
        !vectorOf(state.value("view_up"), up) || !ok || !(angle > 1 && angle < 179))
        return false;
    const Eigen::Vector3d direction = f - p;
    if (direction.norm() < 1e-9 || up.cross(direction).norm() < 1e-9 * direction.norm())
        return false;
    vtkCamera* camera = d_->scene.renderer()->GetActiveCamera();
    camera->SetPosition(p.data());
    camera->SetFocalPoint(f.data());
    camera->SetViewUp(up.data());
    camera->SetViewAngle(angle);
    camera->OrthogonalizeViewUp();
    d_->cameraPending = false;  // the first resize must not fit the mesh over it
    update();
    return true;
}

void MeshView::mousePressEvent(QMouseEvent* event) {
    switch (event->button()) {
        case Qt::LeftButton:
            d_->leftDown = true;
            d_->dragged = false;
            d_->pressPosition = event->position().toPoint();
            d_->forwardMouse(event, vtkCommand::LeftButtonPressEvent);
            break;
        case Qt::MiddleButton:
            d_->forwardMouse(event, vtkCommand::MiddleButtonPressEvent);
            break;
        case Qt::RightButton:
            d_->forwardMouse(event, vtkCommand::RightButtonPressEvent);
            break;
        default:
            break;
    }
}

void MeshView::mouseReleaseEvent(QMouseEvent* event) {
    switch (event->button()) {
        case Qt::LeftButton: {
            d_->forwardMouse(event, vtkCommand::LeftButtonReleaseEvent);
            const bool click = d_->leftDown && !d_->dragged;
            d_->leftDown = false;
            // A press and release without a drag is a pick; a drag only turns the camera.
            if (click) {
                const SurfacePoint point = pickPoint(event->position().toPoint());
                if (point.vertex >= 0)
                    emit pointPicked(point);
                else
                    emit pickMissed();
            }
            break;
        }
        case Qt::MiddleButton:
            d_->forwardMouse(event, vtkCommand::MiddleButtonReleaseEvent);
            break;
        case Qt::RightButton:
            d_->forwardMouse(event, vtkCommand::RightButtonReleaseEvent);
            break;
        default:
            break;
    }
}

void MeshView::mouseMoveEvent(QMouseEvent* event) {
    if (d_->leftDown && (event->position().toPoint() - d_->pressPosition).manhattanLength() > 3)
        d_->dragged = true;
    d_->forwardMouse(event, vtkCommand::MouseMoveEvent);
}

void MeshView::mouseDoubleClickEvent(QMouseEvent* event) {
    // Qt sends press, release, double-click, release: treat the second press as a press.
    mousePressEvent(event);
}

void MeshView::wheelEvent(QWheelEvent* event) {
    const double ratio = devicePixelRatioF();
    d_->interactor->SetEventInformationFlipY(int(event->position().x() * ratio),
                                             int(event->position().y() * ratio));
    const int delta = event->angleDelta().y();
    if (delta > 0) d_->interactor->InvokeEvent(vtkCommand::MouseWheelForwardEvent);
    if (delta < 0) d_->interactor->InvokeEvent(vtkCommand::MouseWheelBackwardEvent);
    event->accept();
}

void MeshView::keyPressEvent(QKeyEvent* event) {
    // VTK's own key bindings (q quits, 3 toggles stereo, ...) do not belong in an editor;
    // only the camera reset is kept. Everything else goes to the window's shortcuts.
    if (event->key() == Qt::Key_R && event->modifiers() == Qt::NoModifier) {
        resetCamera();
        event->accept();
        return;
    }
    QOpenGLWidget::keyPressEvent(event);
}

void MeshView::keyReleaseEvent(QKeyEvent* event) {
    QOpenGLWidget::keyReleaseEvent(event);
}

void MeshView::enterEvent(QEnterEvent* event) {
    d_->interactor->InvokeEvent(vtkCommand::EnterEvent);
    QOpenGLWidget::enterEvent(event);
}

void MeshView::leaveEvent(QEvent* event) {
    d_->interactor->InvokeEvent(vtkCommand::LeaveEvent);
    QOpenGLWidget::leaveEvent(event);
}

Eigen::Vector3d upAxisVector(const QString& axis) {
    const QString a = axis.trimmed().toLower();
    if (a.size() != 2 || (a[0] != '+' && a[0] != '-')) return Eigen::Vector3d::UnitY();
    const double sign = a[0] == '-' ? -1.0 : 1.0;
    if (a[1] == 'x') return sign * Eigen::Vector3d::UnitX();
    if (a[1] == 'y') return sign * Eigen::Vector3d::UnitY();
    if (a[1] == 'z') return sign * Eigen::Vector3d::UnitZ();
    return Eigen::Vector3d::UnitY();
}

}  // namespace boneless::ui
