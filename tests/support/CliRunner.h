#pragma once

// Runs boneless-cli as a user would and captures what it prints.
#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <string>

namespace boneless::testing {

struct CliResult {
    int exitCode = -1;
    std::string out;  // stdout and stderr together
};

// Runs a shell command line, capturing stdout and stderr together.
inline CliResult runShell(const std::string& command) {
    CliResult result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer;
    size_t got;
    while ((got = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
        result.out.append(buffer.data(), got);
    const int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

// Runs boneless-cli `arguments` in the background, and once `path` exists (10 s at most) the shell
// line `then` ("kill -INT $pid": a user's Ctrl-C at that point); its exit status is the CLI's.
inline CliResult runCliAndWhenExists(const std::string& arguments, const std::string& path,
                                     const std::string& then) {
    return runShell(std::string(BONELESS_CLI) + " " + arguments +
                    " 2>&1 & pid=$!; for i in $(seq 1000); do [ -e '" + path +
                    "' ] && break; sleep 0.01; done; " + then + "; wait $pid");
}

inline CliResult runCli(const std::string& arguments) {
    return runShell(std::string(BONELESS_CLI) + " " + arguments + " 2>&1");
}

}  // namespace boneless::testing
