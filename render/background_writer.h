// One thread that writes a sequence's frames behind its device: the device renders frame f + 1
// while frame f's file is written. One task at a time, on the same thread for the whole run, so a
// long sequence starts no thread per frame.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace pm {

class BackgroundWriter {
 public:
  BackgroundWriter();
  ~BackgroundWriter();  // finishes the task in flight, then ends the thread
  BackgroundWriter(const BackgroundWriter&) = delete;
  BackgroundWriter& operator=(const BackgroundWriter&) = delete;

  // Runs task on the thread once the previous task has finished; an exception the previous task
  // threw is rethrown here instead (and task is not started).
  void submit(std::function<void()> task);
  // Waits for the task in flight; rethrows its exception.
  void wait();

 private:
  void run();

  std::mutex mutex_;
  std::condition_variable changed_;
  std::function<void()> task_;  // set: waiting to run or running
  std::exception_ptr failure_;
  bool stopping_ = false;
  std::thread thread_;  // last: starts once the members above exist
};

}  // namespace pm
