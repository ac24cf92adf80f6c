// Contiguous runs of frames with work stealing (see frame_runs.h).
#include "render/frame_runs.h"

#include <algorithm>
#include <stdexcept>

namespace pm {

FrameRuns::FrameRuns(size_t count, size_t workers) {
  if (workers == 0) throw std::invalid_argument("FrameRuns: no worker");
  runs_.resize(workers);
  // The first count % workers runs get one item more.
  size_t begin = 0;
  for (size_t w = 0; w < workers; ++w) {
    const size_t length = count / workers + (w < count % workers ? 1 : 0);
    runs_[w].begin = begin;
    runs_[w].end = begin + length;
    begin += length;
  }
}

std::optional<size_t> FrameRuns::next(size_t worker) {
  std::lock_guard<std::mutex> lock(mutex_);
  Run& own = runs_.at(worker);
  if (own.begin == own.end) {
    // Steal: the longest run left loses its back half (the larger half when odd, so that a run of
    // one is taken whole: its owner is busy with the item before it, the thief is idle).
    auto longest = std::max_element(runs_.begin(), runs_.end(), [](const Run& a, const Run& b) {
      return a.end - a.begin < b.end - b.begin;
    });
    const size_t left = longest->end - longest->begin;
    if (left == 0) return std::nullopt;
    const size_t middle = longest->begin + left / 2;
    own.begin = middle;
    own.end = longest->end;
    own.stolen += own.end - own.begin;
    longest->end = middle;
  }
  return own.begin++;
}

size_t FrameRuns::stolen(size_t worker) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return runs_.at(worker).stolen;
}

}  // namespace pm
