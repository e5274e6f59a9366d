#include "wrc/generator/worker_threads.h"

#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <system_error>

namespace wrc::gen {

WorkerThreads::WorkerThreads(int count, const std::function<void()>& body, const std::string& who) {
  threads_.reserve(static_cast<std::size_t>(std::max(count, 0)));
  std::string refused;
  for (int t = 0; t < count; ++t) {
    try {
      threads_.emplace_back(body);
    } catch (const std::system_error& e) {
      refused = e.what();
      break;
    }
  }
  if (threads_.empty() && count > 0) {
    throw std::runtime_error(who + ": the system refused to start a worker thread (" + refused +
                             "); raise the process limit (ulimit -u) or free memory");
  }
  if (!refused.empty()) {
    std::cerr << "warning: " << who << ": the system started " << threads_.size() << " of " << count
              << " worker threads (" << refused << "); the work goes on with " << threads_.size()
              << '\n';
  }
}

void WorkerThreads::Join() {
  for (std::thread& thread : threads_) {
    if (thread.joinable()) thread.join();
  }
}

}  // namespace wrc::gen
