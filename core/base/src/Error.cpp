#include "boneless/Error.h"

#include <cerrno>
#include <cstring>

namespace boneless {

namespace {
std::string composeMeshMessage(const std::string& file, const std::string& what,
                               const std::string& where) {
    std::string msg = file + ": " + what;
    if (!where.empty()) msg += " (" + where + ")";
    return msg;
}
}  // namespace

MeshError::MeshError(std::string file, std::string what, std::string where)
    : Error(composeMeshMessage(file, what, where)),
      file_(std::move(file)),
      cause_(std::move(what)),
      where_(std::move(where)) {}

std::string writeFailure() {
    return errno ? std::strerror(errno) : "disk full?";
}

}  // namespace boneless
