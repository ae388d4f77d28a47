#pragma once

// Small files the tests write for the readers under test, and the messages those readers give.
#include <functional>
#include <string>

namespace boneless::testing {

// Writes `text` to `name` in a folder of its own inside the test's scratch folder; returns the
// file's path.
std::string writeTestFile(const std::string& name, const std::string& text);

// The message of the boneless::Error that f throws; empty when it throws none.
std::string errorOf(const std::function<void()>& f);

}  // namespace boneless::testing
