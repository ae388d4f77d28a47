#include "boneless/ui/ExportDialog.h"
#include "boneless/OutputFolder.h"

#include <QButtonGroup>
#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QElapsedTimer>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QRadioButton>
#include <QResizeEvent>
#include <QSettings>
#include <QSpinBox>
#include <QStandardPaths>
#include <QVBoxLayout>
#include <algorithm>
#include <memory>
#include <set>
#include <vector>

#include "Counted.h"
#include "boneless/Parallel.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/ExportRunner.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/Timeline.h"

namespace boneless::ui {

namespace {

constexpr std::size_t kSamples = 32;
constexpr int kTimedFrames = 3;  // timed each time the problem changes while the dialog shows

// "about 45 s", "about 3 min 20 s", "under a second".
QString duration(double ms) {
    const int s = int(ms / 1000.0 + 0.5);
    if (s < 1) return QObject::tr("under a second");
    if (s < 60) return QObject::tr("about %1 s").arg(s);
    return QObject::tr("about %1 min %2 s").arg(s / 60).arg(s % 60);
}

// Where an export goes unless the user picks a folder: beside the saved project, else the last
// folder exported into, else the user's documents; never beside the mesh, which may sit in a
// shared, read-only library.
QString defaultFolder(const QString& projectPath) {
    if (!projectPath.isEmpty()) {
        const QFileInfo project(projectPath);
        return project.absolutePath() + "/" + project.completeBaseName() + "_export";
    }
    const QString last = QSettings().value("export/folder").toString();
    if (!last.isEmpty()) return last;
    return QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation) + "/Boneless";
}

}  // namespace

