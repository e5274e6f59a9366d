#pragma once
// The verification behind `wrc verify` and `wrc study tables`: sampled points of a table
// re-solved exactly with the scene stored in it, compared with both interpolation modes.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "wrc/core/scene.h"

namespace wrc::cli {

struct VerifyOptions {
  std::string table;
  int samples = 200;
  std::uint64_t seed = 1;
  std::string sampler = "uniform";
  bool near_jumps = false;
  int threads = 0;
};

/// The scene of a table with its profiles restored from /profiles into a scratch directory
/// (removed with the object), so that a table verifies wherever it is moved.
struct StoredScene {
  Scene scene;
  std::filesystem::path scratch;
  ~StoredScene();
};
std::unique_ptr<StoredScene> LoadStoredScene(const std::filesystem::path& table);

/// One sampled point: where, what the solver gives, what the table gives.
struct VerifiedPoint {
  std::vector<double> point;
  int status = 3;  ///< Of the exact solve: 0 ok, 1 no contact, 2 not converged, 3 error.
  std::vector<double> exact, linear, cubic;
  /// The wheel load there (prescribed fz, or the solved fz where z is prescribed); NaN when
  /// the table cannot tell.
  double load = 0.0;
  /// -1 unknown (no n_patches output), 0 every corner of the cell has the same patch count,
  /// 1 it changes within the cell.
  int patch_change = -1;
};

struct Verification {
  nlohmann::json report;  ///< The JSON of `wrc verify --json`.
  std::vector<VerifiedPoint> points;
  std::vector<std::string> axis_names, output_names;
};

/// Solves the samples on all threads and compares. Throws InputError / TableError for a table
/// that cannot be read.
Verification VerifyTable(const VerifyOptions& options);

/// Exact solves of the scene at the given points (all threads); each result holds the scene's
/// outputs in order, status as in VerifiedPoint, and for a solve that threw, its message.
/// Throws Interrupted when SIGINT or SIGTERM arrives: the solves in flight finish, no new
/// one starts.
void SolveExactly(const Scene& scene, const std::vector<std::vector<double>>& points, int threads,
                  std::vector<std::vector<double>>* values, std::vector<int>* status,
                  std::vector<double>* seconds, std::vector<std::string>* messages);

}  // namespace wrc::cli
