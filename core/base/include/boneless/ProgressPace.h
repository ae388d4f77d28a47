#pragma once

#include <algorithm>

namespace boneless {

// When a progress line is due in a log (not a terminal, where a bar redraws in place at each
// step): once a tenth more of the work is done or `seconds` have passed since the last line,
// whichever comes first, and at the last step. Tenths alone left a long take's log silent for
// a minute.
class ProgressPace {
  public:
    explicit ProgressPace(int total, double seconds = 10) : total_(total), seconds_(seconds) {}

    // `done` steps of the total after `elapsedSeconds`: whether to print a line now.
    bool due(int done, double elapsedSeconds) {
        const bool now = done >= total_ || done - lastDone_ >= std::max(1, total_ / 10) ||
                         elapsedSeconds - lastSeconds_ >= seconds_;
        if (now) {
            lastDone_ = done;
            lastSeconds_ = elapsedSeconds;
        }
        return now;
    }

  private:
    int total_;
    double seconds_;
    int lastDone_ = 0;
    double lastSeconds_ = 0;
};

}  // namespace boneless