ExportDialog::ExportDialog(Document* document, FrameSolver* solver, Timeline* timeline,
                           QWidget* parent)
    : QDialog(parent),
      document_(document),
      solver_(solver),
      timeline_(timeline),
      runner_(new ExportRunner(this)) {
    auto monotonic = std::make_shared<QElapsedTimer>();
    monotonic->start();
    clock_ = [monotonic] { return monotonic->elapsed(); };
    setObjectName("exportDialog");
    setWindowTitle(tr("Export"));

    all_ = new QRadioButton(tr("All frames"));
    inOut_ = new QRadioButton(tr("Frames"));
    current_ = new QRadioButton(tr("Current frame"));
    rangeGroup_ = new QButtonGroup(this);
    rangeGroup_->addButton(all_, int(Range::All));
    rangeGroup_->addButton(inOut_, int(Range::InOut));
    rangeGroup_->addButton(current_, int(Range::Current));
    all_->setChecked(true);
    in_ = new QSpinBox;
    out_ = new QSpinBox;
    in_->setObjectName("exportIn");
    out_->setObjectName("exportOut");
    in_->setAccessibleName(tr("First frame to export"));
    out_->setAccessibleName(tr("Last frame to export"));
    auto* inOutRow = new QHBoxLayout;
    inOutRow->addWidget(inOut_);
    inOutRow->addWidget(in_);
    inOutRow->addWidget(new QLabel(tr("to")));
    inOutRow->addWidget(out_);
    inOutRow->addStretch(1);
    auto* rangeBox = new QVBoxLayout;
    rangeBox->addWidget(all_);
    rangeBox->addLayout(inOutRow);
    rangeBox->addWidget(current_);

    format_ = new QComboBox;
    format_->setObjectName("exportFormat");
    format_->setAccessibleName(tr("Format"));  // a combo box is read by its value, not its label
    for (const ExportFormatInfo& f : exportFormats())
        format_->addItem(QString::fromUtf8(f.description), int(f.format));

    folder_ = new QLineEdit;
    folder_->setObjectName("exportFolder");
    connect(folder_, &QLineEdit::textEdited, this, [this] { folderChosen_ = true; });
    // The last run's message and count describe what it wrote, where: not another folder's.
    connect(folder_, &QLineEdit::textChanged, this, [this] {
        forgetLastRun();
        updateEstimate();
    });
    connect(format_, &QComboBox::currentIndexChanged, this, [this] {
        forgetLastRun();
        updateEstimate();
    });
    browse_ = new QPushButton(tr("Browse…"));
    browse_->setObjectName("exportBrowse");
    auto* folderRow = new QHBoxLayout;
    folderRow->addWidget(folder_, 1);
    folderRow->addWidget(browse_);

    // The rest the frames were solved against: what a user needs to rebuild the rig elsewhere,
    // in the input's vertex order, beside the frames (as solve --write-calibrated-rest).
    calibratedRest_ =
        new QCheckBox(tr("Also write the calibrated rest (the mesh fitted to the actor)"));
    calibratedRest_->setObjectName("exportCalibratedRest");
    calibratedRest_->setChecked(QSettings().value("export/calibratedRest", false).toBool());

    estimate_ = new QLabel;
    estimate_->setObjectName("exportEstimate");
    progress_ = new QProgressBar;
    progress_->setObjectName("exportProgress");
    progress_->setAccessibleName(tr("Export progress"));
    progress_->setValue(0);
    progressText_ = new QLabel;
    progressText_->setObjectName("exportProgressText");
    // A run's message (a cancel's names the folder and the frames written) wraps: on one line
    // it widened the dialog to about 770 px.
    progressText_->setWordWrap(true);
    estimate_->setWordWrap(true);

    auto* form = new QFormLayout;
    form->addRow(tr("Range:"), rangeBox);
    form->addRow(tr("Format:"), format_);
    // A row of a layout gets no buddy from the form: the label names the folder box itself.
    auto* folderLabel = new QLabel(tr("Folder:"));
    folderLabel->setBuddy(folder_);
    form->addRow(folderLabel, folderRow);
    form->addRow(QString(), calibratedRest_);
    form->addRow(tr("Time:"), estimate_);

    auto* buttons = new QDialogButtonBox;
    start_ = buttons->addButton(tr("Export"), QDialogButtonBox::AcceptRole);
    cancel_ = buttons->addButton(tr("Cancel Export"), QDialogButtonBox::ActionRole);
    close_ = buttons->addButton(QDialogButtonBox::Close);
    start_->setObjectName("exportStart");
    cancel_->setObjectName("exportCancel");

    auto* layout = new QVBoxLayout(this);
    layout->addLayout(form);
    layout->addWidget(progress_);
    layout->addWidget(progressText_);
    layout->addWidget(buttons);
    // Enter exports. Made default only once the dialog holds it (before, the call did nothing and
    // the dialog took its first button, Browse…, so Enter in the folder field opened a browser).
    browse_->setAutoDefault(false);
    start_->setDefault(true);
    setRunning(false);

    connect(start_, &QPushButton::clicked, this, &ExportDialog::startExport);
    connect(cancel_, &QPushButton::clicked, this, &ExportDialog::cancelExport);
    connect(close_, &QPushButton::clicked, this, &ExportDialog::reject);
    connect(browse_, &QPushButton::clicked, this, [this] {
        const QString chosen =
            QFileDialog::getExistingDirectory(this, tr("Export Into"), folder_->text());
        if (!chosen.isEmpty()) setFolder(chosen);
    });
    connect(rangeGroup_, &QButtonGroup::idClicked, this, [this] {
        forgetLastRun();
        updateEstimate();
    });
    // Editing the frames means exporting them.
    for (QSpinBox* box : {in_, out_})
        connect(box, &QSpinBox::valueChanged, this, [this] {
            inOut_->setChecked(true);
            forgetLastRun();
            updateEstimate();
        });
    connect(timeline_, &Timeline::frameChanged, this, &ExportDialog::updateEstimate);
    // Frames solved as the export solves them, not the preview's: see FrameSolver::timeFrames.
    connect(solver_, &FrameSolver::frameTimed, this, [this](int, double ms, quint64 generation) {
        if (generation != solver_->generation() || ms <= 0) return;
        solveMs_.push_back(ms);
        if (solveMs_.size() > kSamples) solveMs_.pop_front();
        updateEstimate();
    });
    connect(solver_, &FrameSolver::problemChanged, this, [this] {
        solveMs_.clear();  // another mesh, take, map or settings: another time a frame
        if (!runner_->isRunning()) forgetLastRun();  // and other frames than the last run wrote
        if (isVisible()) timeFrames();
        updateEstimate();
    });
    connect(runner_, &ExportRunner::prepared, this, [this] { framesFromMs_ = clock_(); });
    connect(runner_, &ExportRunner::progress, this,
            [this](int done, int total, double) { onProgress(done, total); });
    connect(runner_, &ExportRunner::finished, this, &ExportDialog::onFinished);
    // The calibrated rest's box follows calibration being turned on or off.
    connect(document_, &Document::settingsChanged, this,
            [this] { setRunning(runner_->isRunning()); });
    forgetLastRun();
    updateEstimate();
}

