// Signal handlers for `render` (signals.h). The handler only records the request; the frame loop
// and the file writer poll it. Everything the handler calls is async-signal-safe.
#include "cli/signals.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>

#include "render/interruption.h"

namespace pm::cli {

namespace {

void on_stop_signal(int signal_number) {
  if (interruption_signal() == 0) {
    request_interruption(signal_number);
    return;
  }
  // Asked twice: stop now, but leave no partial file.
  remove_registered_temporaries();
  static const char message[] = "pmrender: interrupted again, stopping at once\n";
  ssize_t ignored = ::write(STDERR_FILENO, message, sizeof(message) - 1);
  (void)ignored;
  ::_exit(128 + signal_number);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // blocking calls elsewhere (driver threads, file I/O) carry on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int report_interruption(size_t frames_done, size_t frames_total) {
  std::fflush(stdout);
  std::fprintf(stderr, "pmrender: interrupted after %zu of %zu frames\n", frames_done, frames_total);
  return 128 + interruption_signal();
}

}  // namespace pm::cli
