// GenerateTable(): the journal, the worker pool, the MPI protocol and the final table.
//
// Protocol under MPI (rank 0 owns the journal and the table; all MPI calls on main threads):
//   every rank > 0 sends HELLO (scene fingerprint, threads); rank 0 checks the fingerprints,
//   opens the journal and answers START (empty, or the error that stops everyone). Then a rank
//   whose workers wait for work sends REQUEST n and rank 0 answers TASKS, n segments (none: no
//   more work);
//   finished points travel back as RECORDS, which rank 0 stores and journals; an interrupted
//   rank 0 sends STOP; a rank whose workers have all finished sends DONE and leaves.
// Rank 0 only ever sends in reply or with non-blocking sends, so no two ranks can wait on each
// other.

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <optional>
#include <thread>
#include <utility>

#include "generator/cluster.h"
#include "generator/journal.h"
#include "generator/progress.h"
#include "generator/refine.h"
#include "generator/sha256.h"
#include "generator/sweep.h"
#include "generator/table_data.h"
#include "runtime/format/little_endian.h"
#include "wrc/core/errors.h"
#include "wrc/core/output_file.h"
#include "wrc/generator/generator.h"
#include "wrc/generator/interrupt.h"

namespace wrc {
namespace {

using gen::Cluster;
using gen::JournalHeader;
using gen::JournalRecord;
using gen::JournalWriter;
using gen::SegmentLayout;
using gen::SegmentTask;
using gen::TableData;

// A killed machine loses at most this much finished work (the journal's fdatasync cadence);
// syncing more often would cost disk flushes for nothing a process kill can take away.
constexpr auto kSyncInterval = std::chrono::seconds(1);
// How often a main thread looks at messages, progress and the clock. Solves take tens of
// milliseconds or more, so 1 ms (MPI) and 20 ms (single process) add no noticeable latency.
constexpr auto kMpiPollInterval = std::chrono::milliseconds(1);
constexpr auto kLocalPollInterval = std::chrono::milliseconds(20);
constexpr std::size_t kReportedFailures = 10;

std::string RawDigest(const std::string& hex) {
  std::string raw;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    raw += static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16));
  }
  return raw;
}

// What identifies the results of a run: the scene text, the profile bytes, the warm-start
// setting and the segment length (where warm-start chains restart). Two runs with the same
// fingerprint compute bit-identical points.
// The axes' node values to the bit: a refined table's nodes are not those of the scene text.
std::string AxesIdentity(const Scene& scene) {
  std::string identity;
  for (const SceneAxis& axis : scene.axes) {
    identity += axis.name + ":";
    for (const double value : axis.values) {
      char hex[32];
      std::snprintf(hex, sizeof hex, " %a", value);
      identity += hex;
    }
    identity += "\n";
  }
  return identity;
}

std::string Fingerprint(const Scene& scene, const SegmentLayout& layout,
                        const std::string& rail_sha, const std::string& wheel_sha,
                        bool warm_start) {
  const std::string identity = "wrc-journal 2\nwarm_start=" + std::to_string(warm_start) +
                               "\nsegment_length=" + std::to_string(layout.segment_length()) +
                               "\nrail_sha256=" + rail_sha + "\nwheel_sha256=" + wheel_sha +
                               "\naxes:\n" + AxesIdentity(scene) + "scene:\n" +
                               scene.base.source_text;
  return RawDigest(Sha256Hex(identity));
}

std::filesystem::path WithSuffix(const std::filesystem::path& path, const char* suffix) {
  return std::filesystem::path(path.string() + suffix);
}

// A rank's request for work: how many of its workers wait (u32).
std::string EncodeRequest(std::size_t waiting) {
  std::string request;
  le::PutU32(request, static_cast<std::uint32_t>(waiting));
  return request;
}

std::size_t DecodeRequest(const std::string& bytes) {
  le::Reader in(bytes);
  const std::uint32_t waiting = in.U32();
  if (!in.AtEnd()) throw std::runtime_error("MPI protocol: malformed request for work");
  return waiting;
}

