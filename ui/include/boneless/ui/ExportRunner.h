#pragma once

#include <QObject>
#include <QString>
#include <atomic>
#include <memory>

#include "boneless/TakeExport.h"

namespace boneless::ui {

class Document;

// Runs boneless::exportTake (the very function `boneless-cli solve` uses, so the files are the
// same byte for byte) on a worker thread; cancel() stops after the frames being solved. The
// inputs are copied at start, so the document may change meanwhile. ExportDialog shows it.
class ExportRunner : public QObject {
    Q_OBJECT
  public:
    explicit ExportRunner(QObject* parent = nullptr);
    ~ExportRunner() override;  // cancels and waits

    // Starts exporting; false with *error when the document cannot be solved or an export is
    // already running. The request usually comes from Document::exportRequest().
    bool start(const Document& document, const ExportRequest& request, QString* error = nullptr);
    bool isRunning() const { return running_; }
    void cancel();
    // Blocks until the running export ends (for tests and shutdown); true when it had ended.
    bool wait(int timeoutMs = -1);

    const ExportResult& result() const { return result_; }
    QString errorMessage() const { return error_; }

  signals:
    // The solver is prepared (calibrated, factorised) and the first frame is being solved.
    void prepared();
    void progress(int done, int total, double residualRmsMm);
    // ok: every requested frame written, or cancelled cleanly (see result().cancelled).
    void finished(bool ok, const QString& message);

  private:
    struct Job;
    void onProgress(int done, int total, double residualRmsMm);
    void onFinished();

    std::shared_ptr<Job> job_;
    bool running_ = false;
    ExportResult result_;
    QString error_;
};

}  // namespace boneless::ui
