// processIsGone decides whose autosave and temporaries are left behind (ProjectAutosave,
// SpoolFile): these pin down that a process killed a moment ago, still a zombie, counts as gone,
// and that a process id given to another process since does not keep the first one alive.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include "boneless/Process.h"

using namespace boneless;

namespace {

// The state letter of process `pid` (/proc/PID/stat), or 0.
char stateOf(long pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(in, line) || line.rfind(')') == std::string::npos) return 0;
    return line[line.rfind(')') + 2];
}

}  // namespace

TEST(ProcessTest, aRunningProcessIsNotGone) {
    EXPECT_FALSE(processIsGone(::getpid()));
    EXPECT_FALSE(processIsGone(::getpid(), processStartTime(::getpid())));
    EXPECT_NE(processStartTime(::getpid()), 0u);
}

TEST(ProcessTest, aProcessThatEndedAndWasNotReapedYetIsGone) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) ::_exit(0);
    // Not waited for: a zombie, as a Boneless is for a moment after kill -9.
    for (int i = 0; i < 200 && stateOf(child) != 'Z'; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    ASSERT_EQ(stateOf(child), 'Z');
    EXPECT_TRUE(processIsGone(child));
    EXPECT_TRUE(processIsGone(child, processStartTime(child)));
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(processIsGone(child));
}

TEST(ProcessTest, aProcessIdGivenToAProcessThatStartedAtAnotherTimeIsGone) {
    const unsigned long long started = processStartTime(::getpid());
    ASSERT_NE(started, 0u);
    EXPECT_TRUE(processIsGone(::getpid(), started + 1));
}
