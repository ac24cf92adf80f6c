// Progress line and duration formatting.
#include "cli/progress_line.h"

#include <unistd.h>

#include <cstdio>

namespace pm::cli {

std::string seconds_text(double s) {
  char text[32];
  if (s < 1) {
    std::snprintf(text, sizeof(text), "%.0f ms", s * 1000);
  } else if (s < 60) {
    std::snprintf(text, sizeof(text), "%.1f s", s);
  } else {
    const long total = long(s + 0.5);
    if (total >= 3600)
      std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", total / 3600, (total / 60) % 60, total % 60);
    else
      std::snprintf(text, sizeof(text), "%ld:%02ld", total / 60, total % 60);
  }
  return text;
}

ProgressLine::ProgressLine(bool enabled) : enabled_(enabled && ::isatty(STDERR_FILENO)) {}

void ProgressLine::show(const std::string& text) {
  if (!enabled_) return;
  std::fprintf(stderr, "\r\033[K%s", text.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressLine::show_count(const std::string& what, size_t done, size_t total, double seconds_so_far,
                              const char* unit) {
  if (!enabled_) return;
  const double percent = total ? 100.0 * double(done) / double(total) : 100.0;
  const double mean = done ? seconds_so_far / double(done) : 0.0;
  char text[256];
  std::snprintf(text, sizeof(text), "%s  %zu/%zu (%.0f%%)  %s/%s  ETA %s", what.c_str(), done, total, percent,
                seconds_text(mean).c_str(), unit, seconds_text(mean * double(total - done)).c_str());
  show(text);
}

void ProgressLine::clear() {
  if (enabled_ && drawn_) std::fprintf(stderr, "\r\033[K");
  drawn_ = false;
}

}  // namespace pm::cli
