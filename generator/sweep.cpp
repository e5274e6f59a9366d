#include "generator/sweep.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "runtime/format/little_endian.h"
#include "wrc/generator/interrupt.h"

namespace wrc::gen {

SegmentLayout::SegmentLayout(std::vector<std::size_t> shape, std::size_t min_segments)
    : shape_(std::move(shape)) {
  if (shape_.empty()) throw std::invalid_argument("SegmentLayout: a grid needs at least one axis");
  line_count_ = 1;
  for (std::size_t a = 0; a + 1 < shape_.size(); ++a) line_count_ *= shape_[a];
  const std::size_t length = shape_.back();
  segment_length_ = length;
  if (line_count_ < min_segments) {
    segment_length_ = std::max<std::size_t>(1, length * line_count_ / min_segments);
    segment_length_ = std::min(segment_length_, length);
  }
  segments_per_line_ = (length + segment_length_ - 1) / segment_length_;
}

std::uint64_t SegmentLayout::SegmentFirstPoint(std::uint64_t segment) const {
  const std::uint64_t line = segment / segments_per_line_;
  const std::uint64_t part = segment % segments_per_line_;
  return line * shape_.back() + part * segment_length_;
}

std::size_t SegmentLayout::SegmentSize(std::uint64_t segment) const {
  const std::size_t start =
      static_cast<std::size_t>(segment % segments_per_line_) * segment_length_;
  return std::min(segment_length_, shape_.back() - start);
}

std::vector<std::size_t> SegmentLayout::Indices(std::uint64_t point) const {
  std::vector<std::size_t> indices(shape_.size());
  for (std::size_t a = shape_.size(); a-- > 0;) {
    indices[a] = static_cast<std::size_t>(point % shape_[a]);
    point /= shape_[a];
  }
  return indices;
}

// ---------------------------------------------------------------------------------------------
// Task encoding: u32 count, then per task u64 segment, u32 n, n done bytes, n × f64 z.

std::string EncodeTasks(const std::vector<SegmentTask>& tasks) {
  std::string out;
  le::PutU32(out, static_cast<std::uint32_t>(tasks.size()));
  for (const SegmentTask& task : tasks) {
    le::PutU64(out, task.segment);
    le::PutU32(out, static_cast<std::uint32_t>(task.done.size()));
    for (const std::uint8_t d : task.done) le::PutU8(out, d);
    for (std::size_t k = 0; k < task.done.size(); ++k) le::PutF64(out, task.known_z[k]);
  }
  return out;
}

std::vector<SegmentTask> DecodeTasks(const std::string& bytes) {
  le::Reader in(bytes);
  const std::uint32_t count = in.U32();
  std::vector<SegmentTask> tasks;
  for (std::uint32_t t = 0; t < count && in.ok(); ++t) {
    SegmentTask task;
    task.segment = in.U64();
    const std::uint32_t n = in.U32();
    // Nine bytes a point: a count beyond what is left is damage, refused before allocating.
    if (n > in.remaining() / 9) throw std::runtime_error("malformed task message (length)");
    task.done.resize(n);
    task.known_z.resize(n);
    for (std::uint8_t& d : task.done) d = in.U8();
    for (double& z : task.known_z) z = in.F64();
    tasks.push_back(std::move(task));
  }
  if (!in.ok()) throw std::runtime_error("malformed task message (truncated)");
  if (!in.AtEnd()) throw std::runtime_error("malformed task message (trailing bytes)");
  return tasks;
}

// ---------------------------------------------------------------------------------------------
// StopControl, task sources

bool StopControl::ShouldStop() {
  if (stop_.load()) return true;
  if ((cancel_ != nullptr && cancel_->load()) || (watch_signals_ && InterruptRequested())) {
    stop_.store(true);
    return true;
  }
  return false;
}

bool StopControl::ClaimPoint() {
  if (ShouldStop()) return false;
  if (max_points_ > 0 && claimed_.fetch_add(1) >= max_points_) {
    stop_.store(true);
    return false;
  }
  return true;
}

std::optional<SegmentTask> TaskQueue::Next() {
  std::vector<SegmentTask> one = Take(1);
  if (one.empty()) return std::nullopt;
  return std::move(one.front());
}

std::vector<SegmentTask> TaskQueue::Take(std::size_t n) {
  std::vector<SegmentTask> taken;
  if (stop_.ShouldStop()) return taken;
  std::lock_guard<std::mutex> lock(mutex_);
  while (taken.size() < n && next_ < tasks_.size()) taken.push_back(std::move(tasks_[next_++]));
  return taken;
}

std::optional<SegmentTask> TaskInbox::Next() {
  std::unique_lock<std::mutex> lock(mutex_);
  ++waiting_;
  // Re-check the stop condition now and then: a signal cannot notify a condition variable.
  while (tasks_.empty() && !closed_ && !stop_.ShouldStop()) {
    changed_.wait_for(lock, std::chrono::milliseconds(100));
  }
  --waiting_;
  if (tasks_.empty() || stop_.ShouldStop()) return std::nullopt;
  SegmentTask task = std::move(tasks_.front());
  tasks_.pop_front();
  return task;
}

void TaskInbox::Add(std::vector<SegmentTask> tasks) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (tasks.empty()) closed_ = true;
    for (SegmentTask& task : tasks) tasks_.push_back(std::move(task));
  }
  changed_.notify_all();
}

