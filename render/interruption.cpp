// The stop request flag and the table of temporary files in flight (interruption.h). Both are
// touched from signal handlers, so they are lock-free atomics and fixed-size character arrays.
#include "render/interruption.h"

#include <limits.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>

namespace pm {

namespace {

volatile std::sig_atomic_t g_signal = 0;

// Each slot: the path, then `used` set (release) once the path is complete.
constexpr int kSlots = 32;  // per device thread: a frame claim, an output temporary, a checkpoint
struct TemporarySlot {
  std::atomic<bool> used{false};
  std::atomic<bool> claimed{false};
  char path[PATH_MAX];
};
TemporarySlot g_temporaries[kSlots];

static_assert(std::atomic<bool>::is_always_lock_free, "signal handlers need lock-free atomics");

}  // namespace

void request_interruption(int signal_number) { g_signal = signal_number; }

int interruption_signal() { return g_signal; }

void throw_if_interrupted() {
  if (g_signal != 0) throw Interrupted();
}

int register_temporary(const std::string& path) {
  if (path.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (!g_temporaries[i].claimed.compare_exchange_strong(expected, true)) continue;
    std::memcpy(g_temporaries[i].path, path.c_str(), path.size() + 1);
    g_temporaries[i].used.store(true, std::memory_order_release);
    return i;
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot < 0 || slot >= kSlots) return;
  g_temporaries[slot].used.store(false, std::memory_order_release);
  g_temporaries[slot].claimed.store(false, std::memory_order_release);
}

void remove_registered_temporaries() {
  for (TemporarySlot& slot : g_temporaries)
    if (slot.used.load(std::memory_order_acquire)) ::unlink(slot.path);
}

}  // namespace pm
