#include "boneless/ui/MainWindow.h"

#include <QAbstractButton>
#include <QAbstractSpinBox>
#include <QAction>
#include <QComboBox>
#include <QDockWidget>
#include <QFileInfo>
#include <QFutureWatcher>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QInputDialog>
#include <QItemSelectionModel>
#include <QKeySequence>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QShortcut>
#include <QStatusBar>
#include <QTableView>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrentRun>
#include <cmath>
#include <utility>

#include "Counted.h"
#include "EnableWhile.h"
#include "FrameDisplay.h"
#include "MenuText.h"
#include "OffsetRow.h"
#include "ShortcutPassThrough.h"
#include "SuggestionHighlight.h"
#include "boneless/ActorCalibration.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/ui/AppIcon.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/ExportDialog.h"
#include "boneless/ui/ExportRunner.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/MarkerListModel.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Project.h"
#include "boneless/ui/Timeline.h"
#include "boneless/ui/TimelineStrip.h"
#include "boneless/ui/TimelineWidget.h"

namespace boneless::ui {

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent),
      document_(new Document(this)),
      solver_(new FrameSolver(this)),
      timeline_(new Timeline(this)),
      timelineWidget_(nullptr),
      view_(new MeshView),
      markerModel_(new MarkerListModel(document_, this)),
      proxy_(new MarkerFilterProxy(this)),
      display_(nullptr),
      autosave_(new ProjectAutosave(document_, this)),
      exportDialog_(new ExportDialog(document_, solver_, timeline_, this)) {
    setObjectName("mainWindow");
    // The About box shows its parent's icon.
    setWindowIcon(applicationIcon());
    auto* highlight = new SuggestionHighlight(document_, this);
    highlight->setSourceModel(markerModel_);
    proxy_->setSourceModel(highlight);
    display_ = new FrameDisplay(document_, solver_, timeline_, view_, markerModel_, this);
    // Frames are solved ahead only while playing, so that playback finds them solved (about a
    // quarter of a second at 30 Hz); scrubbing keeps the worker free for where the playhead stops.
    auto readAhead = [this] {
        solver_->setReadAhead(timeline_->isPlaying() ? 8 : 0, timeline_->loops());
    };
    connect(timeline_, &Timeline::playingChanged, solver_, readAhead);
    connect(timeline_, &Timeline::loopChanged, solver_, readAhead);

    // The timeline sits under the view, not in a dock, so it keeps the view's width.
    auto* centre = new QWidget;
    auto* layout = new QVBoxLayout(centre);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->setSpacing(2);
    timelineWidget_ = new TimelineWidget(timeline_);
    auto* strip = new TimelineStrip(document_, solver_, timeline_);
    strip->setSlider(timelineWidget_->slider());
    timelineWidget_->setOverview(strip);
    layout->addWidget(view_, 1);
    layout->addWidget(timelineWidget_);
    setCentralWidget(centre);

    buildMarkerDock();
    buildMenus();
    buildStatusBar();
    buildShortcuts();
    connectDocument();
    setAcceptDrops(true);
    resize(1200, 760);
    updateTitle();
}

MainWindow::~MainWindow() {
    // The solver's worker must stop before the document and view it reports to go away.
    solver_->cancelPending();
    disconnect(solver_, nullptr, this, nullptr);
    disconnect(solver_, nullptr, display_, nullptr);
    // The autosave's last save (its destructor) asks nothing of a window that is going.
    disconnect(autosave_, &ProjectAutosave::changedOnDisk, this, nullptr);
}

