// Host work on threads of its own: one thread per device (opening them, uploading a scene,
// beginning a frame; a device's calls stay on one thread at a time and the devices do not wait
// for each other), and loops of independent iterations spread over the CPU's cores in contiguous
// chunks (the radiosity mesh's elements and texture tints on the first frame).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace pm {

// work(0) .. work(count - 1), each on a thread of its own (work(0) on the calling thread). Once
// all have finished, the failure of the lowest index, if any, is rethrown.
void for_each_device(size_t count, const std::function<void(size_t)>& work);

// [begin, end) of one chunk of a loop.
struct IndexRange {
  size_t begin = 0, end = 0;
};

// Threads a loop may use: every hardware thread (0, the default) or at most `threads`.
void set_host_thread_limit(unsigned threads);
unsigned host_thread_count();

// [0, count) cut into contiguous chunks of at least min_chunk iterations, at most one per host
// thread (host_thread_count), in order. A loop whose chunks write their own results, joined in
// chunk order, computes the same as the plain loop however many chunks there are.
std::vector<IndexRange> split_into_chunks(size_t count, size_t min_chunk);

// work(c, chunks[c]) for every chunk, each on a thread of its own (for_each_device runs them:
// the same threads, fallback and failure rules).
void for_each_chunk(const std::vector<IndexRange>& chunks, const std::function<void(size_t, IndexRange)>& work);

// The loop body for i in [0, count), in chunks of at least min_chunk: body(begin, end).
inline void parallel_for(size_t count, size_t min_chunk, const std::function<void(size_t, size_t)>& body) {
  const std::vector<IndexRange> chunks = split_into_chunks(count, min_chunk);
  for_each_chunk(chunks, [&](size_t, IndexRange r) { body(r.begin, r.end); });
}

}  // namespace pm
