// Start-up timing: the process's clock origin (taken while the program's static objects are
// constructed, before main), what opening a device took step by step and what the program cache
// did then. Devices fill a DeviceStartup as they open; `pmrender bench` and `render -v` print it
// beside the frame (cli/startup_report.h). Nothing here waits for a device or adds work.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace pm {

using StartupClock = std::chrono::steady_clock;

// When this process's static initialisation reached pmrender's library: the earliest point the
// program itself can see (the dynamic loader ran before it).
StartupClock::time_point process_clock_origin();
// Milliseconds from the process's creation (the kernel's start time of the process, in clock
// ticks of usually 10 ms) to process_clock_origin(); negative where the system does not say.
double process_start_to_origin_ms();
// Milliseconds from process_clock_origin() to t.
double ms_since_origin(StartupClock::time_point t);

// Milliseconds between two time points.
inline double ms_between(StartupClock::time_point a, StartupClock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// One timed step of start-up.
struct StartupStep {
  std::string name;    // "device open", "program", "scene load", ...
  double ms = 0;
  std::string detail;  // what the step did, e.g. "loaded from the program cache"
};

// What the program cache did when the device opened.
enum class ProgramCacheUse {
  none,        // the backend keeps no program cache (CUDA: its kernels are in the binary)
  off,         // switched off (PMRENDER_PROGRAM_CACHE=off, or no folder to keep it in)
  loaded,      // the program came from the cache
  stored,      // compiled from source, and its binary written to the cache
  not_stored,  // compiled from source; writing the entry failed
};
const char* program_cache_use_name(ProgramCacheUse use);

struct DeviceStartup {
  std::vector<StartupStep> steps;  // in the order they ran
  ProgramCacheUse program_cache = ProgramCacheUse::none;
  bool cache_entry_rejected = false;  // an entry was there but unusable (notes say why); compiled instead
  std::string cache_path;             // the entry's file, when the cache is on
  std::vector<std::string> notes;     // one-line remarks for verbose output
  std::string warning;                // one line worth telling without -v; set on one device per process at most

  double total_ms() const;
};

// Times consecutive steps: each lap() is the time since the previous one (or since construction).
class StepClock {
 public:
  StepClock() : last_(StartupClock::now()) {}
  double lap_ms() {
    const StartupClock::time_point now = StartupClock::now();
    const double ms = ms_between(last_, now);
    last_ = now;
    return ms;
  }

 private:
  StartupClock::time_point last_;
};

}  // namespace pm