void MainWindow::buildMarkerDock() {
    auto* panel = new QWidget;
    auto* layout = new QVBoxLayout(panel);
    layout->setContentsMargins(4, 4, 4, 4);

    auto* filterRow = new QHBoxLayout;
    filterEdit_ = new QLineEdit;
    filterEdit_->setObjectName("markerFilter");
    filterEdit_->setPlaceholderText(tr("Filter labels"));
    filterEdit_->setClearButtonEnabled(true);
    filterEdit_->setAccessibleName(tr("Filter marker labels"));
    stateFilter_ = new QComboBox;
    stateFilter_->setAccessibleName(tr("Markers shown"));
    stateFilter_->addItem(tr("All"), int(MarkerFilterProxy::State::All));
    stateFilter_->addItem(tr("Mapped"), int(MarkerFilterProxy::State::Mapped));
    stateFilter_->addItem(tr("Unmapped"), int(MarkerFilterProxy::State::Unmapped));
    stateFilter_->addItem(tr("Visible"), int(MarkerFilterProxy::State::Visible));
    stateFilter_->addItem(tr("Missing"), int(MarkerFilterProxy::State::Missing));
    stateFilter_->addItem(tr("To check"), int(MarkerFilterProxy::State::ToCheck));
    filterRow->addWidget(filterEdit_, 1);
    filterRow->addWidget(stateFilter_);
    layout->addLayout(filterRow);
    connect(filterEdit_, &QLineEdit::textChanged, proxy_, &MarkerFilterProxy::setText);
    connect(stateFilter_, &QComboBox::currentIndexChanged, this, [this](int index) {
        proxy_->setState(MarkerFilterProxy::State(stateFilter_->itemData(index).toInt()));
    });

    markerTable_ = new QTableView;
    markerTable_->setObjectName("markerTable");
    markerTable_->setAccessibleName(tr("Markers"));
    markerTable_->setModel(proxy_);
    markerTable_->setSelectionBehavior(QAbstractItemView::SelectRows);
    markerTable_->setSelectionMode(QAbstractItemView::SingleSelection);
    markerTable_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    // One Tab stop, the arrows moving within: Tab went from cell to cell, changing the selected
    // marker, and never left, so the buttons under the table could not be reached.
    markerTable_->setTabKeyNavigation(false);
    markerTable_->verticalHeader()->hide();
    // The numbers keep their width; a long label is elided instead, so the Residual column is
    // never cut off.
    markerTable_->horizontalHeader()->setStretchLastSection(false);
    markerTable_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    markerTable_->horizontalHeader()->setSectionResizeMode(MarkerListModel::LabelColumn,
                                                           QHeaderView::Stretch);
    markerTable_->setTextElideMode(Qt::ElideMiddle);
    panel->setMinimumWidth(340);
    layout->addWidget(markerTable_, 1);
    connect(markerTable_, &QTableView::doubleClicked, this, [this](const QModelIndex& index) {
        if (!display_->frameMarker(proxy_->markerAt(index.row())))
            statusBar()->showMessage(tr("This marker has no place to show in this frame"), 5000);
    });
    connect(
        markerTable_->selectionModel(), &QItemSelectionModel::currentRowChanged, this,
        [this](const QModelIndex& current) {
            if (syncingTable_) return;  // the document's selection, shown: not a choice
            document_->setSelectedMarker(current.isValid() ? proxy_->markerAt(current.row()) : -1);
        });

    auto* buttons = new QHBoxLayout;
    auto* clear = new QPushButton(tr("Clear"));
    clear->setObjectName("clearMarker");
    clear->setToolTip(tr("Unmap the selected marker"));
    auto* suggest = new QPushButton(tr("Suggest rest"));
    suggest->setObjectName("suggestRest");
    suggest->setToolTip(
        tr("Map every unmapped marker where the mesh, fitted to the mapped ones, "
           "meets it (needs 4 mapped); doubtful ones are marked to check"));
    auto* align = new QPushButton(tr("Align"));
    align->setObjectName("alignTake");
    align->setToolTip(tr("Fix the take's alignment onto the mesh from the mapped markers"));
    // Mapping holds the picture still, so that each mapping's re-solve does not move the
    // surface under the cursor; leaving shows the playhead's frame again.
    mappingAction_ = new QAction(tr("&Map Markers"), this);
    mappingAction_->setObjectName("actionMapMarkers");
    mappingAction_->setCheckable(true);
    mappingAction_->setToolTip(tr("Hold the mesh and camera still while clicking markers onto it"));
    connect(mappingAction_, &QAction::toggled, this, [this](bool on) {
        if (on) timeline_->pause();
        display_->setFrozen(on);
    });
    for (auto changed : {&Document::meshChanged, &Document::takeChanged})
        connect(document_, changed, mappingAction_, [this] { mappingAction_->setChecked(false); });
    // Left when edits are held too: a click would map nothing.
    connect(document_, &Document::editsHeldChanged, mappingAction_, [this](bool held) {
        if (held) mappingAction_->setChecked(false);
    });
    auto* map = new QToolButton;
    map->setDefaultAction(mappingAction_);
    buttons->addWidget(map);
    buttons->addWidget(clear);
    buttons->addWidget(suggest);
    buttons->addWidget(align);
    layout->addLayout(buttons);
    // "All mapped"'s menu twin (Edit), as every panel button has one.
    offsetAllAction_ = new QAction(tr("Give All Mapped This &Offset"), this);
    offsetAllAction_->setObjectName("actionOffsetAll");
    offsetAllAction_->setStatusTip(
        tr("Give every mapped marker the offset off the skin in the Markers panel's box"));
    layout->addLayout(makeOffsetRow(document_, offsetAllAction_));
    // Enter presses a focused button, as Space does (only a dialog's buttons do by default).
    for (QPushButton* button : {clear, suggest, align}) button->setAutoDefault(true);
    // Ctrl+Z after typing an offset or a filter undoes the last edit, as everywhere else; the
    // boxes' own undo of the typing took it.
    passShortcuts(filterEdit_, undoRedoKeys());
    passShortcuts(panel->findChild<QAbstractSpinBox*>("offsetSpin"), undoRedoKeys());
    connect(clear, &QPushButton::clicked, this, [this] {
        if (document_->selectedMarker() >= 0) document_->clearMapping(document_->selectedMarker());
    });
    connect(suggest, &QPushButton::clicked, this, &MainWindow::suggestMappings);
    connect(align, &QPushButton::clicked, this, &MainWindow::alignTake);
    enableWhile(mappingAction_, document_, hasMarkersToMap);
    enableWhile(clear, document_, hasSelectedMapping);
    enableWhile(suggest, document_, hasMeshAndTake);
    enableWhile(align, document_, hasMeshAndTake);

    auto* dock = new QDockWidget(tr("Markers"), this);
    dock->setObjectName("markerDock");
    dock->setWidget(panel);
    dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
    addDockWidget(Qt::RightDockWidgetArea, dock);
}

