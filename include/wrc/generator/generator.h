#pragma once
/// @file generator.h
/// `wrc generate` (docs/reference/table-layout.md): solves a scene at every grid point and writes
/// the HDF5 table.
///
/// The sweep is split into *lines*: all points along the last axis for fixed other indices
/// (cut into shorter segments when a table has few lines, see GenerateOptions::min_segments).
/// A segment is solved in order by one worker, each point warm-started from the wheelset height
/// of the previous point of the segment; segments go to worker threads (and MPI ranks)
/// dynamically. Because a point's result depends only on its own case, on its predecessor and
/// on the scene's shape, tables are bit-identical whatever the number of threads or ranks, and
/// whether or not the run was interrupted and resumed.
///
/// Every finished point is appended to a journal next to the output (`TABLE.h5.journal`) at
/// once and flushed to disk every second, so an interrupted run loses at most the points in
/// flight (Ctrl-C, kill -9) or the last second of them (a machine that loses power); the table
/// itself is written at the end to `TABLE.h5.tmp` and renamed into place.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "wrc/core/errors.h"
#include "wrc/core/scene.h"
#include "wrc/core/wheelrail.h"

namespace wrc {

namespace h5 {
class File;
}  // namespace h5

/// Outcome of one grid point, as stored in the table's /status dataset.
enum class PointStatus : std::int8_t {
  kOk = 0,            ///< Solved; all outputs hold numbers.
  kNoContact = 1,     ///< Wheel and rail do not touch: forces 0, locations NaN.
  kNotConverged = 2,  ///< A solver hit its iteration limit: outputs NaN, message in /errors.
  kError = 3,         ///< The solve threw (bad pose, ...): outputs NaN, message in /errors.
};

/// Number of PointStatus values.
inline constexpr int kPointStatusCount = 4;

/// "ok", "no_contact", "not_converged" or "error", as `wrc solve` names them.
const char* ToString(PointStatus status);

/// One solved grid point: what the table and the journal store of it.
struct PointResult {
  PointStatus status = PointStatus::kError;
  /// Wall time of the solve, s.
  float solve_time_s = 0.0f;
  /// The wheelset height of the solution (the warm start of the next point of its line); NaN
  /// unless status is kOk.
  double z = std::numeric_limits<double>::quiet_NaN();
  /// One value per scene output, in scene.outputs order.
  std::vector<double> values;
  /// Why the point failed (status kNotConverged or kError); for a solved point its warnings
  /// (WheelRailResult::warnings, joined by "; "), empty when it has none.
  std::string message;
};

/// The stored outputs of a solve, in scene.outputs order (docs/reference/table-layout.md):
///  - fx fy fz mx my mz: force on the rail in the track frame, moments about the rail origin;
///  - fx_ws fy_ws fz_ws: the same force in the wheelset frame;
///  - n_patches; pmax: the largest peak pressure over the patches; z: the wheelset height;
///  - contact_y, contact_angle: where the force resultant meets the rail (paper Eq. 25–27); if
///    that location cannot be found, the reference of the patch carrying the largest normal
///    force stands in for it.
/// For kNoContact: forces, moments, n_patches and pmax are 0, contact_y and contact_angle NaN.
/// For kNotConverged and kError every value is NaN.
std::vector<double> SceneOutputValues(const Scene& scene, const WheelRailResult& result,
                                      PointStatus status);

/// The message a failed point (kError) stores for the exception that ended its solve, when the
/// exception is a property of the point: InputError (the pose or the case) or NumericalError.
/// Anything else is rethrown and stops the run instead of becoming a table entry: a
/// std::logic_error or any other exception (a bug in wrc) unchanged, std::bad_alloc as a
/// ResourceError saying that the points solved so far are kept.
std::string PointFailureMessage(std::exception_ptr error);

/// Solves the grid point at `indices` (one per axis) exactly as `wrc generate` does: z_guess
/// warm-starts a prescribed-fz solve (NaN: cold start); an exception becomes kError or
/// propagates as PointFailureMessage() decides. `cache`
/// (may be null): the calling thread's work kept between points (WheelRailCache).
PointResult SolveScenePoint(const Scene& scene, const std::vector<std::size_t>& indices,
                            double z_guess = std::numeric_limits<double>::quiet_NaN(),
                            WheelRailCache* cache = nullptr);

/// When progress is shown on stderr.
enum class ProgressMode {
  kAuto,   ///< A bar redrawn in place on a terminal, otherwise a line every ~5 s.
  kBar,    ///< Always the bar.
  kLines,  ///< Always plain lines.
  kOff,    ///< Nothing (--quiet).
};

/// Whether to split the work across MPI ranks.
enum class MpiMode {
  kAuto,  ///< Join MPI when launched by mpirun/mpiexec with more than one rank.
  kOff,   ///< Never, even under mpirun (each process would then run the whole table).
};

/// The most worker threads a process starts. Each holds its own solver workspace, so threads
/// beyond the cores only cost memory; 1024 covers the largest single machines, and far more fail
/// to start at all (the system's thread limit).
inline constexpr int kMaxWorkerThreads = 1024;

/// Options of GenerateTable().
struct GenerateOptions {
  /// The table to write (TABLE.h5). The journal is TABLE.h5.journal, the temporary file
  /// TABLE.h5.tmp. An existing table is replaced (atomically) when the run completes.
  std::filesystem::path output;
  /// Worker threads per process; 0: std::thread::hardware_concurrency(), shared out among the
  /// MPI ranks running on the same machine. At most kMaxWorkerThreads (InputError otherwise).
  int threads = 0;
  /// Continue from the journal of an interrupted run. Without it, an existing journal is an
  /// error (InputError) so that no work is thrown away by accident.
  bool resume = false;
  ProgressMode progress = ProgressMode::kAuto;
  /// Warm-start each prescribed-fz point from its predecessor's z in the segment (measured to
  /// save about 15 % of the fz iterations and 3–4 % of the time on tables/mbench.toml). Changes the
  /// last bits of the results, so a journal records it and a resume must use the same setting.
  bool warm_start = true;
  /// Lines are the units of work when the table has at least this many of them; otherwise
  /// they are cut into runs of equal length so that there are about this many units, each
  /// warm-start chain restarting cold. Keeps all cores busy on tables with few lines (a 1-D
  /// sweep is a single line). Part of what a journal records, like warm_start.
  std::size_t min_segments = 64;
  /// Install SIGINT/SIGTERM handlers for the duration of the run: the first signal stops the
  /// run cleanly (finished points stay in the journal), a second one kills the process.
  bool handle_signals = false;
  /// Stop as if interrupted as soon as this becomes true (may be null).
  const std::atomic<bool>* cancel = nullptr;
  /// Stop as if interrupted after solving this many points in this run; 0: no limit.
  /// Deterministic interruption for tests.
  std::size_t max_points = 0;
  MpiMode mpi = MpiMode::kAuto;
  /// A refinement also writes the grid of every pass as a table, TABLE.h5.pass<P>.h5.
  bool keep_passes = false;
};

/// What a GenerateTable() run did.
struct GenerateSummary {
  std::size_t points = 0;    ///< Grid points of the scene.
  std::size_t reused = 0;    ///< Taken over from the journal (--resume).
  std::size_t computed = 0;  ///< Solved in this run (by all ranks).
  /// Finished points by PointStatus (index = status value).
  std::size_t status_counts[kPointStatusCount] = {0, 0, 0, 0};
  /// True when the table was written; false when the run stopped early (interrupted,
  /// cancelled, max_points, a rank that stopped): the journal then holds the finished points.
  bool complete = false;
  bool interrupted = false;  ///< Stopped by a signal, cancel or max_points.
  double seconds = 0.0;      ///< Wall time of the run.
  double cpu_seconds = 0.0;  ///< CPU time of this process (all its threads) in the run.
  /// A refinement on rank 0: per pass, its grid's points and this process's CPU seconds from
  /// the start of the run (or of its resume) to the end of the pass.
  struct Pass {
    std::size_t points = 0;
    double cpu_seconds = 0.0;
  };
  std::vector<Pass> passes;
  int threads = 0;  ///< Worker threads of this process.
  int ranks = 1;    ///< MPI ranks that took part (1 without MPI).
  /// False on MPI ranks other than 0: those neither write nor report, the caller stays quiet.
  bool is_root = true;
  /// Up to 10 failed points (flat row-major index and message), in index order.
  std::vector<std::pair<std::uint64_t, std::string>> failures;
  std::filesystem::path journal;  ///< The journal file used (a refinement: its directory).
  /// The table's axes: the scene's, or the nodes a refinement chose.
  std::vector<SceneAxis> axes;
};

/// Thrown by GenerateTable() on MPI ranks other than 0 when rank 0 refused to start the run;
/// rank 0 reports the reason, the other ranks should exit quietly with the same exit code.
class GenerateAborted : public InputError {
 public:
  using InputError::InputError;
};

/// Generates the table of `scene` (loaded with LoadScene, so profile paths are resolved).
/// Throws InputError for problems the user must fix (an existing journal without resume, a
/// damaged journal or a journal of another scene, unreadable profiles, an unwritable output),
/// ResourceError when memory or threads run out, and h5::Error (runtime/hdf5) when writing the
/// table fails. Failing points do not throw: they are recorded with their status and message;
/// an exception that is no property of a point propagates (PointFailureMessage).
GenerateSummary GenerateTable(const Scene& scene, const GenerateOptions& options);

/// What `wrc generate --estimate` measures before a run: short runs of the scene's grid solved
/// as the generator solves them (consecutive points along the last axis, each prescribed-fz
/// point warm-started from its predecessor's z).
struct GenerateEstimate {
  std::size_t start_points = 0;  ///< Points of the scene's grid (a refinement's starting grid).
  std::size_t max_points = 0;    ///< A refinement's point budget; start_points without one.
  int solves = 0;                ///< Solves measured.
  int failed = 0;                ///< Of those, not converged or errors.
  double mean_solve_s = 0.0;     ///< Mean wall time of a solve on one thread.
  double max_solve_s = 0.0;
};

/// Solves `runs` short runs of up to `run_length` points at grid places drawn with `seed`, one
/// thread, and times them. Throws InputError where the scene cannot be solved at all.
GenerateEstimate EstimateGeneration(const Scene& scene, int runs = 8, int run_length = 4,
                                    std::uint64_t seed = 1);

/// True when this build can split work across MPI ranks.
bool GeneratorSupportsMpi();

/// Throws InputError when a table's stored profile `name` ("rail" or "wheel") does not have
/// the SHA-256 the table records for it in `recorded` (empty: the table records none).
void CheckStoredProfileDigest(const std::string& table, const std::string& name,
                              std::string_view bytes, const std::string& recorded);

/// The version string stored in tables (`wrc_version`).
const char* GeneratorVersion();

/// Writes the fixed state the runtime's wheelset API reads (the wheelset_*, wheel_profile_offset
/// and fixed_* root attributes of the table schema) from the scene, into a table being written
/// (and into an older table `wrc upgrade` rewrites).
void WriteFixedStateAttributes(h5::File& file, const Scene& scene);

/// What `wrc info` shows about a table file.
struct TableInfo {
  struct Axis {
    std::string name, unit;
    std::vector<double> values;
  };
  struct Output {
    std::string name, unit;
    /// Range over the points whose status is ok (NaN when there are none).
    double min = std::numeric_limits<double>::quiet_NaN();
    double max = std::numeric_limits<double>::quiet_NaN();
  };
  struct Failure {
    std::uint64_t index = 0;           ///< Flat row-major point index.
    std::vector<std::size_t> indices;  ///< One per axis.
    std::string message;
  };
  std::string format;
  std::int64_t format_version = 0;
  /// Whether the file carries a seal, checked before HDF5 read it (false: written before seals).
  bool sealed = false;
  /// Solved points with warnings (root attribute warnings_count); -1 when the table predates it.
  std::int64_t warnings_count = -1;
  /// Root string attributes (wrc_version, created, scene, profile hashes, ...), by name.
  std::vector<std::pair<std::string, std::string>> attributes;
  /// Root float64 attributes (the fixed state: wheelset_velocity, fixed_y, ...), by name; none
  /// in tables written before them.
  std::vector<std::pair<std::string, double>> numbers;
  std::vector<Axis> axes;
  std::vector<Output> outputs;
  std::size_t points = 0;
  std::size_t status_counts[kPointStatusCount] = {0, 0, 0, 0};
  std::size_t other_status = 0;  ///< Status values outside 0..3 (a damaged file).
  double solve_time_total_s = 0.0, solve_time_max_s = 0.0;
  std::vector<Failure> failures;  ///< From /errors (an extension; empty in other writers' files).
  std::string rail_profile_name, wheel_profile_name;
  std::size_t rail_profile_bytes = 0, wheel_profile_bytes = 0;
};

/// TableInfo::format of a flat table (the `format` attribute inside is the HDF5 table's, kept as
/// exported).
inline constexpr const char* kFlatTableFormat = "wrc-flat-table";

/// Reads a table's layout, status counts and provenance, from an HDF5 or a flat table, with the
/// runtime's checks. Throws InputError when the file is not a readable wrc table.
TableInfo ReadTableInfo(const std::filesystem::path& path);

/// The bytes of the profile file `name` ("rail" or "wheel") stored in an HDF5 table, checked
/// against the digest the table records. Throws InputError when the table holds none, or other
/// bytes than it recorded.
std::string ReadStoredProfile(const std::filesystem::path& table, const std::string& name);

}  // namespace wrc
