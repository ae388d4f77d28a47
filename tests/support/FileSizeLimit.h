#pragma once

#include <sys/resource.h>

#include <csignal>

namespace boneless::test {

// Lets this process grow no file past `bytes` (RLIMIT_FSIZE, as a quota or a full disk does): a
// write past it then fails with EFBIG instead of killing the process. `normal` receives the limit
// to give back with restoreFileSize. False when either call is refused.
inline bool limitFileSize(rlimit& normal, rlim_t bytes) {
    std::signal(SIGXFSZ, SIG_IGN);
    if (getrlimit(RLIMIT_FSIZE, &normal) != 0) return false;
    rlimit small = normal;
    small.rlim_cur = bytes;
    return setrlimit(RLIMIT_FSIZE, &small) == 0;
}

inline bool restoreFileSize(const rlimit& normal) {
    return setrlimit(RLIMIT_FSIZE, &normal) == 0;
}

}  // namespace boneless::test
