#include "boneless/Process.h"

#include <signal.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <string>

namespace boneless {

namespace {

// Process `pid`'s state letter and start time, from /proc/PID/stat; false where it cannot be read.
bool readStat(long pid, char& state, unsigned long long& startTime) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(in, line)) return false;
    // "PID (COMM) STATE PPID ...": COMM may hold spaces and parentheses, so the fields are counted
    // from its last ')'. STATE is the 3rd field, the 1st after it; starttime the 22nd, the 20th.
    const auto close = line.rfind(')');
    if (close == std::string::npos) return false;
    std::istringstream fields(line.substr(close + 1));
    if (!(fields >> state)) return false;
    std::string skipped;
    for (int i = 0; i < 18; ++i)
        if (!(fields >> skipped)) return false;
    return static_cast<bool>(fields >> startTime);
}

}  // namespace

bool processIsGone(long pid, unsigned long long startTime) {
    if (pid <= 0) return false;
    if (::kill(static_cast<pid_t>(pid), 0) != 0) return errno == ESRCH;
    char state = 0;
    unsigned long long started = 0;
    if (!readStat(pid, state, started)) return false;
    return state == 'Z' || state == 'X' || (startTime != 0 && started != startTime);
}

unsigned long long processStartTime(long pid) {
    char state = 0;
    unsigned long long started = 0;
    return pid > 0 && readStat(pid, state, started) ? started : 0;
}

}  // namespace boneless