ExportDialog::~ExportDialog() = default;

void ExportDialog::setRange(Range range) {
    rangeGroup_->button(int(range))->setChecked(true);
    forgetLastRun();
    updateEstimate();
}

ExportDialog::Range ExportDialog::range() const {
    return Range(rangeGroup_->checkedId());
}

void ExportDialog::setInOut(int in, int out) {
    in_->setValue(in);
    out_->setValue(out);
}

void ExportDialog::setFolder(const QString& folder) {
    folder_->setText(folder);
    folderChosen_ = true;
}

void ExportDialog::setProjectPath(const QString& path) {
    if (path == projectPath_) return;
    projectPath_ = path;
    folderChosen_ = false;  // a folder picked for another project is not this one's
}

QString ExportDialog::folder() const {
    return folder_->text().trimmed();
}

void ExportDialog::setFormat(ExportFormat format) {
    format_->setCurrentIndex(format_->findData(int(format)));
}

ExportRequest ExportDialog::request() const {
    ExportRequest r =
        document_->exportRequest(folder(), ExportFormat(format_->currentData().toInt()));
    r.writeCalibratedRest =
        calibratedRest_->isChecked() && r.options.calibrate != CalibrateMode::None;
    switch (range()) {
        case Range::All:
            break;
        case Range::InOut:
            r.first = std::min(in_->value(), out_->value());
            r.end = std::max(in_->value(), out_->value()) + 1;
            break;
        case Range::Current:
            r.first = timeline_->frame();
            r.end = r.first + 1;
            break;
    }
    return r;
}

int ExportDialog::frameCountToWrite() const {
    const ExportRequest r = request();
    const int count = document_->frameCount();
    return std::max(0, (r.end < 0 ? count : std::min(r.end, count)) - r.first);
}

double ExportDialog::measuredMsPerFrame() const {
    if (solveMs_.empty()) return 0;
    std::vector<double> sorted(solveMs_.begin(), solveMs_.end());
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    return sorted[sorted.size() / 2];
}

double ExportDialog::estimatedMs() const {
    // The export solves a frame on each core at once, each as long as a frame timed alone on one,
    // after preparing its solver as the app did for the same problem (24.9 s of the koala's 62 s
    // went there, before the first frame).
    const int frames = frameCountToWrite();
    const double ms = measuredMsPerFrame();
    if (ms <= 0) return 0;
    const int workers = std::max(1, std::min(solverThreadCount(), frames));
    return solver_->preparationMs() + frames * ms / workers;
}

void ExportDialog::syncFromDocument() {
    const int last = std::max(0, document_->frameCount() - 1);
    for (QSpinBox* box : {in_, out_}) {
        const QSignalBlocker block(box);
        box->setRange(0, last);
    }
    if (out_->value() == 0) {
        const QSignalBlocker block(out_);
        out_->setValue(last);
    }
    current_->setText(tr("Current frame (%1, capture frame %2)")
                          .arg(timeline_->frame())
                          .arg(timeline_->captureFrame(timeline_->frame())));
    if (!folderChosen_) folder_->setText(defaultFolder(projectPath_));
}

