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

// The patch carrying the largest normal force (the first of equals: deterministic).
const PatchResult* MainPatch(const WheelRailResult& result) {
  const PatchResult* main = nullptr;
  for (const PatchResult& patch : result.patches) {
    if (main == nullptr || patch.fn > main->fn) main = &patch;
  }
  return main;
}

double OutputValue(const std::string& name, const WheelRailResult& r) {
  if (name == "fx") return r.force_T(0);
  if (name == "fy") return r.force_T(1);
  if (name == "fz") return r.force_T(2);
  if (name == "mx") return r.moment_T(0);
  if (name == "my") return r.moment_T(1);
  if (name == "mz") return r.moment_T(2);
  if (name == "fx_ws") return r.force_W(0);
  if (name == "fy_ws") return r.force_W(1);
  if (name == "fz_ws") return r.force_W(2);
  if (name == "n_patches") return static_cast<double>(r.patches.size());
  if (name == "z") return r.z;
  if (name == "t_gamma") return TGamma(r);
  if (name == "t_gamma_slip") return TGammaSlip(r);
  if (name == "fi_surf_rail" || name == "fi_surf_wheel") {
    // The patch nearest to (or furthest beyond) the surface's shakedown limit.
    double worst = kNaN;
    for (const PatchResult& patch : r.patches) {
      const double fi = name == "fi_surf_rail" ? patch.fi_surf_rail : patch.fi_surf_wheel;
      if (!std::isnan(fi)) worst = std::isnan(worst) ? fi : std::max(worst, fi);
    }
    return worst;
  }
  if (name == "frictional_power") return FrictionalPower(r);
  if (name == "pmax") {
    double pmax = 0.0;
    for (const PatchResult& patch : r.patches) pmax = std::max(pmax, patch.pmax);
    return pmax;
  }
  if (name == "contact_y" || name == "contact_angle") {
    const bool want_y = name == "contact_y";
    if (r.has_force_location) return want_y ? r.contact_y : r.contact_angle;
    // The resultant's line of action missed the rail profile (rare: nearly horizontal force);
    // the main patch's reference is the closest stand-in and keeps the table finite.
    const PatchResult* main = MainPatch(r);
    if (main == nullptr) return kNaN;
    return want_y ? main->reference_rail(0) : main->contact_angle;
  }
  return kNaN;  // unreachable: the scene parser admits only the names above
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
    const std::string& name = scene.outputs[k];
    if (status == PointStatus::kNoContact) {
      // No contact, no force; a contact location, and a patch to judge for fatigue, do not
      // exist. z (prescribed fz) or fz (prescribed z) are what the solver reports.
      const bool location = name == "contact_y" || name == "contact_angle" ||
                            name == "fi_surf_rail" || name == "fi_surf_wheel";
      values[k] = location ? kNaN : (name == "z" || name == "fz" ? OutputValue(name, result) : 0.0);
    } else {
      values[k] = OutputValue(name, result);
    }
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
