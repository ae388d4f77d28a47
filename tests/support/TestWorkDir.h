#pragma once

// Every test gets a scratch folder of its own (<build>/test-work/<Suite>.<Test>): ctest runs the
// tests as parallel processes, and a folder shared between them would let one test read a file
// another is still writing. Included into every test file by the build (-include).
#include <string>

std::string bonelessTestWorkDir();
#define BONELESS_TEST_WORK_DIR bonelessTestWorkDir()

// An empty folder `name` inside the test's scratch folder (emptied if an earlier run left it).
std::string freshTestDir(const std::string& name);