void ExportDialog::updateEstimate() {
    current_->setText(tr("Current frame (%1, capture frame %2)")
                          .arg(timeline_->frame())
                          .arg(timeline_->captureFrame(timeline_->frame())));
    const int frames = frameCountToWrite();
    // Before a run, the bar counts the frames the chosen range would write (not Qt's 0 / 100);
    // after one, how far it got.
    if (!runner_->isRunning() && !lastRunShown_) {
        progress_->setRange(0, std::max(1, frames));
        progress_->setValue(0);
    }
    const QString frameCount = counted(frames, tr("%n frame"), tr("%n frames"));
    const double ms = measuredMsPerFrame();
    if (ms <= 0) {
        estimate_->setText(tr("%1; measuring the time a frame takes…").arg(frameCount));
        return;
    }
    const int workers = std::max(1, std::min(solverThreadCount(), frames));
    estimate_->setText(
        counted(workers, tr("%1, %2 (preparing %3, then %4 ms a frame on one core)"),
                tr("%1, %2 (preparing %3, then %4 ms a frame on one core, %n at once)"))
            .arg(frameCount, duration(estimatedMs()), duration(solver_->preparationMs()))
            .arg(ms, 0, 'f', 0));
}

void ExportDialog::timeFrames() {
    // A few frames across the take, which are not all as quick: a quick measurement (a tenth
    // of a second on MakeHuman's body), and requests come first.
    const int frames = document_->frameCount();
    if (!solver_->hasProblem() || frames <= 0) return;
    std::vector<int> timed;
    for (int k = 0; k < kTimedFrames; ++k)
        timed.push_back(frames * (2 * k + 1) / (2 * kTimedFrames));
    solver_->timeFrames(timed);
}

void ExportDialog::showEvent(QShowEvent* event) {
    syncFromDocument();
    // Timed again at each showing: the machine may be busier, or quieter, than it was.
    solveMs_.clear();
    timeFrames();
    updateEstimate();
    QDialog::showEvent(event);
}

bool ExportDialog::event(QEvent* event) {
    const bool handled = QDialog::event(event);
    if (event->type() == QEvent::LayoutRequest) fitHeight();
    return handled;
}

void ExportDialog::resizeEvent(QResizeEvent* event) {
    QDialog::resizeEvent(event);
    fitHeight();
}

void ExportDialog::fitHeight() {
    // A top-level layout's minimum size leaves out height-for-width: a message wrapping onto more
    // lines took its height from the rows above it, squeezing the range's spin boxes to a line.
    QLayout* rows = layout();
    if (!rows || !rows->hasHeightForWidth()) return;
    const int needed = std::max(rows->totalMinimumSize().height(), heightForWidth(width()));
    if (minimumHeight() != needed) setMinimumHeight(needed);
    if (height() < needed) resize(width(), needed);
}