void MainWindow::buildStatusBar() {
    frameLabel_ = new QLabel;
    solveLabel_ = new QLabel;
    residualLabel_ = new QLabel;
    frameLabel_->setObjectName("frameLabel");
    solveLabel_->setObjectName("solveLabel");
    residualLabel_->setObjectName("residualLabel");
    // A task with no measure of how far along it is (Suggest Rest): a busy bar while it runs.
    busyBar_ = new QProgressBar;
    busyBar_->setObjectName("busyBar");
    busyBar_->setAccessibleName(tr("Busy"));
    busyBar_->setRange(0, 0);
    busyBar_->setMaximumWidth(120);
    busyBar_->setVisible(false);
    statusBar()->addPermanentWidget(busyBar_);
    statusBar()->addPermanentWidget(frameLabel_);
    statusBar()->addPermanentWidget(solveLabel_);
    statusBar()->addPermanentWidget(residualLabel_);
    residualLabel_->setToolTip(
        tr("Residual: this frame's markers from where the posed mesh puts them (RMS and max).\n"
           "Alignment: the mapped markers, aligned, from their points on the mesh at the "
           "calibration frame (RMS)."));
    connect(display_, &FrameDisplay::statusChanged, this,
            [this](const QString& frame, const QString& solve, const QString& residual,
                   const QString& solveDetail) {
                frameLabel_->setText(frame);
                solveLabel_->setText(solve);
                solveLabel_->setToolTip(solveDetail);
                residualLabel_->setText(residual);
            });
    // A message's whole list while the message is up, else the message itself: the frame's
    // figures on the right cut a long one short, and its tooltip reads whole.
    connect(statusBar(), &QStatusBar::messageChanged, this, [this](const QString& message) {
        if (message.isEmpty() || message != detailedMessage_) statusBar()->setToolTip(message);
    });
}

