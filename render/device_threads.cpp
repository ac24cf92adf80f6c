// One host thread per device (see device_threads.h).
#include "render/device_threads.h"

#include <exception>
#include <thread>
#include <vector>

namespace pm {

void for_each_device(size_t count, const std::function<void(size_t)>& work) {
  if (count == 0) return;
  if (count == 1) return work(0);
  std::vector<std::exception_ptr> failures(count);
  std::vector<std::thread> threads;
  for (size_t d = 1; d < count; ++d)
    threads.emplace_back([&, d] {
      try {
        work(d);
      } catch (...) {
        failures[d] = std::current_exception();
      }
    });
  try {
    work(0);
  } catch (...) {
    failures[0] = std::current_exception();
  }
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& failure : failures)  // the first device's failure first
    if (failure) std::rethrow_exception(failure);
}

}  // namespace pm
