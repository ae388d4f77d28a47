#include "boneless/C3dError.h"

namespace boneless {

namespace {
std::string composeC3dMessage(const std::string& file, std::uint64_t offset,
                              const std::string& cause) {
    std::string msg = file + ": " + cause;
    if (offset != C3dError::kNoOffset) msg += " (at byte " + std::to_string(offset) + ")";
    return msg;
}
}  // namespace

C3dError::C3dError(std::string file, std::uint64_t offset, std::string cause)
    : Error(composeC3dMessage(file, offset, cause)),
      file_(std::move(file)),
      offset_(offset),
      cause_(std::move(cause)) {}

}  // namespace boneless
