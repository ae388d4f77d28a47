// MainWindow: the menu bar (File, Edit, View, Playback, Help) and the help boxes.
#include <tuple>

#include <QAction>
#include <QActionGroup>
#include <QKeySequence>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QSignalBlocker>
#include <QUndoStack>

#include "CalibrationMenu.h"
#include "EnableWhile.h"
#include "FrameDisplay.h"
#include "MenuText.h"
#include "ShortcutPassThrough.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Timeline.h"

namespace boneless::ui {

void MainWindow::buildMenus() {
    buildFileMenu();
    QMenu* edit = buildEditMenu();
    QMenu* view = buildViewMenu();
    addCalibrationActions(
        edit, view, document_, timeline_, display_,
        [this](const QString& message, const QString& detail) { showError(message, detail); });
    buildPlaybackMenu();
    buildHelpMenu();
}

void MainWindow::buildFileMenu() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("Open &Project…"), QKeySequence::Open, this, &MainWindow::chooseProject);
    file->addAction(tr("Open &Mesh…"), QKeySequence(Qt::CTRL | Qt::Key_M), this,
                    &MainWindow::chooseMesh)
        ->setObjectName("actionOpenMesh");
    file->addAction(tr("Open &Take…"), QKeySequence(Qt::CTRL | Qt::Key_T), this,
                    &MainWindow::chooseTake)
        ->setObjectName("actionOpenTake");
    QAction* openMap =
        file->addAction(tr("Open &Correspondence…"), this, &MainWindow::chooseCorrespondence);
    openMap->setObjectName("actionOpenCorrespondence");
    enableWhile(openMap, document_, always);  // a map opened is an edit
    file->addAction(tr("Open &Demo"), this, &MainWindow::openDemo);
    recentMenu_ = file->addMenu(tr("&Recent Files"));
    recentMenu_->setObjectName("recentMenu");
    connect(recentMenu_, &QMenu::aboutToShow, this, &MainWindow::rebuildRecentMenu);
    file->addSeparator();
    file->addAction(tr("&Save Project"), QKeySequence::Save, this, &MainWindow::saveProject);
    // Not QKeySequence::SaveAs: it has no key on Windows, nor on X11 without a desktop theme.
    file->addAction(tr("Save Project &As…"), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S), this,
                    &MainWindow::chooseSaveProjectAs);
    file->addAction(tr("Save Correspo&ndence As…"), this, &MainWindow::chooseSaveCorrespondence);
    file->addSeparator();
    file->addAction(tr("&Export…"), QKeySequence(Qt::CTRL | Qt::Key_E), this,
                    &MainWindow::showExportDialog)
        ->setObjectName("actionExport");
    file->addSeparator();
    file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);
}

QMenu* MainWindow::buildEditMenu() {
    QMenu* edit = menuBar()->addMenu(tr("&Edit"));
    QAction* undo = document_->undoStack()->createUndoAction(this, tr("&Undo"));
    undo->setObjectName("actionUndo");
    undo->setShortcut(undoRedoKeys()[0]);
    QAction* redo = document_->undoStack()->createRedoAction(this, tr("&Redo"));
    redo->setObjectName("actionRedo");
    redo->setShortcut(undoRedoKeys()[1]);
    // The stack's own text takes an edit's "&" (a marker or file named "R&D") for a mnemonic:
    // "Undo Clear RD", the D underlined. Set after the stack's, so this one is what shows.
    connect(document_->undoStack(), &QUndoStack::undoTextChanged, undo, [this, undo] {
        const QString text = document_->undoStack()->undoText();
        undo->setText(text.isEmpty() ? tr("&Undo") : tr("&Undo %1").arg(asWritten(text)));
    });
    connect(document_->undoStack(), &QUndoStack::redoTextChanged, redo, [this, redo] {
        const QString text = document_->undoStack()->redoText();
        redo->setText(text.isEmpty() ? tr("&Redo") : tr("&Redo %1").arg(asWritten(text)));
    });
    // Undo and redo are edits too: held while an export runs (after the stack's own enabling).
    QUndoStack* stack = document_->undoStack();
    const auto holdUndo = [this, stack, undo, redo] {
        undo->setEnabled(!document_->editsHeld() && stack->canUndo());
        redo->setEnabled(!document_->editsHeld() && stack->canRedo());
    };
    connect(stack, &QUndoStack::canUndoChanged, undo, holdUndo);
    connect(stack, &QUndoStack::canRedoChanged, redo, holdUndo);
    connect(document_, &Document::editsHeldChanged, undo, holdUndo);
    edit->addAction(undo);
    edit->addAction(redo);
    edit->addSeparator();
    edit->addAction(mappingAction_);
    // Mapping without the pointer: the vertex's number, as the Vertex column shows it.
    QAction* toVertex = edit->addAction(tr("Map Selected Marker to &Vertex…"),
                                        QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_M), this,
                                        &MainWindow::askVertexForSelected);
    toVertex->setObjectName("actionMapToVertex");
    enableWhile(toVertex, document_, hasMarkersToMap);
    QAction* suggest = edit->addAction(tr("&Suggest Rest"), this, &MainWindow::suggestMappings);
    suggest->setObjectName("actionSuggestRest");
    QAction* align = edit->addAction(tr("&Align Take to Mesh"), this, &MainWindow::alignTake);
    align->setObjectName("actionAlign");
    QAction* clear = edit->addAction(tr("&Clear Mapping"), this, [this] {
        if (document_->selectedMarker() >= 0) document_->clearMapping(document_->selectedMarker());
    });
    clear->setObjectName("actionClearMapping");
    QAction* clearAll =
        edit->addAction(tr("Clear A&ll Mappings"), document_, &Document::clearAllMappings);
    clearAll->setObjectName("actionClearAllMappings");
    edit->addAction(offsetAllAction_);
    enableWhile(suggest, document_, hasMeshAndTake);
    enableWhile(align, document_, hasMeshAndTake);
    enableWhile(clear, document_, hasSelectedMapping);
    enableWhile(clearAll, document_, hasMappings);
    return edit;
}