void TaskInbox::WakeAll() { changed_.notify_all(); }

std::size_t TaskInbox::Queued() {
  std::lock_guard<std::mutex> lock(mutex_);
  return tasks_.size();
}

std::size_t TaskInbox::Waiting() {
  std::lock_guard<std::mutex> lock(mutex_);
  return waiting_;
}

// ---------------------------------------------------------------------------------------------
// WorkerPool

WorkerPool::WorkerPool(const Scene& scene, const SegmentLayout& layout, int threads,
                       bool warm_start, TaskSource& source, PointSink& sink, StopControl& stop)
    : scene_(scene),
      layout_(layout),
      warm_start_(warm_start),
      source_(source),
      sink_(sink),
      stop_(stop),
      threads_(
          threads, [this] { Work(); }, "wrc generate") {}

WorkerPool::~WorkerPool() {
  // Only reached with workers running when the owner is unwinding from an exception.
  if (!Finished()) stop_.RequestStop();
  Join();
}

void WorkerPool::Join() { threads_.Join(); }

void WorkerPool::RethrowIfFailed() {
  std::lock_guard<std::mutex> lock(failure_mutex_);
  if (failure_) std::rethrow_exception(failure_);
}

void WorkerPool::Work() {
  try {
    while (!stop_.ShouldStop()) {
      std::optional<SegmentTask> task = source_.Next();
      if (!task) break;
      SolveSegment(*task);
    }
  } catch (...) {
    {
      std::lock_guard<std::mutex> lock(failure_mutex_);
      if (!failure_) failure_ = std::current_exception();
    }
    stop_.RequestStop();
  }
}

void WorkerPool::SolveSegment(const SegmentTask& task) {
  const std::uint64_t first = layout_.SegmentFirstPoint(task.segment);
  const std::size_t size = layout_.SegmentSize(task.segment);
  // Warm start: z of the previous point of this segment when it solved fine, else a cold start.
  double previous_z = std::numeric_limits<double>::quiet_NaN();
  // A segment runs along the last axis: its points share the pose when that axis is a load or
  // a creepage, and the contact search with it.
  WheelRailCache cache;
  for (std::size_t k = 0; k < size; ++k) {
    if (!task.done.empty() && task.done[k] != 0) {
      previous_z = task.known_z[k];
      continue;
    }
    if (!stop_.ClaimPoint()) return;
    const std::uint64_t point = first + k;
    PointResult result = SolveScenePoint(
        scene_, layout_.Indices(point),
        warm_start_ ? previous_z : std::numeric_limits<double>::quiet_NaN(), &cache);
    previous_z = result.z;
    sink_.Accept(point, std::move(result));
  }
}

}  // namespace wrc::gen
