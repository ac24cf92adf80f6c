// A request to stop early (SIGINT, SIGTERM), set from a signal handler and polled by host work
// that can stop cleanly between steps: the command line's frame loop, and AtomicFile between
// writes (so that no partial file is left behind). Also the table of temporary files in flight,
// which a handler that must end the process at once removes first.
#pragma once

#include <stdexcept>
#include <string>

namespace pm {

// Records that the process was asked to stop by signal_number. Async-signal-safe.
void request_interruption(int signal_number);

// The signal that asked to stop, or 0 when none did.
int interruption_signal();

// Thrown by work that stopped because of a request (see throw_if_interrupted).
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted") {}
};

// Throws Interrupted when a stop was requested.
void throw_if_interrupted();

// Files that must not outlive the process: output temporaries and frame claims (frame_claim.h).
// register_temporary returns a slot (or -1 when all slots are taken, which only means the file is
// not removed on a hard exit).
int register_temporary(const std::string& path);
void unregister_temporary(int slot);

// Unlinks every registered temporary. Async-signal-safe: for a handler about to _exit().
void remove_registered_temporaries();

}  // namespace pm