void MainWindow::buildShortcuts() {
    auto add = [this](QKeySequence key, auto slot) {
        auto* shortcut = new QShortcut(key, this);
        connect(shortcut, &QShortcut::activated, timeline_, slot);
    };
    add(QKeySequence(Qt::Key_Space), [this] { timeline_->togglePlay(); });
    add(QKeySequence(Qt::Key_Right), [this] { timeline_->stepForward(1); });
    add(QKeySequence(Qt::Key_Left), [this] { timeline_->stepBackward(1); });
    add(QKeySequence(Qt::SHIFT | Qt::Key_Right), [this] { timeline_->stepForward(10); });
    add(QKeySequence(Qt::SHIFT | Qt::Key_Left), [this] { timeline_->stepBackward(10); });
    add(QKeySequence(Qt::Key_Home), [this] { timeline_->goToFirst(); });
    add(QKeySequence(Qt::Key_End), [this] { timeline_->goToLast(); });
    // A focused control keeps those keys it uses itself: Space presses a button or opens a
    // combo's list, ← and → move the marker table's cell cursor. Line edits and spin boxes keep
    // their editing keys without help; the frame box hands Space on (passShortcuts). The table's
    // Home and End (first and last cell of a row, which a row selection does not show) stay the
    // first and last frame; Ctrl+Home and Ctrl+End are its first and last marker.
    const QKeySequence space(Qt::Key_Space);
    for (auto* button : findChildren<QAbstractButton*>()) keepKeys(button, {space});
    for (auto* combo : findChildren<QComboBox*>())
        keepKeys(combo, {space, QKeySequence(Qt::Key_Home), QKeySequence(Qt::Key_End)});
    keepKeys(markerTable_, {QKeySequence(Qt::Key_Left), QKeySequence(Qt::Key_Right)});
}

