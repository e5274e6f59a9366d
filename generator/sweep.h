#pragma once
// The sweep engine: segments of grid lines solved by a pool of worker threads.
//
// A line is all points along the last axis for fixed other indices. The unit of work is a
// segment: a whole line, or, when the table has too few lines to keep many workers busy, a
// run of consecutive points of a line (see SegmentLayout). One worker solves a segment in
// order, warm-starting each point from the z of its predecessor in the segment, so the result
// of a point depends only on the point, its predecessor and the scene's shape, never on which
// worker, thread or rank ran it. Segments are handed out dynamically (TaskSource).

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "wrc/generator/generator.h"
#include "wrc/generator/worker_threads.h"

namespace wrc::gen {

/// Index arithmetic of a row-major grid split into segments along its last axis.
class SegmentLayout {
 public:
  /// Whole lines make the segments when there are at least min_segments lines; otherwise
  /// lines are cut into equal runs so that there are about that many segments. Depends only on
  /// the shape, so that results do not depend on the thread or rank count.
  SegmentLayout(std::vector<std::size_t> shape, std::size_t min_segments);

  std::size_t line_length() const { return shape_.back(); }
  std::size_t segment_length() const { return segment_length_; }
  std::size_t segment_count() const { return line_count_ * segments_per_line_; }
  std::size_t point_count() const { return line_count_ * shape_.back(); }
  /// First flat point index of a segment and its number of points.
  std::uint64_t SegmentFirstPoint(std::uint64_t segment) const;
  std::size_t SegmentSize(std::uint64_t segment) const;
  /// Per-axis indices of a flat row-major point index.
  std::vector<std::size_t> Indices(std::uint64_t point) const;

 private:
  std::vector<std::size_t> shape_;
  std::size_t line_count_ = 0;
  std::size_t segment_length_ = 1;
  std::size_t segments_per_line_ = 1;
};

/// One segment to solve. Points already finished (from a journal) are skipped; their z still
/// warm-starts the next point, exactly as if the segment had been solved in one go.
struct SegmentTask {
  std::uint64_t segment = 0;
  std::vector<std::uint8_t> done;  ///< Per point of the segment; empty: none done.
  std::vector<double> known_z;     ///< z of the done points (NaN where not ok).
};

/// Serialises tasks for sending to another rank (little-endian, like the journal).
std::string EncodeTasks(const std::vector<SegmentTask>& tasks);
/// Inverse of EncodeTasks; throws std::runtime_error on malformed bytes.
std::vector<SegmentTask> DecodeTasks(const std::string& bytes);

/// When the workers should stop early: an interrupt, a cancel flag, a point budget.
class StopControl {
 public:
  StopControl(const std::atomic<bool>* cancel, std::size_t max_points, bool watch_signals)
      : cancel_(cancel), max_points_(max_points), watch_signals_(watch_signals) {}
  /// Asks every worker to stop after its current point.
  void RequestStop() { stop_.store(true); }
  /// True once a stop was requested by any of the means above.
  bool ShouldStop();
  /// Reserves one point of the budget; false (and stop) when it is used up.
  bool ClaimPoint();

 private:
  std::atomic<bool> stop_{false};
  const std::atomic<bool>* cancel_;
  std::size_t max_points_;
  bool watch_signals_;
  std::atomic<std::size_t> claimed_{0};
};

/// Where workers get segments from.
class TaskSource {
 public:
  virtual ~TaskSource() = default;
  /// The next segment, or nothing when there is no more work (or a stop was requested). May block.
  virtual std::optional<SegmentTask> Next() = 0;
};

/// Where finished points go. Called concurrently from the workers.
class PointSink {
 public:
  virtual ~PointSink() = default;
  virtual void Accept(std::uint64_t point, PointResult result) = 0;
};

/// A fixed list of tasks handed out in order (rank 0, or a process on its own).
class TaskQueue : public TaskSource {
 public:
  TaskQueue(std::vector<SegmentTask> tasks, StopControl& stop)
      : tasks_(std::move(tasks)), stop_(stop) {}
  std::optional<SegmentTask> Next() override;
  /// Up to n tasks at once (for a remote rank); empty when none are left.
  std::vector<SegmentTask> Take(std::size_t n);

 private:
  std::mutex mutex_;
  std::vector<SegmentTask> tasks_;
  std::size_t next_ = 0;
  StopControl& stop_;
};

/// Tasks that arrive over time (an MPI rank other than 0): Next() waits for them.
class TaskInbox : public TaskSource {
 public:
  explicit TaskInbox(StopControl& stop) : stop_(stop) {}
  std::optional<SegmentTask> Next() override;
  /// Adds tasks; an empty list means no more will come.
  void Add(std::vector<SegmentTask> tasks);
  /// Wakes waiting workers (after a stop request).
  void WakeAll();
  std::size_t Queued();
  /// Workers currently waiting in Next() for a task.
  std::size_t Waiting();

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<SegmentTask> tasks_;
  bool closed_ = false;
  std::size_t waiting_ = 0;
  StopControl& stop_;
};

/// Worker threads solving segments until the source runs dry or a stop is requested.
class WorkerPool {
 public:
  WorkerPool(const Scene& scene, const SegmentLayout& layout, int threads, bool warm_start,
             TaskSource& source, PointSink& sink, StopControl& stop);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;
  /// True when every worker has exited.
  bool Finished() const { return threads_.Finished(); }
  /// How many workers started (fewer than asked when the system refused threads).
  int threads() const { return threads_.started(); }
  void Join();
  /// Rethrows the first exception a worker hit outside a solve (e.g. the journal's disk is
  /// full); such an exception also stops the other workers.
  void RethrowIfFailed();

 private:
  void Work();
  void SolveSegment(const SegmentTask& task);

  const Scene& scene_;
  SegmentLayout layout_;
  bool warm_start_;
  TaskSource& source_;
  PointSink& sink_;
  StopControl& stop_;
  std::mutex failure_mutex_;
  std::exception_ptr failure_;
  WorkerThreads threads_;  // last: its threads start once every other member is ready
};

}  // namespace wrc::gen