QMenu* MainWindow::buildViewMenu() {
    QMenu* view = menuBar()->addMenu(tr("&View"));
    view->addAction(tr("&Reset Camera"), QKeySequence(Qt::CTRL | Qt::Key_R), view_,
                    &MeshView::resetCamera);
    labelsAction_ = view->addAction(tr("Marker &Labels"));
    trailsAction_ = view->addAction(tr("Marker &Trails"));
    heatMapAction_ = view->addAction(tr("Shape Error &Heat Map"));
    followAction_ = view->addAction(tr("&Follow the Mesh"));
    followAction_->setObjectName("actionFollow");
    const std::pair<QAction*, const char*> toggles[] = {{labelsAction_, "labels"},
                                                        {trailsAction_, "trails"},
                                                        {heatMapAction_, "heatMap"},
                                                        {followAction_, "follow"}};
    for (const auto& [action, key] : toggles) {
        action->setCheckable(true);
        connect(action, &QAction::toggled, this,
                [this, action = action, key = QString(key)](bool on) {
                    if (action == labelsAction_) view_->setLabelsVisible(on);
                    if (action == trailsAction_) display_->setTrailsVisible(on);
                    if (action == heatMapAction_) display_->setHeatMapVisible(on);
                    if (action == followAction_) view_->setCameraFollow(on);
                    // Kept in the project as the frame and camera are (storeSession), not here:
                    // a display choice is no edit, to autosave, mark or ask about.
                });
    }
    const QSignalBlocker quiet(followAction_);  // on by default, not an edit of the session
    followAction_->setChecked(true);
    return view;
}

void MainWindow::buildPlaybackMenu() {
    // The timeline's Loop and speed box, with keys: before, only the pointer reached them.
    QMenu* playback = menuBar()->addMenu(tr("&Playback"));
    QAction* loop = playback->addAction(tr("&Loop"));
    loop->setObjectName("actionLoop");
    loop->setCheckable(true);
    loop->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_L));
    loop->setChecked(timeline_->loops());
    connect(loop, &QAction::toggled, timeline_, &Timeline::setLoop);
    connect(timeline_, &Timeline::loopChanged, loop, &QAction::setChecked);
    QMenu* speedMenu = playback->addMenu(tr("&Speed"));
    auto* speeds = new QActionGroup(speedMenu);
    const std::tuple<Timeline::Speed, QString, const char*> choices[] = {
        {Timeline::Speed::Realtime, tr("&Realtime"), "speedRealtime"},
        {Timeline::Speed::Half, tr("&Half Speed"), "speedHalf"},
        {Timeline::Speed::Quarter, tr("&Quarter Speed"), "speedQuarter"},
        {Timeline::Speed::EveryFrame, tr("&Every Frame"), "speedEveryFrame"}};
    int key = Qt::Key_1;
    for (const auto& [speed, text, name] : choices) {
        QAction* action = speedMenu->addAction(text);
        action->setObjectName(name);
        action->setCheckable(true);
        action->setData(int(speed));
        action->setShortcut(QKeySequence(Qt::CTRL | Qt::Key(key++)));
        speeds->addAction(action);
        connect(action, &QAction::triggered, timeline_,
                [this, speed = speed] { timeline_->setSpeed(speed); });
    }
    // The speed in use is checked, however it was set (the box, a project).
    const auto showSpeed = [this, speeds] {
        for (QAction* action : speeds->actions())
            action->setChecked(action->data().toInt() == int(timeline_->speed()));
    };
    connect(timeline_, &Timeline::speedChanged, speeds, showSpeed);
    showSpeed();
}