void MainWindow::connectDocument() {
    connect(document_, &Document::errorOccurred, this, [this](const QString& message) {
        if (loadingProject_) return;  // openProject says it once, with the project's name
        if (opening_.isEmpty())
            showError(message);
        else
            showError(plainError(opening_), message);
    });
    connect(display_, &FrameDisplay::solverFailed, this, [this](const QString& message) {
        showError(tr("The take could not be solved with this map and settings."), message);
    });
    connect(display_, &FrameDisplay::solveRefused, this, [this](const QString& message) {
        showError(tr("%1 is too large to solve in the memory available: it is shown, unsolved.")
                      .arg(QFileInfo(document_->meshPath()).fileName()),
                  message);
    });
    connect(autosave_, &ProjectAutosave::failed, this,
            [this](const QString& message) { showError(message); });
    connect(autosave_, &ProjectAutosave::savedAgain, this, [this](const QString& path) {
        statusBar()->showMessage(tr("Saved again: the edits made meanwhile are in %1").arg(path),
                                 15000);
    });
    connect(autosave_, &ProjectAutosave::changedOnDisk, this, &MainWindow::askChangedOnDisk);
    connect(autosave_, &ProjectAutosave::aboutToSave, this, &MainWindow::storeSession,
            Qt::DirectConnection);
    // What closing or opening another file must not drop unasked (keepUnsavedWork): edits since
    // the state opened or saved, which undoing back to it takes away.
    const auto edited = [this] {
        if (!loading_) setUnsavedEdits(!document_->undoStack()->isClean());
    };
    connect(document_->undoStack(), &QUndoStack::indexChanged, this, edited);
    connect(autosave_, &ProjectAutosave::saved, this, [this](const QString& path) {
        if (demo_ || path != projectPath_) return;
        document_->undoStack()->setClean();  // the project file holds this state
        setUnsavedEdits(false);
    });
    connect(display_, &FrameDisplay::frameDisplayed, this, &MainWindow::frameDisplayed);
    connect(display_, &FrameDisplay::latencyMeasured, this, &MainWindow::latencyMeasured);
    connect(document_, &Document::selectionChanged, this, &MainWindow::syncTableSelection);
    connect(document_, &Document::takeChanged, this, &MainWindow::onTakeLoaded);
    connect(document_, &Document::meshChanged, this, &MainWindow::updateTitle);
    connect(view_, &MeshView::pointPicked, this, &MainWindow::onPointPicked);
    connect(view_, &MeshView::pickMissed, this, [this] {
        // Outside Map Markers a click beside the body is no attempt to map: nothing to say.
        if (!mappingAction_->isChecked()) return;
        const int selected = document_->selectedMarker();
        statusBar()->showMessage(selected >= 0
                                     ? tr("The click missed the mesh: nothing was mapped to %1")
                                           .arg(document_->markerLabel(selected))
                                     : tr("The click missed the mesh"),
                                 8000);
    });
    // An export solves the map, alignment and settings it started with: an edit made meanwhile
    // would not be in what it writes, so edits wait for it.
    connect(exportDialog_, &ExportDialog::runningChanged, document_, [this] { updateEditsHeld(); });
    // A suggestion made from inputs that changed while it ran is not theirs (the settings: their
    // mesh up).
    for (auto changed : {&Document::meshChanged, &Document::takeChanged,
                         &Document::correspondenceChanged, &Document::settingsChanged})
        connect(document_, changed, this, [this] { ++suggestInputs_; });
    connect(exportDialog_, &ExportDialog::finished, this, [this](bool ok, const QString& message) {
        if (ok)
            statusBar()->showMessage(message, 10000);
        else
            showError(message);
    });
}

void MainWindow::onTakeLoaded() {
    // A project's take: restoreSession() puts the start frame over the project's own.
    if (startFrame_ >= 0 && document_->hasTake() && !loadingProject_) {
        timeline_->setFrame(startFrame_);
        startFrame_ = -1;
    }
    updateTitle();
}

namespace {

// The speed's name in the project file.
const std::pair<Timeline::Speed, const char*> kSpeedNames[] = {
    {Timeline::Speed::Realtime, "realtime"},
    {Timeline::Speed::Half, "half"},
    {Timeline::Speed::Quarter, "quarter"},
    {Timeline::Speed::EveryFrame, "every_frame"}};

}  // namespace

// Where the user was: frame, speed, camera and the View menu's toggles go into the project's
// view settings.
void MainWindow::storeSession() {
    if (!document_->hasTake() && !document_->hasMesh()) return;
    if (document_->hasTake()) document_->setViewSetting("frame", timeline_->frame());
    for (const auto& [speed, name] : kSpeedNames)
        if (speed == timeline_->speed()) document_->setViewSetting("speed", QString(name));
    if (document_->hasMesh()) document_->setViewSetting("camera", view_->cameraState());
    const std::pair<QAction*, const char*> toggles[] = {{labelsAction_, "labels"},
                                                        {trailsAction_, "trails"},
                                                        {heatMapAction_, "heatMap"},
                                                        {followAction_, "follow"}};
    for (const auto& [action, key] : toggles) {
        // Follow is on unless the project says otherwise; the others are off.
        const bool stored = document_->viewSettings().value(key, action == followAction_).toBool();
        if (stored != action->isChecked()) document_->setViewSetting(key, action->isChecked());
    }
}