bool ExportDialog::startExport() {
    forgetLastRun();  // a refusal below is not said under the last run's full bar
    updateEstimate();
    if (folder().isEmpty()) {
        progressText_->setText(tr("Choose a folder to export into."));
        return false;
    }
    // An earlier export's files are the user's: replaced only when they say so, and then all of
    // them, so that the folder holds the one export its sidecar describes.
    ExportRequest r = request();
    // The calibrated rest the app fitted for these very inputs: fitting it again is most of the
    // export's preparation on a large mesh.
    if (r.options.calibrate == CalibrateMode::Shape)
        if (const auto rest = solver_->calibratedRestFor(*document_)) r.fittedRest = *rest;
    // Files of the outputs' names that no export wrote (the mesh's own walker.glb beside it, a map
    // saved as walker.json) are the user's: asked about as such, and never removed as an earlier
    // export's (Replace removed them once this export was written).
    const int frames = document_->frameCount();
    const std::vector<std::string> foreign =
        filesNoExportWrote(r, r.end < 0 ? frames : std::min(r.end, frames));
    const QString map = QFileInfo(document_->correspondencePath()).canonicalFilePath();
    for (const std::string& name : foreign)
        if (!map.isEmpty() &&
            QFileInfo(QDir(folder()).filePath(QString::fromStdString(name))).canonicalFilePath() ==
                map) {
            progressText_->setText(
                tr("Not exported: %1 is this document's correspondence file, which the export's "
                   "sidecar would replace. Choose another folder.")
                    .arg(QString::fromStdString(name)));
            return false;
        }
    if (!foreign.empty() && !askToReplaceOthersFiles(foreign)) {
        progressText_->setText(tr("Not exported: the folder keeps its files."));
        return false;
    }
    const std::vector<std::string> earlier = exportFilesWrittenIn(r.outDir, exportStem(r));
    // Another take's or actor's solve, found by the check `solve` refuses it with: said whose it
    // is, or Replace read as replacing an earlier export of this take (lost work).
    std::vector<std::string> subjects;
    try {
        subjects = document_->correspondence().subjects(document_->take());
    } catch (const std::exception&) {
        // A map the take does not resolve: the runner refuses it below, saying why.
    }
    const std::optional<OtherSolve> other = otherSolveIn(r, subjects);
    if ((other || !earlier.empty()) &&
        !askToReplace(earlier, other ? &*other : nullptr, subjects)) {
        const QString whose = !other ? QString()
                              : other->sameTake
                                  ? QString::fromStdString(subjectsText(other->subjects))
                                  : QFileInfo(QString::fromStdString(other->c3d)).fileName();
        progressText_->setText(
            other ? tr("Not exported: the folder keeps the solve of %1.").arg(whose)
                  : tr("Not exported: the folder keeps its earlier export."));
        return false;
    }
    QString error;
    if (!runner_->start(*document_, r, &error)) {
        progressText_->setText(error);
        return false;
    }
    replaced_ = earlier;
    running_ = r;
    QSettings().setValue("export/folder", folder());
    QSettings().setValue("export/calibratedRest", calibratedRest_->isChecked());
    forgetLastRun();
    progress_->setRange(0, std::max(1, frameCountToWrite()));
    progress_->setValue(0);
    // Until the first frame is written the bar says what the export is doing, which takes
    // seconds on a large mesh, rather than standing at "0 / 40 frames".
    const bool calibrating = r.options.calibrate == CalibrateMode::Shape && !r.fittedRest;
    progress_->setFormat(calibrating ? tr("preparing (calibrating, factorising)…")
                                     : tr("preparing (factorising)…"));
    const double preparingMs = solver_->preparationMs();
    progressText_->setText(
        preparingMs > 0
            ? tr("Preparing the solver (%1 when the app last did)…").arg(duration(preparingMs))
            : tr("Preparing the solver…"));
    startedMs_ = clock_();
    framesFromMs_ = -1;
    setRunning(true);
    emit runningChanged(true);
    return true;
}

void ExportDialog::cancelExport() {
    if (!runner_->isRunning()) return;
    runner_->cancel();
    progressText_->setText(tr("Stopping after the frames being solved…"));
}

void ExportDialog::reject() {
    // Close, Esc and the window's close button: a running export is the user's work, stopped
    // only when they say so. An export that ends while they are asked needs no answer.
    if (runner_->isRunning() && !askToStop() && runner_->isRunning()) return;
    cancelExport();
    QDialog::reject();
}

bool ExportDialog::mayCloseApp(QWidget* window) {
    // Stop Export, or an export that ended while asked: nothing of it is left to lose.
    return !runner_->isRunning() || askToStop(window) || !runner_->isRunning();
}

