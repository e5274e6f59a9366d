#include "generator/progress.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <limits>

namespace wrc::gen {
namespace {

constexpr auto kBarInterval = std::chrono::milliseconds(250);
constexpr auto kLineInterval = std::chrono::seconds(5);
constexpr int kBarWidth = 30;

}  // namespace

ProgressReporter::ProgressReporter(ProgressMode mode, std::size_t total, std::size_t reused,
                                   std::FILE* stream)
    : total_(total), reused_(reused), stream_(stream) {
  enabled_ = mode != ProgressMode::kOff;
  bar_ = mode == ProgressMode::kBar || (mode == ProgressMode::kAuto && isatty(fileno(stream)));
  start_ = last_draw_ = std::chrono::steady_clock::now();
}

std::string ProgressReporter::FormatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  const auto s = static_cast<long long>(std::llround(seconds));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%lldh%02lldm", s / 3600, s / 60 % 60);
  } else if (s >= 60) {
    std::snprintf(text, sizeof text, "%lldm%02llds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%llds", s);
  }
  return text;
}

void ProgressReporter::Update(std::size_t computed) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const std::chrono::steady_clock::duration interval =
      bar_ ? std::chrono::steady_clock::duration(kBarInterval)
           : std::chrono::steady_clock::duration(kLineInterval);
  if (now - last_draw_ < interval) return;
  last_draw_ = now;
  Draw(computed, false);
}

void ProgressReporter::Finish(std::size_t computed) {
  if (!enabled_) return;
  if (bar_ || drawn_) Draw(computed, true);
}

void ProgressReporter::Draw(std::size_t computed, bool final_line) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::size_t done = reused_ + computed;
  const double fraction = total_ > 0 ? static_cast<double>(done) / static_cast<double>(total_) : 1;
  const double rate = elapsed > 0.0 ? static_cast<double>(computed) / elapsed : 0.0;
  const double eta = rate > 0.0 ? static_cast<double>(total_ - done) / rate
                                : std::numeric_limits<double>::quiet_NaN();
  const std::string eta_text = final_line ? "" : ", ETA " + FormatDuration(eta);
  if (bar_) {
    const int filled = static_cast<int>(fraction * kBarWidth);
    std::string bar(static_cast<std::size_t>(kBarWidth), ' ');
    for (int i = 0; i < filled; ++i) bar[static_cast<std::size_t>(i)] = '=';
    if (filled < kBarWidth) bar[static_cast<std::size_t>(filled)] = '>';
    // \r returns to the line start, \033[K clears what a longer previous line left behind.
    std::fprintf(stream_, "\r%3.0f%% [%s] %zu/%zu points, %.1f points/s, elapsed %s%s\033[K%s",
                 100.0 * fraction, bar.c_str(), done, total_, rate, FormatDuration(elapsed).c_str(),
                 eta_text.c_str(), final_line ? "\n" : "");
  } else {
    std::fprintf(stream_, "wrc generate: %zu/%zu points (%.0f%%), %.1f points/s, elapsed %s%s\n",
                 done, total_, 100.0 * fraction, rate, FormatDuration(elapsed).c_str(),
                 eta_text.c_str());
  }
  std::fflush(stream_);
  drawn_ = true;
}

double ProcessCpuSeconds() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return std::numeric_limits<double>::quiet_NaN();
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

}  // namespace wrc::gen
