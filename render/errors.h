// The two kinds of failure the command line turns into exit codes: InputError (bad usage or bad
// input: exit 2, nothing written) and DeviceError (a CUDA/OpenCL/render failure: exit 1).
#pragma once

#include <stdexcept>
#include <string>

namespace pm {

// Bad scene file, mesh, option or frame spec. The message names the file and the field or line.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A device call failed. The message names the failing call and where it was made.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pm
