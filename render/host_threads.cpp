// Host threads: per device and per chunk of a loop (host_threads.h).
#include "render/host_threads.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace pm {

void for_each_device(size_t count, const std::function<void(size_t)>& work) {
  if (count == 0) return;
  if (count == 1) return work(0);
  std::vector<std::exception_ptr> failures(count);
  auto run = [&](size_t d) {
    try {
      work(d);
    } catch (...) {
      failures[d] = std::current_exception();
    }
  };
  // Where the system gives no more threads (a process or cgroup limit), the calling thread runs
  // the rest itself after its own.
  std::vector<std::thread> threads;
  size_t inline_from = count;
  for (size_t d = 1; d < count; ++d) {
    try {
      threads.emplace_back(run, d);
    } catch (const std::system_error&) {
      inline_from = d;
      break;
    }
  }
  run(0);
  for (size_t d = inline_from; d < count; ++d) run(d);
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& failure : failures)  // the lowest index's failure first
    if (failure) std::rethrow_exception(failure);
}

namespace {
std::atomic<unsigned> thread_limit{0};
}  // namespace

void set_host_thread_limit(unsigned threads) { thread_limit = threads; }

unsigned host_thread_count() {
  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const unsigned limit = thread_limit;
  return limit > 0 ? std::min(limit, hardware) : hardware;
}

std::vector<IndexRange> split_into_chunks(size_t count, size_t min_chunk) {
  const size_t threads = host_thread_count();
  const size_t chunks = std::max<size_t>(1, std::min(threads, count / std::max<size_t>(min_chunk, 1)));
  std::vector<IndexRange> out;
  for (size_t c = 0; c < chunks; ++c) out.push_back({count * c / chunks, count * (c + 1) / chunks});
  return out;
}

void for_each_chunk(const std::vector<IndexRange>& chunks, const std::function<void(size_t, IndexRange)>& work) {
  for_each_device(chunks.size(), [&](size_t c) { work(c, chunks[c]); });
}

}  // namespace pm