bool ExportDialog::askToStop(QWidget* closing) {
    // The bar says how far it got: "360 / 810 frames", or what it is preparing.
    QMessageBox box(QMessageBox::Question, closing ? tr("Close Boneless") : tr("Export"),
                    closing ? tr("An export is running (%1): closing stops it. Stop the export?")
                                  .arg(progress_->text())
                            : tr("Stop the export?"),
                    QMessageBox::NoButton, closing ? closing : this);
    box.setObjectName(closing ? "closeWhileExportingQuestion" : "stopExportQuestion");
    box.setInformativeText(tr("The frames written so far are kept in %1, and its sidecar records "
                              "the take as incomplete.")
                               .arg(QString::fromStdString(running_.outDir)));
    QPushButton* stop = box.addButton(closing ? tr("Stop Export and Close") : tr("Stop Export"),
                                      QMessageBox::DestructiveRole);
    QPushButton* keep = box.addButton(tr("Keep Exporting"), QMessageBox::RejectRole);
    stop->setObjectName("stopExportButton");
    keep->setObjectName("keepExportingButton");
    box.setDefaultButton(keep);
    box.setEscapeButton(keep);
    const QMetaObject::Connection ended =
        connect(runner_, &ExportRunner::finished, &box, [&box, keep] { keep->click(); });
    box.exec();
    disconnect(ended);
    return box.clickedButton() == stop;
}

void ExportDialog::onProgress(int done, int total) {
    progress_->setFormat(tr("%v / %m frames"));  // prepared: frames are being written
    progress_->setRange(0, total);
    progress_->setValue(done);
    // The time left from this run's own pace, writing included, timed from when its solver was
    // prepared: the preparation (16 s of the koala's) is not spent again for each frame left.
    // Frames solved at once on several workers count alike, so the pace is theirs together.
    const qint64 framesFrom = framesFromMs_ >= 0 ? framesFromMs_ : startedMs_;
    const double msPerFrame = (clock_() - framesFrom) / double(std::max(1, done));
    progressText_->setText(tr("%1 left").arg(duration(msPerFrame * (total - done))));
}

// "walker.json, walker_0001.obj, walker_0002.obj and 5 more files"
QString ExportDialog::listed(const std::vector<std::string>& names) const {
    QStringList first;
    for (std::size_t i = 0; i < names.size() && i < 3; ++i)
        first << QString::fromStdString(names[i]);
    const QString text = first.join(", ");
    if (names.size() <= 3) return text;
    return counted(int(names.size() - 3), tr("%1 and %n more file"), tr("%1 and %n more files"))
        .arg(text);
}

bool ExportDialog::askToReplaceOthersFiles(const std::vector<std::string>& names) {
    return askReplace(
        counted(int(names.size()), tr("%1 holds %2, which no Boneless export wrote. Replace it?"),
                tr("%1 holds %2, which no Boneless export wrote. Replace them?"))
            .arg(folder(), listed(names)),
        "replaceOthersFilesQuestion",
        tr("A file of the name an export writes, made by another program or by you: this export "
           "would write over it. Choose another folder to keep it."));
}

bool ExportDialog::askToReplace(const std::vector<std::string>& names, const OtherSolve* other,
                                const std::vector<std::string>& subjects) {
    const QString mine = other && other->sameTake ? QString::fromStdString(subjectsText(subjects))
                                                  : QFileInfo(document_->takePath()).fileName();
    return askReplace(
        other ? tr("%1 is the solve of %2. Replace it with the solve of %3?")
                    .arg(QString::fromStdString(other->sidecar),
                         QString::fromStdString(other->whose()), mine)
              : tr("%1 holds an earlier export (%2). Replace it?").arg(folder(), listed(names)),
        other ? "replaceOtherSolveQuestion" : "replaceExportQuestion",
        tr("Its files are removed once this export is written, or stopped part-way, so that "
           "the folder holds this export alone. Choose another folder to keep it."));
}

