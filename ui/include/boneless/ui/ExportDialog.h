#pragma once

#include <QDialog>
#include <QStringList>
#include <deque>
#include <functional>

#include "boneless/OutputFolder.h"
#include "boneless/TakeExport.h"

class QButtonGroup;
class QCheckBox;
class QComboBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QRadioButton;
class QSpinBox;

namespace boneless::ui {

class Document;
class ExportRunner;
class FrameSolver;
class Timeline;

// File → Export: which frames (all, in–out, the current one), the format (core's table), the
// folder, whether to write the calibrated rest beside the frames, an estimate of the time before
// starting, then a progress bar with the time left and Cancel. The estimate comes from a few
// frames across the take solved as the export solves them, on one core each
// (FrameSolver::timeFrames), timed each time the dialog shows and when the problem changes; the
// preview's frames are no measure (their loops share the cores with the drawing). A cancelled
// export's
// sidecar says "complete": false. After a run the bar keeps the frames it wrote ("12 / 60 frames:
// cancelled") until the frames to write change or another run starts.
class ExportDialog : public QDialog {
    Q_OBJECT
  public:
    enum class Range { All, InOut, Current };

    ExportDialog(Document* document, FrameSolver* solver, Timeline* timeline,
                 QWidget* parent = nullptr);
    ~ExportDialog() override;

    void setRange(Range range);
    Range range() const;
    void setInOut(int in, int out);  // inclusive, 0-based
    void setFolder(const QString& folder);
    QString folder() const;
    // The saved project the export belongs to (empty: untitled or the demo); the folder offered
    // is beside it until the user picks another.
    void setProjectPath(const QString& path);
    void setFormat(ExportFormat format);
    // What Export would start: the document's request for the folder, format and frames.
    ExportRequest request() const;
    int frameCountToWrite() const;
    // Median milliseconds of the frames timed for this problem; 0 when none.
    double measuredMsPerFrame() const;
    // The estimate for the chosen frames in milliseconds, the solver's preparation included
    // (FrameSolver::preparationMs); 0 when nothing is measured yet.
    double estimatedMs() const;

    // The widgets have object names for tests: exportFormat, exportCalibratedRest, exportEstimate,
    // exportProgress, exportProgressText, exportStart, exportCancel, exportBrowse.
    ExportRunner* runner() const { return runner_; }
    // Milliseconds since an arbitrary origin, read for the time left; replaceable so that tests
    // drive time themselves.
    void setClock(std::function<qint64()> clock) { clock_ = std::move(clock); }

  public slots:
    // Starts writing (false with the reason in the dialog when refused).
    bool startExport();
    void cancelExport();
    // Closing while writing asks whether to stop the export (Stop Export / Keep Exporting).
    void reject() override;
    // The app's `window` closing: false when an export runs and the user keeps it (Keep
    // Exporting, the default). True leaves the export running: the caller stops it once nothing
    // else keeps the window open (cancelExport).
    bool mayCloseApp(QWidget* window);

  signals:
    // As ExportRunner::finished: the message names the folder or the reason.
    void finished(bool ok, const QString& message);
    // An export started (true) or ended, finished, cancelled or failed (false).
    void runningChanged(bool running);

  protected:
    void showEvent(QShowEvent* event) override;
    bool event(QEvent* event) override;              // layout requests: fitHeight()
    void resizeEvent(QResizeEvent* event) override;  // narrower: fitHeight()

  private:
    // At least as tall as the wrapped messages need at this width (see ExportDialog.cpp).
    void fitHeight();
    std::vector<std::string> replaced_;  // an earlier export's files the running one replaces
    ExportRequest running_;              // what the running export writes
    void syncFromDocument();
    void timeFrames();  // asks the solver to time a few frames for the estimate
    void updateEstimate();
    void onProgress(int done, int total);
    void onFinished(bool ok, const QString& message);
    // The bar counts the frames to write again, not the last run's.
    void forgetLastRun();
    // Asks whether to replace the earlier export's files `names` in the folder: by whose solve
    // it is when `other`, another take's or actor's (core's otherSolveIn, as `solve` refuses it),
    // this export animating `subjects`.
    bool askToReplace(const std::vector<std::string>& names, const OtherSolve* other = nullptr,
                      const std::vector<std::string>& subjects = {});
    // Asks whether to write over `names`, files of the outputs' names that no export wrote.
    bool askToReplaceOthersFiles(const std::vector<std::string>& names);
    // The question both ask (Replace / Cancel, Cancel the default), named `name`: true for Replace.
    bool askReplace(const QString& text, const char* name, const QString& informative);
    QString listed(const std::vector<std::string>& names) const;
    // Asks whether to stop the running export, over the dialog or, when the app's window
    // `closing` closes, over it naming how far the export got; true for Stop Export.
    bool askToStop(QWidget* closing = nullptr);
    // After a run, finished or cancelled: removes the earlier export's files it did not write
    // again, which would pass for its, and returns their names.
    QStringList removeReplaced(const ExportRequest& request, const ExportResult& result);
    void setRunning(bool running);

    Document* document_;
    FrameSolver* solver_;
    Timeline* timeline_;
    ExportRunner* runner_;
    std::deque<double> solveMs_;  // the timed frames' solve times, this problem's

    QButtonGroup* rangeGroup_;
    QRadioButton *all_, *inOut_, *current_;
    QSpinBox *in_, *out_;
    QComboBox* format_;
    QLineEdit* folder_;
    QPushButton* browse_;
    QString projectPath_;
    bool folderChosen_ = false;  // by the user, for this project: not replaced by the default
    QCheckBox* calibratedRest_;
    QLabel* estimate_;
    QProgressBar* progress_;
    QLabel* progressText_;
    bool lastRunShown_ = false;  // the bar shows how far the last run got
    QPushButton *start_, *cancel_, *close_;
    std::function<qint64()> clock_;
    qint64 startedMs_ = 0;  // when the running export started
    // When its solver was prepared and its first frame began (-1: not yet).
    qint64 framesFromMs_ = -1;
};

}  // namespace boneless::ui
