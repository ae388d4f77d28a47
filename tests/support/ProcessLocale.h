#pragma once

// The process's C locale set as the application's QApplication sets it (setlocale(LC_ALL, "")),
// for a test's span, and restored after.

#include <gtest/gtest.h>

#include <clocale>
#include <string>

namespace testlocale {

class ProcessLocale {
  public:
    explicit ProcessLocale(const char* name) : saved_(std::setlocale(LC_ALL, nullptr)) {
        set_ = std::setlocale(LC_ALL, name) != nullptr;
    }
    ~ProcessLocale() { std::setlocale(LC_ALL, saved_.c_str()); }
    ProcessLocale(const ProcessLocale&) = delete;
    ProcessLocale& operator=(const ProcessLocale&) = delete;
    bool isSet() const { return set_; }

  private:
    std::string saved_;
    bool set_ = false;
};

}  // namespace testlocale

// Sets the locale `name` till the end of the calling test, or skips the test on a machine that
// has not generated it (CI generates de_DE.UTF-8 and tr_TR.UTF-8: .ci/run).
#define PROCESS_LOCALE_OR_SKIP(var, name)      \
    const testlocale::ProcessLocale var(name); \
    if (!var.isSet()) GTEST_SKIP() << "the locale " << (name) << " is not generated here"
