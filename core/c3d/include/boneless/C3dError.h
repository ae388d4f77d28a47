#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "boneless/Error.h"

namespace boneless {

// A C3D file that cannot be read. The message is one complete line: "FILE: CAUSE (at byte N)",
// so the CLI prints it as is and the GUI can show it without reformatting.
class C3dError : public Error {
  public:
    static constexpr std::uint64_t kNoOffset = std::numeric_limits<std::uint64_t>::max();

    C3dError(std::string file, std::uint64_t offset, std::string cause);

    const std::string& file() const { return file_; }
    // Byte offset in the file where the problem was found, or kNoOffset (e.g. cannot open).
    std::uint64_t offset() const { return offset_; }
    const std::string& cause() const { return cause_; }

  private:
    std::string file_;
    std::uint64_t offset_;
    std::string cause_;
};

}  // namespace boneless
