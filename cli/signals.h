// SIGINT and SIGTERM during `render`: the first asks the frame loop to stop (render/interruption.h:
// the frame in progress is abandoned, a file being written is removed, finished frames stay);
// a second one ends the process at once, removing the temporary being written first.
#pragma once

#include <cstddef>

namespace pm::cli {

// Installs the handlers for SIGINT and SIGTERM.
void install_interrupt_handlers();

// Prints "pmrender: interrupted after N of M frames" and returns the exit code for the signal
// that stopped the run: 130 for SIGINT, 143 for SIGTERM (128 + the signal number, as shells do).
int report_interruption(size_t frames_done, size_t frames_total);

}  // namespace pm::cli
