#pragma once
// Progress of `wrc generate` on stderr: on a terminal a bar redrawn in place (points done of
// total, rate, ETA); otherwise, e.g. in a batch job's log, a plain line every ~5 s.

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

#include "wrc/generator/generator.h"

namespace wrc::gen {

class ProgressReporter {
 public:
  /// total: points of the table; reused: finished before this run (not part of the rate).
  ProgressReporter(ProgressMode mode, std::size_t total, std::size_t reused,
                   std::FILE* stream = stderr);
  /// Called often (every ~0.1 s); draws at most every 0.25 s (bar) or 5 s (lines).
  void Update(std::size_t computed);
  /// Final state and a newline after the bar.
  void Finish(std::size_t computed);

  /// "1h02m", "3m15s", "42s", "?" for a non-finite or negative duration.
  static std::string FormatDuration(double seconds);

 private:
  void Draw(std::size_t computed, bool final_line);

  bool bar_ = false;
  bool enabled_ = true;
  std::size_t total_, reused_;
  std::FILE* stream_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool drawn_ = false;
};

/// CPU time (user and system, all threads) this process has used so far, in seconds: what a
/// table costs, as against the wall time, which depends on the cores and their other work.
double ProcessCpuSeconds();

}  // namespace wrc::gen