// A project opens where it was left, paused, or at the start frame asked for (--frame). What it
// does not give (the demo, an older file) is the default, never the previous project's: the first
// frame, the take's rate, the camera fitted to the mesh. What a hostile file holds there is
// checked: a frame out of range, an unknown speed or a camera that is not one count as not given.
void MainWindow::restoreSession() {
    timeline_->pause();
    const QVariantMap settings = document_->viewSettings();
    const QVariant frame = settings.value("frame");
    bool ok = false;
    const double f = frame.toDouble(&ok);
    const int start = std::exchange(startFrame_, -1);  // --frame
    if (start >= 0 && start < timeline_->frameCount())
        timeline_->setFrame(start);
    else
        timeline_->setFrame(
            ok && f >= 0 && f < timeline_->frameCount() && f == std::floor(f) ? int(f) : 0);
    const QString speedName = settings.value("speed").toString();
    timeline_->setSpeed(Timeline::Speed::Realtime);
    for (const auto& [speed, name] : kSpeedNames)
        if (speedName == name) timeline_->setSpeed(speed);
    // Without one, the camera fitted to the mesh as it loaded.
    if (settings.contains("camera")) view_->setCameraState(settings.value("camera").toMap());
}

void MainWindow::applyViewSettings() {
    const QVariantMap settings = document_->viewSettings();
    labelsAction_->setChecked(settings.value("labels").toBool());
    trailsAction_->setChecked(settings.value("trails").toBool());
    heatMapAction_->setChecked(settings.value("heatMap").toBool());
    followAction_->setChecked(settings.value("follow", true).toBool());
}

void MainWindow::setUnsavedEdits(bool edited) {
    unsavedEdits_ = edited;
    setWindowModified(edited);
}

void MainWindow::showStatus(const QString& message, const QString& detail, int timeoutMs) {
    detailedMessage_ = detail.isEmpty() ? QString() : message;
    statusBar()->showMessage(message, timeoutMs);
    statusBar()->setToolTip(detail);
}

void MainWindow::syncTableSelection(int marker) {
    const int row = proxy_->rowOfMarker(marker);
    QItemSelectionModel* selection = markerTable_->selectionModel();
    const QModelIndex current = selection->currentIndex();
    if (current.isValid() && current.row() == row) return;
    if (row < 0) {
        // The current row goes too: left on the marker selected before, a click on that row
        // again changed nothing, and Map Markers then moved the hidden marker, not the one the
        // list showed selected.
        syncingTable_ = true;
        selection->setCurrentIndex(QModelIndex(), QItemSelectionModel::Clear);
        syncingTable_ = false;
        return;
    }
    const QModelIndex index = proxy_->index(row, 0);
    selection->setCurrentIndex(index,
                               QItemSelectionModel::ClearAndSelect | QItemSelectionModel::Rows);
    markerTable_->scrollTo(index);
}

void MainWindow::onPointPicked(const SurfacePoint& point) {
    const int vertex = point.vertex;
    const int selected = document_->selectedMarker();
    // Only Map Markers maps: a click to look at the body must not move a marker.
    if (selected >= 0 && !mappingAction_->isChecked()) {
        const int onVertex = document_->markerForVertex(vertex);
        if (onVertex >= 0 && onVertex != selected) {
            document_->setSelectedMarker(onVertex);
            return;
        }
        statusBar()->showMessage(tr("Vertex %1 — turn on Edit → Map Markers to map %2 by clicking")
                                     .arg(vertex)
                                     .arg(document_->markerLabel(selected)),
                                 8000);
        return;
    }
    if (selected >= 0) {
        mapSelectedMarker(point);
        return;
    }
    const int onVertex = document_->markerForVertex(vertex);
    if (onVertex >= 0) {
        document_->setSelectedMarker(onVertex);
        return;
    }
    statusBar()->showMessage(
        mappingAction_->isChecked()
            ? tr("Vertex %1 — select a marker in the list, then click the mesh to map it")
                  .arg(vertex)
            : tr("Vertex %1 — Edit → Map Markers maps a marker by clicking").arg(vertex),
        8000);
}

