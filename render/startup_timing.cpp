// The process clock origin and the process's age at that origin (startup_timing.h).
#include "render/startup_timing.h"

#include <time.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace pm {

namespace {

// Seconds since boot on the clock /proc/self/stat's start time counts on.
double boot_seconds_now() {
  timespec t{};
  if (clock_gettime(CLOCK_BOOTTIME, &t) != 0) return -1;
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// The process's start time in seconds since boot (field 22 of /proc/self/stat), or -1.
double process_start_boot_seconds() {
  std::ifstream in("/proc/self/stat");
  const std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The command name (field 2) is in parentheses and may hold spaces: count fields after its ')'.
  const size_t close = stat.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream fields(stat.substr(close + 1));
  std::string field;
  for (int i = 3; i <= 22 && (fields >> field); ++i)
    if (i == 22) {
      const long ticks_per_second = sysconf(_SC_CLK_TCK);
      return ticks_per_second > 0 ? std::stod(field) / double(ticks_per_second) : -1;
    }
  return -1;
}

struct Origin {
  StartupClock::time_point time = StartupClock::now();
  double boot_seconds = boot_seconds_now();
};

// Constructed with the program's static objects, before main runs.
const Origin origin;

}  // namespace

StartupClock::time_point process_clock_origin() { return origin.time; }

double process_start_to_origin_ms() {
  const double started = process_start_boot_seconds();
  if (started < 0 || origin.boot_seconds < 0) return -1;
  const double ms = 1000.0 * (origin.boot_seconds - started);
  return ms >= 0 ? ms : -1;
}

double ms_since_origin(StartupClock::time_point t) { return ms_between(origin.time, t); }

const char* program_cache_use_name(ProgramCacheUse use) {
  switch (use) {
    case ProgramCacheUse::none: return "none";
    case ProgramCacheUse::off: return "off";
    case ProgramCacheUse::loaded: return "loaded";
    case ProgramCacheUse::stored: return "stored";
    case ProgramCacheUse::not_stored: return "not stored";
  }
  return "?";
}

double DeviceStartup::total_ms() const {
  double sum = 0;
  for (const StartupStep& s : steps) sum += s.ms;
  return sum;
}

}  // namespace pm