// The sink of rank 0: stores each point and appends it to the journal.
class Collector : public gen::PointSink {
 public:
  Collector(TableData& data, JournalWriter& journal) : data_(data), journal_(journal) {}

  void Accept(std::uint64_t point, PointResult result) override {
    const std::string record = gen::EncodeRecord(point, result);
    std::lock_guard<std::mutex> lock(mutex_);
    if (!data_.Store(point, result)) return;  // a duplicate cannot differ: keep the first
    journal_.Append(record);
    computed_.fetch_add(1);
    dirty_.store(true);
  }

  std::size_t computed() const { return computed_.load(); }

  // fdatasync outside the lock: workers keep appending meanwhile.
  void Sync() {
    if (dirty_.exchange(false)) journal_.Sync();
  }

 private:
  TableData& data_;
  JournalWriter& journal_;
  std::mutex mutex_;
  std::atomic<std::size_t> computed_{0};
  std::atomic<bool> dirty_{false};
};

// The sink of a rank > 0: records wait here until the main thread sends them to rank 0.
class Outbox : public gen::PointSink {
 public:
  void Accept(std::uint64_t point, PointResult result) override {
    const std::string record = gen::EncodeRecord(point, result);
    std::lock_guard<std::mutex> lock(mutex_);
    bytes_ += record;
  }
  std::string Take() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(bytes_, {});
  }

 private:
  std::mutex mutex_;
  std::string bytes_;
};

// Segments that still have unfinished points, in row-major order, with what is known of them.
std::vector<SegmentTask> PendingSegments(const SegmentLayout& layout, const TableData& data) {
  std::vector<SegmentTask> tasks;
  for (std::uint64_t segment = 0; segment < layout.segment_count(); ++segment) {
    const std::uint64_t first = layout.SegmentFirstPoint(segment);
    const std::size_t size = layout.SegmentSize(segment);
    SegmentTask task;
    task.segment = segment;
    std::size_t done = 0;
    for (std::size_t k = 0; k < size; ++k) done += data.Has(first + k) ? 1 : 0;
    if (done == size) continue;
    if (done > 0) {
      task.done.resize(size);
      task.known_z.resize(size);
      for (std::size_t k = 0; k < size; ++k) {
        task.done[k] = data.Has(first + k) ? 1 : 0;
        task.known_z[k] = data.z[first + k];
      }
    }
    tasks.push_back(std::move(task));
  }
  return tasks;
}

// The table's z_warm_start attribute: how each prescribed-fz solve was started.
std::string WarmStartDescription(const SegmentLayout& layout, bool warm_start) {
  if (!warm_start) return "none";
  if (layout.segment_length() == 1) {
    return "none: every point starts from first contact (too few lines to chain points)";
  }
  std::string text = "previous point along the last axis";
  if (layout.segment_length() < layout.line_length()) {
    text += ", restarting cold every " + std::to_string(layout.segment_length()) + " points";
  }
  return text;
}

// Makes a finished file durable before it is renamed into place. A failed fsync is a failed
// write (delayed allocation reports a full disk only here), so it is an error.
void SyncFile(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) throw InputError(path.string() + ": cannot open to sync: " + std::strerror(errno));
  const bool synced = ::fsync(fd) == 0;
  const int error = errno;
  if (::close(fd) != 0 || !synced) {
    throw InputError(path.string() +
                     ": cannot sync to disk: " + std::strerror(synced ? errno : error));
  }
}

