// Frames shared between devices (render/frame_runs.h): contiguous runs first, stealing the back
// half of the longest run left, every frame exactly once under concurrency.
#include "render/frame_runs.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace pm {
namespace {

std::vector<size_t> drain(FrameRuns& runs, size_t worker) {
  std::vector<size_t> items;
  while (auto item = runs.next(worker)) items.push_back(*item);
  return items;
}

TEST(FrameRuns, OneWorkerTakesEveryItemInOrder) {
  FrameRuns runs(5, 1);
  EXPECT_EQ(drain(runs, 0), (std::vector<size_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(runs.stolen(0), 0u);
}

TEST(FrameRuns, WorkersStartOnContiguousRunsOfNearlyEqualLength) {
  FrameRuns runs(10, 3);  // 4 + 3 + 3
  EXPECT_EQ(runs.next(0), 0u);
  EXPECT_EQ(runs.next(1), 4u);
  EXPECT_EQ(runs.next(2), 7u);
  EXPECT_EQ(runs.next(1), 5u);
}

TEST(FrameRuns, AnIdleWorkerTakesTheBackHalfOfTheLongestRunLeft) {
  FrameRuns runs(12, 2);  // 0..5 and 6..11
  EXPECT_EQ(runs.next(0), 0u);  // worker 0 is slow: 1..5 are left to it
  for (size_t expected = 6; expected < 12; ++expected) EXPECT_EQ(runs.next(1), expected);
  // Worker 1's run is spent: of 1..5 it takes 3..5 (the larger half), worker 0 keeps 1..2.
  EXPECT_EQ(runs.next(1), 3u);
  EXPECT_EQ(runs.stolen(1), 3u);
  EXPECT_EQ(runs.next(0), 1u);
  EXPECT_EQ(runs.next(0), 2u);
  // Worker 0 now steals from worker 1's 4..5: the back one.
  EXPECT_EQ(runs.next(0), 5u);
  EXPECT_EQ(runs.next(1), 4u);
  EXPECT_FALSE(runs.next(0).has_value());
  EXPECT_FALSE(runs.next(1).has_value());
}

TEST(FrameRuns, ARunOfOneIsTakenWhole) {
  FrameRuns runs(3, 2);  // 0..1 and 2
  EXPECT_EQ(runs.next(0), 0u);
  EXPECT_EQ(runs.next(1), 2u);
  EXPECT_EQ(runs.next(1), 1u);  // worker 0 is busy with 0; 1 is the only item left
  EXPECT_FALSE(runs.next(0).has_value());
}

TEST(FrameRuns, MoreWorkersThanItems) {
  FrameRuns runs(2, 4);
  EXPECT_EQ(runs.next(3), 0u);  // runs are {0}, {1}, {}, {}: worker 3 steals the first longest
  EXPECT_EQ(runs.next(2), 1u);
  EXPECT_FALSE(runs.next(0).has_value());
  EXPECT_FALSE(runs.next(1).has_value());
}

TEST(FrameRuns, ConcurrentWorkersTakeEveryItemExactlyOnce) {
  constexpr size_t kItems = 1000, kWorkers = 6;
  FrameRuns runs(kItems, kWorkers);
  std::vector<std::atomic<int>> taken(kItems);
  std::vector<std::thread> threads;
  for (size_t w = 0; w < kWorkers; ++w)
    threads.emplace_back([&, w] {
      while (auto item = runs.next(w)) {
        taken[*item]++;
        if (w == 0) std::this_thread::yield();  // a slower worker, so that others steal from it
      }
    });
  for (std::thread& t : threads) t.join();
  for (size_t i = 0; i < kItems; ++i) EXPECT_EQ(taken[i].load(), 1) << "item " << i;
}

}  // namespace
}  // namespace pm
