// Process identities (process_identity.h): host name, boot id and start time read from /proc.
#include "render/process_identity.h"

#include <limits.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>

namespace pm {

namespace {

std::string host_name() {
  char name[HOST_NAME_MAX + 1] = {};
  if (::gethostname(name, sizeof(name) - 1) != 0) return "unknown-host";
  return name;
}

std::string boot_id() {
  std::ifstream in("/proc/sys/kernel/random/boot_id");
  std::string id;
  std::getline(in, id);
  return id;
}

// Fields 3 (state) and 22 (start time) of /proc/<pid>/stat, or false when it cannot be read.
bool read_process_stat(long pid, char* state, unsigned long long* start_ticks) {
  if (pid <= 0) return false;
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(in, line)) return false;
  // "pid (comm) state ppid ...": comm may hold blanks and parentheses, so fields are counted
  // from the last ')'. The first field after it is field 3 (state); the start time is field 22.
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return false;
  std::istringstream fields(line.substr(close + 1));
  std::string field, state_field;
  for (int number = 3; number <= 22; ++number) {
    if (!(fields >> field)) return false;
    if (number == 3) state_field = field;
  }
  try {
    size_t used = 0;
    *start_ticks = std::stoull(field, &used);
    if (used != field.size() || state_field.size() != 1) return false;
  } catch (const std::exception&) {
    return false;
  }
  *state = state_field[0];
  return true;
}

}  // namespace

std::optional<unsigned long long> process_start_ticks(long pid) {
  char state = 0;
  unsigned long long ticks = 0;
  if (!read_process_stat(pid, &state, &ticks)) return std::nullopt;
  return ticks;
}

ProcessIdentity this_process_identity() {
  ProcessIdentity self;
  self.host = host_name();
  self.boot_id = boot_id();
  self.pid = long(::getpid());
  self.start_ticks = process_start_ticks(self.pid).value_or(0);
  return self;
}

ProcessState local_process_state(const ProcessIdentity& identity) {
  if (identity.pid <= 0) return ProcessState::gone;
  // EPERM: the pid exists but belongs to another user; it may still be the same process.
  if (::kill(pid_t(identity.pid), 0) != 0 && errno == ESRCH) return ProcessState::gone;
  char state = 0;
  unsigned long long ticks = 0;
  if (!read_process_stat(identity.pid, &state, &ticks)) return ProcessState::running;
  // A killed process its parent has not yet reaped (a zombie) does no more work.
  if (state == 'Z' || state == 'X') return ProcessState::gone;
  if (identity.start_ticks != 0 && ticks != identity.start_ticks) return ProcessState::replaced;
  return ProcessState::running;
}

}  // namespace pm
