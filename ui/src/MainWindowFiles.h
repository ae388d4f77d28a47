#pragma once

// What MainWindowFiles.cpp and MainWindowRecovery.cpp share: a load's scope, and the names of the
// files the user gave, for messages.

#include <QFileInfo>
#include <QStringList>

#include "boneless/ui/MainWindow.h"
#include "boneless/ui/Project.h"

namespace boneless::ui {

// A load is no edit: while it runs (loading_), the title's mark is left alone, and the autosave it
// sets off (Document::changed) is dropped at its end, unless an edit was waiting already. Files
// opened after Discard at start were autosaved over the crash's work that the question had said
// would stay until the next change.
class MainWindow::Loading {
  public:
    explicit Loading(MainWindow* window)
        : window_(window), editWaiting_(window->loading_ > 0 || window->autosave_->isPending()) {
        ++window_->loading_;
    }
    ~Loading() {
        if (--window_->loading_ == 0 && !editWaiting_) window_->autosave_->discardPending();
    }
    Loading(const Loading&) = delete;
    Loading& operator=(const Loading&) = delete;

  private:
    MainWindow* window_;
    bool editWaiting_;  // or an outer load ends it
};

// "walk.boneless, take.c3d": what the user named, without the folders.
inline QString fileNames(const QStringList& paths) {
    QStringList names;
    for (const QString& path : paths) names << QFileInfo(path).fileName();
    return names.join(", ");
}

}  // namespace boneless::ui
