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

inline CliResult runCli(const std::string& arguments) {
    return runShell(std::string(BONELESS_CLI) + " " + arguments + " 2>&1");
}

}  // namespace boneless::testing
