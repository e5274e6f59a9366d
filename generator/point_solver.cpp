// One grid point: solve, classify, pick the scene's outputs.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <limits>
#include <new>
#include <stdexcept>
#include <utility>

#include "wrc/core/errors.h"
#include "wrc/generator/generator.h"

namespace wrc {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

PointStatus StatusOf(SolverStatus status) {
  switch (status) {
    case SolverStatus::kConverged:
      return PointStatus::kOk;
    case SolverStatus::kNoContact:
      return PointStatus::kNoContact;
    case SolverStatus::kNotConverged:
      return PointStatus::kNotConverged;
  }
  return PointStatus::kError;
}

}  // namespace

const char* ToString(PointStatus status) {
  switch (status) {
    case PointStatus::kOk:
      return "ok";
    case PointStatus::kNoContact:
      return "no_contact";
    case PointStatus::kNotConverged:
      return "not_converged";
    case PointStatus::kError:
      return "error";
  }
  return "error";
}

std::vector<double> SceneOutputValues(const Scene& scene, const WheelRailResult& result,
                                      PointStatus status) {
  std::vector<double> values(scene.outputs.size(), kNaN);
  if (status == PointStatus::kNotConverged || status == PointStatus::kError) return values;
  for (std::size_t k = 0; k < scene.outputs.size(); ++k) {
    values[k] = OutputValue(scene.outputs[k], result);
  }
  return values;
}

namespace {

std::string JoinWarnings(const std::vector<std::string>& warnings) {
  std::string text;
  for (const std::string& w : warnings) text += (text.empty() ? "" : "; ") + w;
  return text;
}

// One solve of the point from the given start (NaN: the solver's own cold start).
PointResult SolveOnce(const Scene& scene, const std::vector<std::size_t>& indices, double z_guess,
                      WheelRailCache* cache) {
  PointResult point;
  try {
    Case c = CaseAtIndex(scene, indices);
    // Messages name the scene by its file name only, so that they (and so the table) do not
    // depend on the directory a run or a resumed run was started from.
    c.source_name = std::filesystem::path(c.source_name).filename().string();
    WheelRailOptions options;
    options.z_guess = z_guess;
    options.cache = cache;
    const WheelRailResult result = SolveWheelRail(c, options);
    point.status = StatusOf(result.status);
    point.values = SceneOutputValues(scene, result, point.status);
    if (point.status == PointStatus::kOk) point.z = result.z;
    if (point.status == PointStatus::kNotConverged) {
      point.message =
          result.message.empty() ? "the solver reached its iteration limit" : result.message;
    } else {
      point.message = JoinWarnings(result.warnings);  // the doubts about a solved point
    }
  } catch (...) {
    point.status = PointStatus::kError;
    point.values.assign(scene.outputs.size(), kNaN);
    point.message = PointFailureMessage(std::current_exception());
  }
  return point;
}

bool Failed(const PointResult& point) {
  return point.status == PointStatus::kError || point.status == PointStatus::kNotConverged;
}

}  // namespace

std::string PointFailureMessage(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const ResourceError&) {
    throw;  // an InputError too, but no property of the point
  } catch (const InputError& e) {
    return e.what();
  } catch (const NumericalError& e) {
    return e.what();
  } catch (const std::bad_alloc&) {
    // Not a property of the point: stored as a failed point it would stay in the table after
    // memory was back. The run stops instead; its journal keeps the points solved so far.
    throw ResourceError(
        "out of memory while solving a point; the points solved so far are kept: resume with "
        "fewer --threads or more memory");
  }
  // Anything else (std::logic_error above all) is a bug in wrc: it propagates and stops the run
  // with its message rather than become a table entry.
}

PointResult SolveScenePoint(const Scene& scene, const std::vector<std::size_t>& indices,
                            double z_guess, WheelRailCache* cache) {
  const auto start = std::chrono::steady_clock::now();
  PointResult point = SolveOnce(scene, indices, z_guess, cache);
  // A warm start from the neighbouring point can lead the vertical force iteration astray
  // where the contact changes between the two (a patch appearing at the flange): such a point
  // is solved once more from the solver's own cold start, and then stored exactly as a cold
  // solve. Bad input fails the same way again and keeps its reason (once); a different reason
  // from the warm start is kept after it.
  if (Failed(point) && std::isfinite(z_guess)) {
    PointResult cold = SolveOnce(scene, indices, kNaN, cache);
    if (Failed(cold) && cold.message != point.message) {
      cold.message +=
          " (from the warm start z = " + FormatNumber(z_guess) + " mm: " + point.message + ")";
    }
    point = std::move(cold);
  }
  point.solve_time_s =
      std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count();
  return point;
}

}  // namespace wrc
