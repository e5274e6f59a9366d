#pragma once
/// @file worker_threads.h
/// The threads of a pool that takes its work from a shared queue (`wrc generate`, `wrc verify`,
/// the studies). The system may refuse a thread (a per-user process limit, no memory for its
/// stack); since each worker takes work until the queue is empty, the threads that did start
/// carry all of it, and a warning on stderr says how many there are. Part of the generator
/// library.

#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace wrc::gen {

/// Up to `count` threads that each run `body`, joined on destruction (also when the owner is
/// unwinding from an exception, where a joinable std::thread would end the process).
class WorkerThreads {
 public:
  /// Throws std::runtime_error naming `who` and the system's reason when not one thread starts.
  WorkerThreads(int count, const std::function<void()>& body, const std::string& who);
  ~WorkerThreads() { Join(); }
  WorkerThreads(const WorkerThreads&) = delete;
  WorkerThreads& operator=(const WorkerThreads&) = delete;

  /// How many threads started (1 … count).
  int started() const { return static_cast<int>(threads_.size()); }
  /// Waits for every thread; safe to call more than once.
  void Join();

 private:
  std::vector<std::thread> threads_;
};

}  // namespace wrc::gen
