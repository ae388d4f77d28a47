#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace boneless {

// Every failure the core reports to a user is one of these: the message is complete on its own
// (file, what, where), so a CLI prints it as one line and a window shows it as is.
class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// A mesh file that cannot be used: unreadable, empty, non-manifold, NaN coordinates, ...
class MeshError : public Error {
  public:
    MeshError(std::string file, std::string what, std::string where = {});
    const std::string& file() const { return file_; }
    const std::string& cause() const { return cause_; }
    const std::string& where() const { return where_; }

  private:
    std::string file_, cause_, where_;
};

// A solver input that cannot be solved: bad marker ids, wrong target count, ...
class SolverError : public Error {
  public:
    using Error::Error;
};

// Why the write just made failed, as the system words it ("No space left on device", "File too
// large", "Input/output error"); a guess only when the C library failed without saying.
std::string writeFailure();

}  // namespace boneless
