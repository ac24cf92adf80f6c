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

// A setting outside its range, from the library's validation of its settings structs. The
// message starts with the setting's name ("smoothing: must be positive, got -1"), which the
// command line spells as its option (--smoothing); the library itself names no option.
class SettingError : public InputError {
 public:
  SettingError(const std::string& setting, const std::string& problem)
      : InputError(setting + ": " + problem), setting_(setting) {}
  const std::string& setting() const { return setting_; }

 private:
  std::string setting_;
};

// A device call failed. The message names the failing call and where it was made.
class DeviceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace pm