void MainWindow::buildHelpMenu() {
    QMenu* help = menuBar()->addMenu(tr("&Help"));
    help->addAction(
            tr("&Getting Started"), QKeySequence::HelpContents, this,
            [this] {
                showHelp(
                    tr("Getting Started"),
                    tr("<ol><li>File → Open Mesh (Ctrl+M): the character, OBJ/PLY/OFF/STL.</li>"
                       "<li>File → Open Take (Ctrl+T): the C3D motion capture.</li>"
                       "<li>Map markers: turn on Edit → Map Markers, select one in the Markers "
                       "list, click the mesh where it sits. After four, <i>Suggest rest</i> maps "
                       "the others; <i>Align</i> fixes "
                       "the take onto the mesh.</li>"
                       "<li>Play (Space), scrub the timeline, check the residual column.</li>"
                       "<li>File → Export (Ctrl+E): the frames, format and folder.</li></ol>"
                       "The README that comes with Boneless is the full manual."));
            })
        ->setObjectName("actionGettingStarted");
    help->addAction(tr("&Keyboard Shortcuts"), this,
                    [this] {
                        showHelp(
                            tr("Keyboard Shortcuts"),
                            tr("<table cellspacing=6>"
                               "<tr><td>Space</td><td>play / pause</td></tr>"
                               "<tr><td>← →</td><td>previous / next frame</td></tr>"
                               "<tr><td>Shift+← →</td><td>10 frames back / on</td></tr>"
                               "<tr><td>Home / End</td><td>first / last frame</td></tr>"
                               "<tr><td>PageUp / PageDown (slider focused)</td><td>a tenth "
                               "of the take on / back</td></tr>"
                               "<tr><td>frame box, Enter</td><td>go to the frame typed</td></tr>"
                               "<tr><td>Ctrl+L</td><td>loop on / off</td></tr>"
                               "<tr><td>Ctrl+1 … Ctrl+4</td><td>realtime, ½, ¼ speed, every "
                               "frame</td></tr>"
                               "<tr><td>Ctrl+O</td><td>open a project</td></tr>"
                               "<tr><td>Ctrl+M / Ctrl+T</td><td>open a mesh / a take</td></tr>"
                               "<tr><td>Ctrl+S / Ctrl+Shift+S</td><td>save / save as</td></tr>"
                               "<tr><td>Ctrl+E</td><td>export</td></tr>"
                               "<tr><td>Ctrl+Z / Ctrl+Shift+Z</td><td>undo / redo</td></tr>"
                               "<tr><td>Ctrl+R</td><td>reset the camera</td></tr>"
                               "<tr><td>Ctrl+Shift+M</td><td>map the selected marker to a "
                               "vertex typed</td></tr>"
                               "<tr><td>double-click a marker in the list</td><td>bring the "
                               "camera to it</td></tr>"
                               "<tr><td>mouse</td><td>left drag turns, right drag or wheel zooms, "
                               "middle drag pans; in Edit → Map Markers mode a click maps the "
                               "selected marker</td></tr>"
                               "</table>"));
                    })
        ->setObjectName("actionShortcuts");
    help->addSeparator();
    help->addAction(tr("&About Boneless"), this, [this] {
        QMessageBox::about(
            this, tr("About Boneless"),
            tr("<b>Boneless</b><br>Skeleton-free mesh animation from motion-capture "
               "markers (Kraevoy &amp; Sheffer).<br><br>Select a marker in the list, "
               "click the mesh to map it; drag to turn the camera."));
    });
}

void MainWindow::showHelp(const QString& title, const QString& html) {
    // Non-modal, so it can stay open beside the window while the user tries the keys.
    auto* box = new QMessageBox(QMessageBox::NoIcon, title, html, QMessageBox::Close, this);
    box->setObjectName("helpMessage");
    box->setTextFormat(Qt::RichText);
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->setModal(false);
    box->show();
}

}  // namespace boneless::ui
