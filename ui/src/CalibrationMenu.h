#pragma once

#include <functional>

class QMenu;
class QString;

namespace boneless::ui {

class Document;
class FrameDisplay;
class Timeline;

// The app's side of actor calibration (docs/calibration.md):
//  Edit → Calibrate at This Frame / Calibrate Automatically: the frame the take is aligned and
//    the rest fitted at (the project's settings.calibration_frame), and calibration on; a frame
//    that aligns much worse than the automatic choice is warned about through `warn` (a message
//    and its detail), naming both residuals and the way back;
//  Edit → Do Not Calibrate: calibrate none, frames solved against the rest as given;
//    of these three, the mode in use is checked (the document's settings, through undo);
//  Edit → Mesh Up → Guessed from the Take / +X … -Z: the project's settings.mesh_up, checked;
//  Edit → Take Units → From the File / Millimetres (mm) … Feet (ft): settings.take_units, checked;
//  View → Show → Frame / Calibrated Rest / Rest: what the view draws (FrameDisplay::Shown), and
//    the status bar says which rest is shown.
// The actions' object names: calibrateAtFrame, calibrateAutomatically, calibrateNone, meshUpauto,
// meshUp+x … meshUp-z, takeUnits, takeUnitsfile, takeUnitsmm … takeUnitsft, showFrame,
// showCalibratedRest, showRest.
void addCalibrationActions(QMenu* edit, QMenu* view, Document* document, Timeline* timeline,
                           FrameDisplay* display,
                           const std::function<void(const QString&, const QString&)>& warn);

}  // namespace boneless::ui
