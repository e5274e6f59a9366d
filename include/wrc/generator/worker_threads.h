#pragma once
/// @file worker_threads.h
/// The threads of a pool that takes its work from a shared queue (`wrc generate`, `wrc verify`,
/// the studies). The system may refuse a thread (a per-user process limit, no memory for its
/// stack); since each worker takes work until the queue is empty, the threads that did start
/// carry all of it, and a warning on stderr says how many there are. Part of the generator
/// library.

#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace wrc::gen {

/// Up to `count` threads that each run `body`, joined on destruction (also when the owner is
/// unwinding from an exception, where a joinable std::thread would end the process). An
/// exception that leaves `body` ends that thread only (escaping a std::thread it would end the
/// process); the first one is rethrown by Join().
class WorkerThreads {
 public:
  /// Throws ResourceError (wrc/core/errors.h) naming `who` and the system's reason when not one
  /// thread starts.
  WorkerThreads(int count, const std::function<void()>& body, const std::string& who);
  ~WorkerThreads() { JoinAll(); }
  WorkerThreads(const WorkerThreads&) = delete;
  WorkerThreads& operator=(const WorkerThreads&) = delete;

  /// How many threads started (1 … count).
  int started() const { return static_cast<int>(threads_.size()); }
  /// True when every started thread has left its body.
  bool Finished() const { return unfinished_.load() == 0; }
  /// Waits for every thread, then rethrows the first exception a body let out.
  void Join();

 private:
  void JoinAll();

  std::atomic<int> unfinished_{0};
  std::vector<std::thread> threads_;
  std::mutex failure_mutex_;
  std::exception_ptr failure_;
};

}  // namespace wrc::gen
