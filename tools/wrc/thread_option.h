#pragma once
// The check and the default of every --threads option of the table commands.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <string>
#include <thread>

#include "tools/wrc/commands.h"
#include "wrc/generator/generator.h"

namespace wrc::cli {

/// A --threads value: 1 … kMaxWorkerThreads (wrc/generator/generator.h), or also 0 ("all cores")
/// where `zero_is_all_cores`.
inline CLI::Validator ThreadCount(bool zero_is_all_cores) {
  const double low = zero_is_all_cores ? 0.0 : 1.0;
  return NumberCheck(
      [low](double v) { return v >= low && v <= kMaxWorkerThreads && v == static_cast<int>(v); },
      std::string(zero_is_all_cores ? "0 (all cores) or " : "") + "a whole number 1 … " +
          std::to_string(kMaxWorkerThreads),
      "threads");
}

/// The default of --threads: all cores.
inline int AllCores() { return std::max(1, static_cast<int>(std::thread::hardware_concurrency())); }

}  // namespace wrc::cli
