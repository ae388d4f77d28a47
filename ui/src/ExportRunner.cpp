#include "boneless/ui/ExportRunner.h"

#include <QEventLoop>
#include <QFuture>
#include <QMetaObject>
#include <QPointer>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>

#include "Counted.h"
#include "boneless/ui/Document.h"

namespace boneless::ui {

struct ExportRunner::Job {
    std::atomic<bool> cancel{false};
    TriMesh mesh;
    C3dTake take;
    Correspondence map;
    ExportRequest request;
    ExportResult result;
    QString error;
    QFuture<void> future;
};

ExportRunner::ExportRunner(QObject* parent) : QObject(parent) {}

ExportRunner::~ExportRunner() {
    if (job_) {
        job_->cancel = true;
        // The job posts back to this object, so it must end before this object does.
        job_->future.waitForFinished();
    }
}

bool ExportRunner::start(const Document& document, const ExportRequest& request, QString* error) {
    QString why;
    if (running_)
        why = tr("An export is already running.");
    else if (!document.canSolve(&why))
        why = tr("Cannot export: %1").arg(why);
    if (!why.isEmpty()) {
        if (error) *error = why;
        return false;
    }
    auto job = std::make_shared<Job>();
    job->mesh = document.mesh();
    job->take = document.take();
    job->map = document.correspondence();
    job->request = request;
    job_ = job;
    running_ = true;
    error_.clear();
    result_ = ExportResult();

    QPointer<ExportRunner> self(this);
    job->future = QtConcurrent::run([job, self] {
        try {
            job->result = exportTake(
                job->mesh, job->take, job->map, job->request,
                [job, self](int done, int total, const FrameReport& last) {
                    const double residual = last.residualRmsMm;
                    if (done > 0)
                        QMetaObject::invokeMethod(self.data(), [self, done, total, residual] {
                            if (self) self->onProgress(done, total, residual);
                        });
                    return !job->cancel.load();
                },
                [self](const Calibration&) {
                    QMetaObject::invokeMethod(self.data(), [self] {
                        if (self) emit self->prepared();
                    });
                });
        } catch (const std::exception& e) {
            job->error = QString::fromStdString(e.what());
        }
        QMetaObject::invokeMethod(self.data(), [self] {
            if (self) self->onFinished();
        });
    });
    return true;
}

void ExportRunner::cancel() {
    if (job_) job_->cancel = true;
}

void ExportRunner::onProgress(int done, int total, double residualRmsMm) {
    emit progress(done, total, residualRmsMm);
}

void ExportRunner::onFinished() {
    const auto job = job_;
    job->future.waitForFinished();
    result_ = job->result;
    error_ = job->error;
    running_ = false;
    job_.reset();
    QString message;
    if (!error_.isEmpty())
        message = error_;
    else if (result_.wroteNothing())
        message = tr("Export cancelled before any frame was written: the folder is as it was.");
    else if (result_.cancelled)
        message = counted(result_.framesWritten,
                          tr("Export stopped after %n frame: it is valid, and %1 records "
                             "the take as incomplete."),
                          tr("Export stopped after %n frames: they are valid, and %1 records "
                             "the take as incomplete."))
                      .arg(QString::fromStdString(result_.sidecarPath));
    else
        message = counted(result_.framesWritten, tr("Exported %n frame to %1."),
                          tr("Exported %n frames to %1."))
                      .arg(QString::fromStdString(job->request.outDir));
    emit finished(error_.isEmpty(), message);
}

bool ExportRunner::wait(int timeoutMs) {
    if (!running_) return true;
    QEventLoop loop;
    connect(this, &ExportRunner::finished, &loop, &QEventLoop::quit);
    if (timeoutMs >= 0) QTimer::singleShot(timeoutMs, &loop, &QEventLoop::quit);
    loop.exec();
    return !running_;
}

}  // namespace boneless::ui
