#include "boneless/Process.h"

#include <signal.h>

#include <cerrno>

namespace boneless {

bool processIsGone(long pid) {
    return pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

}  // namespace boneless
