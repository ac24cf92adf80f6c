// The one progress line of the program: a single self-overwriting line on stderr when it is a
// terminal ("frame 12  5/24 (21%)  48 ms/frame  ETA 0:01"), nothing otherwise. Cleared before
// any other output so it never interleaves with messages.
#pragma once

#include <string>

namespace pm::cli {

// "850 ms", "12.3 s", "4:05", "1:02:03".
std::string seconds_text(double seconds);

class ProgressLine {
 public:
  // enabled: draw at all (the caller's --quiet); drawing also needs stderr to be a terminal.
  explicit ProgressLine(bool enabled);
  ~ProgressLine() { clear(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // Replaces the line with text.
  void show(const std::string& text);
  // "<what>  done/total (p%)  <per item>/<unit>  ETA <remaining>", from the mean time per item.
  void show_count(const std::string& what, size_t done, size_t total, double seconds_so_far, const char* unit);
  // Erases the line (before other output).
  void clear();

 private:
  bool enabled_;
  bool drawn_ = false;
};

}  // namespace pm::cli