void MainWindow::mapSelectedMarker(const SurfacePoint& point) {
    const int selected = document_->selectedMarker();
    if (!document_->assign(selected, point)) return;
    const QString label = document_->markerLabel(selected);
    statusBar()->showMessage(
        point.face >= 0
            ? tr("%1 mapped to face %2 by vertex %3").arg(label).arg(point.face).arg(point.vertex)
            : tr("%1 mapped to vertex %2").arg(label).arg(point.vertex),
        5000);
}

void MainWindow::askVertexForSelected() {
    const int selected = document_->selectedMarker();
    if (selected < 0) {
        statusBar()->showMessage(tr("Select a marker in the list first, then map it to a vertex"),
                                 8000);
        return;
    }
    // Only the mesh's vertices can be typed: the box stops at its last.
    const int last = document_->mesh().vertexCount() - 1;
    const int current = document_->mappedVertex(selected);
    bool ok = false;
    const int vertex = QInputDialog::getInt(
        this, tr("Map to Vertex"),
        // The dialog's label is its spin box's buddy: an "&" in a name would be a mnemonic.
        tr("The vertex of %1 that carries %2 (0 to %3):")
            .arg(asWritten(QFileInfo(document_->meshPath()).fileName()),
                 asWritten(document_->markerLabel(selected)))
            .arg(last),
        std::max(current, 0), 0, last, 1, &ok);
    if (ok) mapSelectedMarker(SurfacePoint{vertex});
}

struct MainWindow::SuggestJob {
    Document::SuggestInputs read;
    quint64 inputs = 0;             // suggestInputs_ when it started
    std::atomic<bool> stop{false};  // the window closed: the app waits for no fit
    Suggestion result;
    QString error;
};

bool MainWindow::isSuggesting() const {
    return suggestJob_ != nullptr;
}

void MainWindow::stopSuggesting() {
    if (suggestJob_) suggestJob_->stop = true;
}

void MainWindow::updateEditsHeld() {
    // An export solves the map, alignment and settings it started with, and a suggestion adds to
    // the map it started from: an edit made meanwhile would be lost, so edits wait for both.
    if (exportDialog_->runner()->isRunning())
        document_->holdEdits(tr("An export is running: edits wait until it ends or is cancelled."));
    else if (suggestJob_)
        document_->holdEdits(tr("Suggest Rest is running: edits wait until it ends."));
    else
        document_->holdEdits({});
}

bool MainWindow::suggestMappings() {
    if (suggestJob_) {
        statusBar()->showMessage(tr("Suggest Rest is already running"), 5000);
        return false;
    }
    if (!document_->canSuggest()) return false;
    auto job = std::make_shared<SuggestJob>();
    job->read = document_->suggestInputs();
    job->inputs = suggestInputs_;
    suggestJob_ = job;
    updateEditsHeld();
    busyBar_->setVisible(true);
    statusBar()->showMessage(tr("Suggesting the rest of the map for %1…")
                                 .arg(QFileInfo(document_->meshPath()).fileName()));
    // The worker shares the job, so a window closed meanwhile leaves it whole; the watcher, the
    // window's, goes with the window.
    auto* watcher = new QFutureWatcher<void>(this);
    connect(watcher, &QFutureWatcher<void>::finished, this, [this, watcher] {
        watcher->deleteLater();
        finishSuggestion();
    });
    watcher->setFuture(QtConcurrent::run([job] {
        try {
            job->result = Document::suggest(job->read, &job->stop);
        } catch (const std::exception& e) {
            job->error = QString::fromStdString(e.what());
        }
    }));
    return true;
}

