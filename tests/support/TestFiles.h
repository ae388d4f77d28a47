#pragma once

// Small files the tests write for the readers under test, and the messages those readers give.
#include <functional>
#include <string>

namespace boneless::testing {

// Writes `text` to `name` in a folder of its own inside the test's scratch folder; returns the
// file's path.
std::string writeTestFile(const std::string& name, const std::string& text);

// A real 2×2 RGB PNG (red, green / blue, white): a texture any image reader decodes.
std::string twoByTwoPng();

// Rewrites a triangle-only OBJ as an artist's file: a texture coordinate per corner, every face
// under material `material` of library `library` (named relative to the OBJ).
void addTextureCoordinatesAndMaterial(const std::string& objPath, const std::string& library,
                                      const std::string& material);

// The message of the boneless::Error that f throws; empty when it throws none.
std::string errorOf(const std::function<void()>& f);

}  // namespace boneless::testing
