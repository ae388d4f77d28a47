#include "TestWorkDir.h"

#include <gtest/gtest.h>

#include <filesystem>

std::string bonelessTestWorkDir() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string name =
        test ? std::string(test->test_suite_name()) + "." + test->name() : std::string("global");
    const auto dir = std::filesystem::path(BONELESS_TEST_WORK_BASE) / name;
    std::filesystem::create_directories(dir);
    return dir.string();
}

std::string freshTestDir(const std::string& name) {
    const auto dir = std::filesystem::path(bonelessTestWorkDir()) / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}