void MainWindow::finishSuggestion() {
    const std::shared_ptr<SuggestJob> job = std::move(suggestJob_);
    if (!job) return;
    busyBar_->setVisible(false);
    updateEditsHeld();
    if (!job->error.isEmpty()) {
        statusBar()->clearMessage();
        showError(tr("Suggest Rest failed."), job->error);
        emit suggestionFinished(false);
        return;
    }
    if (job->result.stopped) {
        statusBar()->showMessage(tr("Suggest Rest was stopped: nothing was mapped"), 10000);
        emit suggestionFinished(false);
        return;
    }
    if (job->inputs != suggestInputs_) {
        statusBar()->showMessage(
            tr("Suggest Rest was dropped: the mesh, take or map changed while it ran"), 10000);
        emit suggestionFinished(false);
        return;
    }
    Suggestion& s = job->result;
    const int suggested = s.suggested, toCheck = s.needsReview;
    QStringList offBody;
    for (const std::string& label : s.offBody) offBody << QString::fromStdString(label);
    document_->applySuggestion(std::move(s));
    // What this click added: markers suggested by an earlier click are the user's map by now.
    QString message;
    if (suggested == 0 && offBody.isEmpty())
        message = tr("Nothing to suggest: every marker seen in the take is mapped");
    else
        message = counted(suggested, tr("%n marker suggested"), tr("%n markers suggested"));
    if (toCheck > 0)
        message += tr(", %1 of them to check: the list's \"To check\" shows them").arg(toCheck);
    // A prop's or another actor's markers: no place on this body, so none was given.
    // Named a few at a time: the status bar cuts off what does not fit, the tooltip has them all.
    if (!offBody.isEmpty())
        message +=
            counted(offBody.size(), tr("; %n left unmapped, more than %1 mm from the body: %2"),
                    tr("; %n left unmapped, more than %1 mm from the body: %2"))
                .arg(kUnreachableMm)
                .arg(firstFew(offBody));
    showStatus(message,
               offBody.isEmpty() ? QString()
                                 : tr("Left unmapped, more than %1 mm from the body: %2")
                                       .arg(kUnreachableMm)
                                       .arg(offBody.join(", ")),
               toCheck == 0 && offBody.isEmpty() ? 10000 : 15000);
    emit suggestionFinished(true);
}

void MainWindow::alignTake() {
    // At the user's calibration frame when one is set: the solver aligns and fits at one frame,
    // so an alignment made elsewhere would move the calibration there.
    if (!document_->align(document_->settings().calibrationFrame)) return;
    const Calibration& aligned = *document_->alignment();
    statusBar()->showMessage(
        tr("Aligned at frame %1: the mapped markers sit %2 mm (RMS) from their points on the mesh")
            .arg(timeline_->frameName(aligned.frame))
            .arg(aligned.residualMm(document_->take().unitToMm), 0, 'f', 1),
        10000);
}

int MainWindow::displayedFrame() const {
    return display_->displayedFrame();
}
bool MainWindow::frameUpToDate() const {
    return display_->upToDate();
}
bool MainWindow::isSolving() const {
    return display_->solving();
}

QString MainWindow::frameSummary() const {
    QStringList parts;
    for (const QLabel* label : {frameLabel_, solveLabel_, residualLabel_})
        if (!label->text().isEmpty()) parts << label->text();
    return parts.join(" · ");
}

QMessageBox* MainWindow::errorBox(const QString& message, const QString& detail) {
    // Not exec(): a nested event loop would hold back frames and tests; the box just stays up.
    auto* box =
        new QMessageBox(QMessageBox::Warning, tr("Boneless"), message, QMessageBox::Ok, this);
    box->setObjectName("errorMessage");
    box->setDetailedText(detail);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->setModal(false);
    return box;
}

void MainWindow::showError(const QString& message, const QString& detail) {
    statusBar()->showMessage(message, 15000);
    emit errorShown(detail.isEmpty() ? message : message + "\n" + detail);
    if (!messageBoxes_) return;
    if (asking_)
        heldErrors_.emplace_back(message, detail);
    else
        errorBox(message, detail)->show();
}

}  // namespace boneless::ui
