#pragma once

#include <QObject>
#include <QPointer>
#include <QProgressDialog>
#include <QString>
#include <atomic>
#include <memory>

#include "boneless/TakeExport.h"

class QWidget;

namespace boneless::ui {

class Document;

// Runs boneless::exportTake (the very function `boneless-cli solve` uses, so the files are the
// same byte for byte) on a worker thread, with a progress dialog whose Cancel stops after the
// current frame. The inputs are copied at start, so the document may change meanwhile.
class ExportRunner : public QObject {
    Q_OBJECT
  public:
    // dialogParent: where the modal progress dialog appears; nullptr = no dialog.
    explicit ExportRunner(QWidget* dialogParent = nullptr, QObject* parent = nullptr);
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
    QProgressDialog* dialog() const { return dialog_; }

  signals:
    void progress(int done, int total, double residualRmsMm);
    // ok: every requested frame written, or cancelled cleanly (see result().cancelled).
    void finished(bool ok, const QString& message);

  private:
    struct Job;
    void onProgress(int done, int total, double residualRmsMm);
    void onFinished();

    QPointer<QWidget> dialogParent_;
    QPointer<QProgressDialog> dialog_;
    std::shared_ptr<Job> job_;
    bool running_ = false;
    ExportResult result_;
    QString error_;
};

}  // namespace boneless::ui
