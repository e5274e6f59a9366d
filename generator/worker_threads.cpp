#include "wrc/generator/worker_threads.h"

#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "wrc/core/errors.h"

namespace wrc::gen {

WorkerThreads::WorkerThreads(int count, const std::function<void()>& body, const std::string& who) {
  threads_.reserve(static_cast<std::size_t>(std::max(count, 0)));
  std::string refused;
  for (int t = 0; t < count; ++t) {
    unfinished_.fetch_add(1);
    try {
      threads_.emplace_back([this, body] {
        try {
          body();
        } catch (...) {
          const std::lock_guard<std::mutex> lock(failure_mutex_);
          if (!failure_) failure_ = std::current_exception();
        }
        unfinished_.fetch_sub(1);
      });
    } catch (const std::system_error& e) {
      unfinished_.fetch_sub(1);
      refused = e.what();
      break;
    }
  }
  if (threads_.empty() && count > 0) {
    throw ResourceError(who + ": the system refused to start a worker thread (" + refused +
                        "); raise the process limit (ulimit -u) or free memory");
  }
  if (!refused.empty()) {
    std::cerr << "warning: " << who << ": the system started " << threads_.size() << " of " << count
              << " worker threads (" << refused << "); the work goes on with " << threads_.size()
              << '\n';
  }
}

void WorkerThreads::JoinAll() {
  for (std::thread& thread : threads_) {
    if (thread.joinable()) thread.join();
  }
}

void WorkerThreads::Join() {
  JoinAll();
  const std::lock_guard<std::mutex> lock(failure_mutex_);
  if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
}

}  // namespace wrc::gen