void SyncDirectory(const std::filesystem::path& file) {
  const std::filesystem::path dir = file.has_parent_path() ? file.parent_path() : ".";
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// Writes the table to `temporary` (created exclusively: a planted symlink is never followed),
// syncs it and renames it to `output`, which must be a regular file or absent. On any failure
// the temporary file is removed and `output` keeps what it held.
void WriteTableSafely(const std::filesystem::path& temporary, const std::filesystem::path& output,
                      const Scene& scene, const gen::TableData& data,
                      const gen::TableProvenance& provenance) {
  RequireRegularOutput(output);
  CreateExclusively(temporary);
  try {
    gen::WriteTableFile(temporary, scene, data, provenance);
    SyncFile(temporary);
    RequireRegularOutput(temporary);  // still the file created above, not something swapped in
    std::filesystem::rename(temporary, output);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

struct RunContext {
  const Scene& scene;
  const GenerateOptions& options;
  Cluster* cluster;
  int threads;
  const SegmentLayout& layout;
  std::string fingerprint;
  std::string rail_sha, wheel_sha;
  gen::StopControl& stop;
  const gen::GridHooks& hooks;
};

// Points an earlier refinement pass knows: stored and journaled as if solved in this run, so
// that the journal alone describes the pass (a resume needs nothing else).
void TakeOverKnownPoints(const gen::GridHooks& hooks, TableData& data, JournalWriter& journal) {
  if (!hooks.known) return;
  PointResult result;
  for (std::uint64_t point = 0; point < data.status.size(); ++point) {
    if (data.Has(point) || !hooks.known(point, &result)) continue;
    data.Store(point, result);
    journal.Append(gen::EncodeRecord(point, result));
  }
  journal.Sync();
}

// Waits (polling) for one message with the given tag from anyone; other tags are a protocol
// error at this stage.
std::string AwaitMessage(Cluster& cluster, int wanted_tag, int* source) {
  int tag = 0;
  std::string bytes;
  for (;;) {
    if (cluster.Receive(source, &tag, &bytes)) {
      if (tag != wanted_tag) {
        throw std::runtime_error("MPI protocol: unexpected message tag " + std::to_string(tag) +
                                 " while waiting for " + std::to_string(wanted_tag));
      }
      return bytes;
    }
    std::this_thread::sleep_for(kMpiPollInterval);
  }
}

// Every other rank must solve the same scene with the same profiles: its hello is its
// fingerprint of them.
void CheckRankFingerprints(const RunContext& run) {
  for (int r = 1; r < run.cluster->size(); ++r) {
    int source = 0;
    const std::string hello = AwaitMessage(*run.cluster, gen::kTagHello, &source);
    if (hello != run.fingerprint) {
      throw InputError("MPI rank " + std::to_string(source) +
                       " sees a different scene or different profile files than rank 0; "
                       "every rank must read the same files");
    }
  }
}

// Continues the journal of an interrupted run (--resume), its points into `data`.
JournalWriter ContinueJournal(const RunContext& run, const std::filesystem::path& path,
                              const JournalHeader& header, TableData& data) {
  if (!run.options.resume) {
    throw InputError(path.string() +
                     " exists: an earlier run of this table was interrupted. Pass --resume to "
                     "continue it (finished points are reused), or delete the journal to start "
                     "over");
  }
  gen::JournalContents contents;
  JournalWriter journal = JournalWriter::Continue(path, header, &contents);
  for (JournalRecord& record : contents.records) data.Store(record.index, record.result);
  if (contents.valid_bytes < contents.file_bytes && run.options.progress != ProgressMode::kOff) {
    std::fprintf(stderr, "wrc generate: dropped %llu bytes of a torn record at the end of %s\n",
                 static_cast<unsigned long long>(contents.file_bytes - contents.valid_bytes),
                 path.c_str());
  }
  return journal;
}

// The journal of this run: continued when one exists, else created next to the output.
JournalWriter OpenJournal(const RunContext& run, const std::filesystem::path& path,
                          TableData& data) {
  const std::filesystem::path output = run.options.output;
  const std::filesystem::path directory =
      output.has_parent_path() ? output.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(directory)) {
    throw InputError(output.string() + ": the directory " + directory.string() + " does not exist");
  }
  const JournalHeader header{run.fingerprint, data.status.size(),
                             static_cast<std::uint32_t>(run.scene.outputs.size())};
  if (std::filesystem::exists(path)) return ContinueJournal(run, path, header, data);
  if (run.options.resume && run.options.progress != ProgressMode::kOff) {
    std::fprintf(stderr,
                 "wrc generate: no journal %s to resume from; starting from the beginning\n",
                 path.c_str());
  }
  return JournalWriter::Create(path, header);
}

// Tells the other ranks whether rank 0 could start (an empty refusal: yes), so that none waits
// forever for work that will not come.
void ShareSetupOutcome(Cluster* cluster, const std::exception_ptr& failure) {
  if (cluster == nullptr) return;
  std::string refusal;
  if (failure) {
    try {
      std::rethrow_exception(failure);
    } catch (const std::exception& e) {
      refusal = e.what();
    } catch (...) {
    }
    if (refusal.empty()) refusal = "rank 0 could not start the run";
  }
  for (int r = 1; r < cluster->size(); ++r) cluster->Send(r, gen::kTagStart, refusal);
  cluster->CompleteSends();
}

// Set-up on rank 0: the ranks' fingerprints checked, the journal opened (its points in `data`),
// the outcome shared with every rank.
JournalWriter SetUpRoot(const RunContext& run, const std::filesystem::path& journal_path,
                        TableData& data) {
  std::exception_ptr failure;
  std::optional<JournalWriter> journal;
  try {
    if (run.cluster != nullptr) CheckRankFingerprints(run);
    journal.emplace(OpenJournal(run, journal_path, data));
  } catch (...) {
    failure = std::current_exception();
  }
  ShareSetupOutcome(run.cluster, failure);
  if (failure) std::rethrow_exception(failure);
  return std::move(*journal);
}

// One round of the other ranks' messages: requests for work answered, their points collected,
// finished ranks counted. True when anything arrived.
bool ServeRanks(Cluster& cluster, gen::TaskQueue& queue, Collector& collector, int* active_ranks) {
  bool received = false;
  int source = 0, tag = 0;
  std::string bytes;
  while (cluster.Receive(&source, &tag, &bytes)) {
    received = true;
    if (tag == gen::kTagRequest) {
      cluster.Send(source, gen::kTagTasks, gen::EncodeTasks(queue.Take(DecodeRequest(bytes))));
    } else if (tag == gen::kTagRecords) {
      for (JournalRecord& record : gen::DecodeRecords(bytes)) {
        collector.Accept(record.index, std::move(record.result));
      }
    } else if (tag == gen::kTagDone) {
      --*active_ranks;
    }
  }
  return received;
}

// Solves the pending segments on this rank's workers and serves the other ranks until every
// segment is done or the run stops; the journal synced at least every kSyncInterval. Returns
// the number of worker threads that ran.
int SolveOnRoot(const RunContext& run, gen::TaskQueue& queue, Collector& collector,
                gen::ProgressReporter& progress) {
  Cluster* cluster = run.cluster;
  const int ranks = cluster ? cluster->size() : 1;
  gen::WorkerPool pool(run.scene, run.layout, run.threads, run.options.warm_start, queue, collector,
                       run.stop);
  int active_ranks = ranks - 1;
  bool stop_sent = false;
  auto last_sync = std::chrono::steady_clock::now();
  while (!pool.Finished() || active_ranks > 0) {
    const bool received = cluster && ServeRanks(*cluster, queue, collector, &active_ranks);
    if (cluster && !stop_sent && run.stop.ShouldStop()) {
      for (int r = 1; r < ranks; ++r) cluster->Send(r, gen::kTagStop, {});
      stop_sent = true;
    }
    const auto now = std::chrono::steady_clock::now();
    if (now - last_sync >= kSyncInterval) {
      collector.Sync();
      last_sync = now;
    }
    progress.Update(collector.computed());
    if (!received) std::this_thread::sleep_for(cluster ? kMpiPollInterval : kLocalPollInterval);
  }
  pool.Join();
  collector.Sync();
  pool.RethrowIfFailed();
  if (cluster) cluster->CompleteSends();
  return pool.threads();  // fewer than asked when the system refused some
}

void CountOutcomes(const TableData& data, GenerateSummary& summary) {
  for (const std::int8_t status : data.status) {
    if (status >= 0) ++summary.status_counts[status];
  }
  for (const auto& [point, message] : data.messages) {
    if (summary.failures.size() == kReportedFailures) break;
    summary.failures.emplace_back(point, message);
  }
}

// A finished grid becomes the table (or, for a refinement pass, stays in its journal); an
// unfinished one leaves its journal for --resume.
void FinishRoot(const RunContext& run, TableData& data, JournalWriter& journal,
                GenerateSummary& summary) {
  if (data.finished == summary.points && !run.hooks.write_table) {
    // A refinement pass: its journal is its record; the table is written after the last pass.
    journal.Close();
    summary.complete = true;
    if (run.hooks.data_out != nullptr) *run.hooks.data_out = std::move(data);
  } else if (data.finished == summary.points) {
    const std::filesystem::path temporary = WithSuffix(run.options.output, ".tmp");
    gen::TableProvenance provenance;
    provenance.rail_sha256 = run.rail_sha;
    provenance.wheel_sha256 = run.wheel_sha;
    provenance.created = gen::IsoTimestampUtc();
    provenance.z_warm_start = WarmStartDescription(run.layout, run.options.warm_start);
    provenance.attributes = run.hooks.attributes;
    WriteTableSafely(temporary, run.options.output, run.scene, data, provenance);
    SyncDirectory(run.options.output);
    // Only now is the journal redundant; a crash before this line leaves a complete journal,
    // from which --resume rewrites the table without solving anything.
    journal.Close();
    std::filesystem::remove(summary.journal);
    summary.complete = true;
  } else {
    journal.Close();
    summary.interrupted = true;
  }
}

GenerateSummary RunRoot(const RunContext& run) {
  const auto start = std::chrono::steady_clock::now();
  const Scene& scene = run.scene;
  GenerateSummary summary;
  summary.points = scene.PointCount();
  summary.threads = run.threads;
  summary.ranks = run.cluster ? run.cluster->size() : 1;
  summary.journal = WithSuffix(run.options.output, ".journal");
  summary.axes = scene.axes;

  TableData data(summary.points, scene.outputs.size());
  JournalWriter journal = SetUpRoot(run, summary.journal, data);
  TakeOverKnownPoints(run.hooks, data, journal);
  summary.reused = data.finished;

  gen::TaskQueue queue(PendingSegments(run.layout, data), run.stop);
  Collector collector(data, journal);
  gen::ProgressReporter progress(run.options.progress, summary.points, summary.reused);
  summary.threads = SolveOnRoot(run, queue, collector, progress);
  summary.computed = collector.computed();
  progress.Finish(summary.computed);

  CountOutcomes(data, summary);
  FinishRoot(run, data, journal, summary);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

GenerateSummary RunOtherRank(const RunContext& run) {
  const auto start = std::chrono::steady_clock::now();
  Cluster& cluster = *run.cluster;
  cluster.Send(0, gen::kTagHello, run.fingerprint);
  int source = 0;
  const std::string refusal = AwaitMessage(cluster, gen::kTagStart, &source);
  if (!refusal.empty()) throw GenerateAborted(refusal);

  GenerateSummary summary;
  summary.points = run.scene.PointCount();
  summary.threads = run.threads;
  summary.ranks = cluster.size();
  summary.is_root = false;

  gen::TaskInbox inbox(run.stop);
  Outbox outbox;
  {
    gen::WorkerPool pool(run.scene, run.layout, run.threads, run.options.warm_start, inbox, outbox,
                         run.stop);
    summary.threads = pool.threads();
    bool request_open = false, no_more_work = false;
    for (;;) {
      int tag = 0;
      std::string bytes;
      while (cluster.Receive(&source, &tag, &bytes)) {
        if (tag == gen::kTagTasks) {
          request_open = false;
          std::vector<SegmentTask> tasks = gen::DecodeTasks(bytes);
          no_more_work = no_more_work || tasks.empty();
          inbox.Add(std::move(tasks));
        } else if (tag == gen::kTagStop) {
          run.stop.RequestStop();
          inbox.WakeAll();
        }
      }
      // Ask for segments only when workers are idle: segments held here could not go to idle
      // workers elsewhere, which would stretch the end of the run.
      const std::size_t waiting = inbox.Waiting();
      if (!request_open && !no_more_work && !run.stop.ShouldStop() && waiting > 0 &&
          inbox.Queued() == 0) {
        cluster.Send(0, gen::kTagRequest, EncodeRequest(waiting));
        request_open = true;
      }
      std::string records = outbox.Take();
      if (!records.empty()) cluster.Send(0, gen::kTagRecords, std::move(records));
      if (run.stop.ShouldStop()) inbox.WakeAll();
      // Leave only with every record sent and no answer outstanding.
      if (pool.Finished() && !request_open) {
        records = outbox.Take();
        if (!records.empty()) cluster.Send(0, gen::kTagRecords, std::move(records));
        cluster.Send(0, gen::kTagDone, {});
        break;
      }
      std::this_thread::sleep_for(kMpiPollInterval);
    }
    pool.Join();
    pool.RethrowIfFailed();
    summary.interrupted = run.stop.ShouldStop();
  }
  cluster.CompleteSends();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace

bool GeneratorSupportsMpi() { return gen::ClusterSupportAvailable(); }

const char* GeneratorVersion() { return WRC_VERSION; }

namespace gen {

int ThreadsFor(const GenerateOptions& options, const Cluster* cluster) {
  if (options.threads < 0 || options.threads > kMaxWorkerThreads) {
    throw InputError("threads: must be 0 (all cores) … " + std::to_string(kMaxWorkerThreads) +
                     ", is " + std::to_string(options.threads));
  }
  if (options.threads > 0) return options.threads;
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return std::max(1, cores / (cluster ? cluster->local_size() : 1));
}

GenerateSummary GenerateGrid(const Scene& scene, const GenerateOptions& options, Cluster* cluster,
                             const GridHooks& hooks) {
  std::optional<gen::InterruptHandlers> handlers;
  if (options.handle_signals) {
    gen::ClearInterrupt();
    handlers.emplace();
  }
  gen::StopControl stop(options.cancel, options.max_points,
                        options.handle_signals || hooks.watch_signals);

  const std::string rail_sha = Sha256FileHex(scene.base.rail.path);
  const std::string wheel_sha = Sha256FileHex(scene.base.wheel.path);
  const SegmentLayout layout(scene.Shape(), std::max<std::size_t>(1, options.min_segments));
  const RunContext run{
      scene,    options,
      cluster,  ThreadsFor(options, cluster),
      layout,   Fingerprint(scene, layout, rail_sha, wheel_sha, options.warm_start),
      rail_sha, wheel_sha,
      stop,     hooks};
  if (cluster && cluster->rank() != 0) return RunOtherRank(run);
  return RunRoot(run);
}

}  // namespace gen

GenerateSummary GenerateTable(const Scene& scene, const GenerateOptions& options) {
  if (options.output.empty()) throw InputError("no output file given");
  RequireRegularOutput(options.output);  // before any solving, not after it
  RequireNotAnInput(options.output, {scene.base.rail.path, scene.base.wheel.path});
  std::unique_ptr<Cluster> cluster;
  if (options.mpi == MpiMode::kAuto) cluster = gen::JoinClusterIfLaunched();
  const double cpu_start = gen::ProcessCpuSeconds();
  GenerateSummary summary =
      scene.refine ? gen::RefineTable(scene, options, cluster.get())
                   : gen::GenerateGrid(scene, options, cluster.get(), gen::GridHooks{});
  summary.cpu_seconds = gen::ProcessCpuSeconds() - cpu_start;
  return summary;
}

}  // namespace wrc
