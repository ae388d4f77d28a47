#include "CalibrationMenu.h"

#include <QAction>
#include <QActionGroup>
#include <QMenu>

#include "EnableWhile.h"
#include "FrameDisplay.h"
#include "boneless/Alignment.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/Timeline.h"

namespace boneless::ui {

namespace {

// A frame whose pose is far from the rest's (a stride) can align the body turned against its
// markers: CMU 85_02 at frame 300 on MakeHuman turned it about 90°, and only the status bar's
// figure said so. Warned by core's rule (alignsMuchWorse), as solve and batch warn.
void warnIfWorseThanAutomatic(const Document* document, const Timeline* timeline, int frame,
                              const std::function<void(const QString&, const QString&)>& warn) {
    const std::optional<Calibration> automatic = document->alignmentAt(-1);
    if (!automatic || automatic->frame == frame) return;
    // A fixed alignment was refitted at the frame already (calibrateAt).
    const std::optional<Calibration> chosen =
        document->alignment() ? document->alignment() : document->alignmentAt(frame);
    if (!chosen) return;
    const double unitToMm = document->take().unitToMm;
    const double chosenMm = chosen->residualMm(unitToMm);
    const double automaticMm = automatic->residualMm(unitToMm);
    if (!alignsMuchWorse(chosenMm, automaticMm)) return;
    warn(QObject::tr("Frame %1 aligns the take much worse than the automatic choice, frame %2: "
                     "alignment %3 mm (RMS), against %4 mm. Undo (Ctrl+Z) goes back; Edit → "
                     "Calibrate Automatically picks the automatic frame.")
             .arg(timeline->frameName(frame))
             .arg(timeline->frameName(automatic->frame))
             .arg(chosenMm, 0, 'f', 1)
             .arg(automaticMm, 0, 'f', 1),
         QObject::tr("A pose far from the rest's (a stride, a crouch) can align the body turned "
                     "against its markers, and the solve then bends the mesh to meet them. Said "
                     "when the frame's alignment is more than %1 times and %2 mm worse than the "
                     "automatic frame's. Undo (Ctrl+Z) goes back too.")
             .arg(kMuchWorseAlignmentRatio)
             .arg(kMuchWorseAlignmentMm));
}

}  // namespace

void addCalibrationActions(QMenu* edit, QMenu* view, Document* document, Timeline* timeline,
                           FrameDisplay* display,
                           const std::function<void(const QString&, const QString&)>& warn) {
    QAction* atFrame = edit->addAction(QObject::tr("Calibrate at &This Frame"), document, [=] {
        const int frame = timeline->frame();
        if (document->calibrateAt(frame)) warnIfWorseThanAutomatic(document, timeline, frame, warn);
    });
    atFrame->setObjectName("calibrateAtFrame");
    atFrame->setStatusTip(QObject::tr(
        "Fit the mesh to the actor at the frame on screen, and solve every frame against it"));
    QAction* automatic = edit->addAction(QObject::tr("Calibrate Automat&ically"), document,
                                         [=] { document->calibrateAt(-1); });
    automatic->setObjectName("calibrateAutomatically");
    // The way out when the mesh cannot reach the actor with a right map, as `solve --calibrate
    // none`.
    QAction* none = edit->addAction(QObject::tr("&Do Not Calibrate"), document, [=] {
        TakeSolveOptions settings = document->settings();
        settings.calibrate = CalibrateMode::None;
        document->setSettings(settings, QObject::tr("Do Not Calibrate"));
    });
    none->setObjectName("calibrateNone");
    none->setStatusTip(
        QObject::tr("Solve every frame against the rest as the mesh gives it (calibrate none)"));
    // Calibrating at a frame needs markers mapped to align; the modes are the take's settings.
    enableWhile(atFrame, document, hasMeshTakeAndMappings);
    for (QAction* action : {automatic, none}) enableWhile(action, document, hasTake);
    // The mode in use is checked, from the document's settings: a refused calibration, an undo
    // or a loaded project changes it without the menu.
    auto* modes = new QActionGroup(edit);
    for (QAction* action : {atFrame, automatic, none}) {
        action->setCheckable(true);
        modes->addAction(action);
    }
    auto showMode = [=] {
        const TakeSolveOptions& settings = document->settings();
        QAction* mode = settings.calibrate == CalibrateMode::None ? none
                        : settings.calibrationFrame >= 0          ? atFrame
                                                                  : automatic;
        mode->setChecked(true);
    };
    QObject::connect(document, &Document::settingsChanged, modes, showMode);
    for (QAction* action : {atFrame, automatic, none})
        QObject::connect(action, &QAction::triggered, modes, showMode);
    showMode();

    // The mesh's up, where the take's vertical goes (mesh_up): the guess fails for an actor who
    // never stands. The choices are the option's own, from the one table of options.
    QMenu* up = edit->addMenu(QObject::tr("Mesh U&p"));
    up->setObjectName("meshUp");
    enableWhile(up->menuAction(), document, hasMeshAndTake);  // the take's vertical goes there
    auto* ups = new QActionGroup(up);
    for (const std::string& choice : findTakeOption("mesh_up")->choices) {
        const bool guess = choice == "auto";
        QAction* action = up->addAction(guess ? QObject::tr("&Guessed from the Take")
                                              : QString::fromStdString(choice).toUpper());
        action->setObjectName(QString::fromStdString("meshUp" + choice));
        action->setCheckable(true);
        ups->addAction(action);
        QObject::connect(action, &QAction::triggered, document, [=] {
            TakeSolveOptions settings = document->settings();
            settings.meshUp = parseAxis(choice);
            // Named as the menu names it: "Undo Mesh Up +X".
            document->setSettings(settings,
                                  QObject::tr("Mesh Up %1").arg(action->text().remove('&')));
        });
    }
    auto showUp = [=] {
        const auto& meshUp = document->settings().meshUp;
        const QString name =
            QString::fromStdString("meshUp" + (meshUp ? axisName(*meshUp) : "auto"));
        for (QAction* action : ups->actions()) action->setChecked(action->objectName() == name);
    };
    QObject::connect(document, &Document::settingsChanged, ups, showUp);
    for (QAction* action : ups->actions())  // a refused change leaves the up in use checked
        QObject::connect(action, &QAction::triggered, ups, showUp);
    showUp();

    // The units the take's coordinates are in (take_units): a take whose file states others
    // (CMU 85_02 in metres under "mm") is read right without another tool editing the file.
    QMenu* units = edit->addMenu(QObject::tr("Ta&ke Units"));
    units->setObjectName("takeUnits");
    enableWhile(units->menuAction(), document, hasTake);
    auto* unitChoices = new QActionGroup(units);
    for (const std::string& choice : findTakeOption("take_units")->choices) {
        QAction* action = units->addAction(Document::takeUnitsName(choice));
        action->setObjectName(QString::fromStdString("takeUnits" + choice));
        action->setCheckable(true);
        unitChoices->addAction(action);
        QObject::connect(action, &QAction::triggered, document, [=] {
            TakeSolveOptions settings = document->settings();
            settings.takeUnits = choice;
            // Named as the menu names it: "Undo Take Units Metres (m)".
            document->setSettings(settings, QObject::tr("Take Units %1").arg(action->text()));
        });
    }
    auto showUnits = [=] {
        const QString name = QString::fromStdString("takeUnits" + document->settings().takeUnits);
        for (QAction* action : unitChoices->actions())
            action->setChecked(action->objectName() == name);
    };
    QObject::connect(document, &Document::settingsChanged, unitChoices, showUnits);
    for (QAction* action : unitChoices->actions())
        QObject::connect(action, &QAction::triggered, unitChoices, showUnits);
    showUnits();

    QMenu* show = view->addMenu(QObject::tr("&Show"));
    auto* group = new QActionGroup(show);
    const std::tuple<const char*, QString, FrameDisplay::Shown> choices[] = {
        {"showFrame", QObject::tr("&Frame"), FrameDisplay::Shown::Frame},
        {"showCalibratedRest", QObject::tr("&Calibrated Rest"),
         FrameDisplay::Shown::CalibratedRest},
        {"showRest", QObject::tr("&Rest"), FrameDisplay::Shown::Rest}};
    for (const auto& [name, text, shown] : choices) {
        QAction* action = show->addAction(text);
        action->setObjectName(name);
        action->setCheckable(true);
        action->setChecked(shown == display->shown());
        group->addAction(action);
        QObject::connect(action, &QAction::triggered, display,
                         [display, shown = shown] { display->setShown(shown); });
    }
}

}  // namespace boneless::ui