bool ExportDialog::askReplace(const QString& text, const char* name, const QString& informative) {
    QMessageBox box(QMessageBox::Question, tr("Export"), text, QMessageBox::Cancel, this);
    box.setObjectName(name);
    box.setInformativeText(informative);
    QPushButton* replace = box.addButton(tr("Replace"), QMessageBox::AcceptRole);
    replace->setObjectName("replaceButton");
    box.setDefaultButton(QMessageBox::Cancel);
    box.exec();
    return box.clickedButton() == replace;
}

QStringList ExportDialog::removeReplaced(const ExportRequest& r, const ExportResult& result) {
    const std::string stem = exportStem(r);
    std::set<std::string> written{stem + ".json"};
    if (r.format != ExportFormat::Obj) written.insert(stem + exportFormatInfo(r.format).extension);
    if (r.writeCalibratedRest) written.insert(stem + "_calibrated_rest.obj");
    if (r.format == ExportFormat::Obj)
        for (int f = result.first; f < result.first + result.framesWritten; ++f)
            written.insert(objFrameFile(stem, f));
    QStringList removed;
    for (const std::string& name : replaced_)
        if (!written.count(name) &&
            QFile::remove(
                QDir(QString::fromStdString(r.outDir)).filePath(QString::fromStdString(name))))
            removed << QString::fromStdString(name);
    replaced_.clear();
    return removed;
}

void ExportDialog::onFinished(bool ok, const QString& message) {
    setRunning(false);
    emit runningChanged(false);
    // Replace was said and the run wrote its sidecar, finished or cancelled: the earlier export's
    // files it did not write again go, or a cancelled run would leave them beside its own frames,
    // with the shared names (the sidecar, the calibrated rest) already this run's. A failed run
    // removes nothing more.
    const ExportResult& result = runner_->result();
    QString said = message;
    // Cancelled while the solver was prepared, the run wrote nothing: the earlier export stays.
    if (ok && !result.wroteNothing()) {
        const QStringList removed = removeReplaced(running_, result);
        if (result.cancelled && !removed.isEmpty()) {
            const int n = int(removed.size());
            QString names = QStringList(removed.mid(0, 3)).join(", ");
            if (n > 3) names = tr("%1 and %2 more").arg(names).arg(n - 3);
            said += " " + counted(n,
                                  tr("The earlier export's file it did not write again was "
                                     "removed (%1): the folder holds this export alone."),
                                  tr("The earlier export's %n files it did not write again were "
                                     "removed (%1): the folder holds this export alone."))
                              .arg(names);
        }
    }
    replaced_.clear();
    // The bar keeps how far the run got, the frames written, until the frames to write change or
    // another run starts: reset to 0 by the next solved frame, it read as nothing written.
    lastRunShown_ = true;
    if (ok) progress_->setValue(result.framesWritten);
    if (result.cancelled)
        progress_->setFormat(tr("%v / %m frames: cancelled"));
    else if (!ok)
        progress_->setFormat(tr("%v / %m frames: failed"));
    else
        progress_->setFormat(tr("%v / %m frames"));  // no longer preparing, whatever it wrote
    progressText_->setText(said);
    emit finished(ok, said);
}

void ExportDialog::forgetLastRun() {
    progressText_->clear();
    lastRunShown_ = false;
    progress_->setFormat(tr("%v / %m frames"));
}

void ExportDialog::setRunning(bool running) {
    start_->setEnabled(!running);
    cancel_->setEnabled(running);
    // The folder shown is the one being written into: Browse… cannot change it meanwhile.
    for (QWidget* w : std::initializer_list<QWidget*>{all_, inOut_, current_, in_, out_, format_,
                                                      folder_, browse_})
        w->setEnabled(!running);
    // Without calibration the rest is the input mesh: nothing to write.
    const bool calibrates = document_->settings().calibrate != CalibrateMode::None;
    calibratedRest_->setEnabled(!running && calibrates);
    calibratedRest_->setToolTip(calibrates ? tr("<stem>_calibrated_rest.obj: the input's vertices "
                                                "and faces, in the actor's proportions")
                                           : tr("Calibration is off: the rest is the input mesh"));
}

}  // namespace boneless::ui
