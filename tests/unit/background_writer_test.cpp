// The thread that writes frames behind the device (render/background_writer.h): tasks run one at
// a time in order on one thread, a task's exception comes back at the next wait or submit, and
// the destructor finishes the task in flight.
#include "render/background_writer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace pm {
namespace {

TEST(BackgroundWriter, RunsTasksOneAtATimeInOrderOnOneThread) {
  std::vector<int> order;
  std::set<std::thread::id> threads;
  std::atomic<int> running{0};
  bool overlapped = false;
  {
    BackgroundWriter writer;
    for (int i = 0; i < 20; ++i)
      writer.submit([&, i] {
        overlapped |= ++running > 1;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        order.push_back(i);
        threads.insert(std::this_thread::get_id());
        --running;
      });
    writer.wait();
    EXPECT_EQ(order.size(), 20u);
  }
  for (int i = 0; i < 20; ++i) EXPECT_EQ(order[i], i);
  EXPECT_EQ(threads.size(), 1u);
  EXPECT_NE(*threads.begin(), std::this_thread::get_id());
  EXPECT_FALSE(overlapped);
}

TEST(BackgroundWriter, ATasksFailureComesBackAtTheNextWaitOrSubmit) {
  BackgroundWriter writer;
  writer.submit([] { throw std::runtime_error("disk full"); });
  EXPECT_THROW(writer.wait(), std::runtime_error);
  writer.wait();  // reported once
  bool ran = false;
  writer.submit([] { throw std::runtime_error("disk full"); });
  EXPECT_THROW(writer.submit([&] { ran = true; }), std::runtime_error);
  writer.wait();
  EXPECT_FALSE(ran) << "a task submitted after a failure is not started";
}

TEST(BackgroundWriter, TheDestructorFinishesTheTaskInFlight) {
  std::atomic<bool> done{false};
  {
    BackgroundWriter writer;
    writer.submit([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      done = true;
    });
  }
  EXPECT_TRUE(done);
}

}  // namespace
}  // namespace pm
