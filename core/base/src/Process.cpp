#include "boneless/Process.h"

#include <signal.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <string>

namespace boneless {

bool processIsGone(long pid) {
    return pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

unsigned long long processStartTime(long pid) {
    if (pid <= 0) return 0;
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(in, line)) return 0;
    // "PID (COMM) STATE PPID ...": COMM may hold spaces and parentheses, so the fields are counted
    // from its last ')'. starttime is the 22nd field, the 20th after it.
    const auto close = line.rfind(')');
    if (close == std::string::npos) return 0;
    std::istringstream fields(line.substr(close + 1));
    std::string skipped;
    for (int i = 0; i < 19; ++i)
        if (!(fields >> skipped)) return 0;
    unsigned long long start = 0;
    return fields >> start ? start : 0;
}

}  // namespace boneless
