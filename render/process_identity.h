// Who a process is, written so that another process can tell later whether it still runs: the
// host name, the boot id, the pid and the pid's start time since boot. The start time is what
// tells a process from a later one that got the same pid; the boot id tells one running kernel
// from another (a restart, or another machine of the same name). Linux only (/proc).
#pragma once

#include <optional>
#include <string>

namespace pm {

struct ProcessIdentity {
  std::string host;                  // gethostname()
  std::string boot_id;               // /proc/sys/kernel/random/boot_id; empty where unreadable
  long pid = 0;
  unsigned long long start_ticks = 0;  // /proc/<pid>/stat field 22: clock ticks after boot
};

// This process.
ProcessIdentity this_process_identity();

// The start time of pid in clock ticks after boot, or nothing when no such process exists or
// /proc does not show it (hidepid, or /proc not mounted).
std::optional<unsigned long long> process_start_ticks(long pid);

enum class ProcessState {
  running,   // the process of that identity still runs (or this machine cannot tell otherwise)
  gone,      // no process has that pid any more
  replaced,  // the pid belongs to a later process (another start time)
};

// Whether the process of identity, which must be of this host and this boot, still runs.
// Conservative: when the pid exists but /proc cannot say when it started, it counts as running.
ProcessState local_process_state(const ProcessIdentity& identity);

}  // namespace pm
