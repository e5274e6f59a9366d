// What a solve gives as table outputs (wrc/quantities.h) and as the wear and fatigue
// quantities of its patches.

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "wrc/core/wheelrail.h"
#include "wrc/quantities.h"

namespace wrc {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The patch carrying the largest normal force (the first of equals: deterministic).
const PatchResult* MainPatch(const WheelRailResult& result) {
  const PatchResult* main = nullptr;
  for (const PatchResult& patch : result.patches) {
    if (main == nullptr || patch.fn > main->fn) main = &patch;
  }
  return main;
}

double LargestPmax(const WheelRailResult& r) {
  double pmax = 0.0;
  for (const PatchResult& patch : r.patches) pmax = std::max(pmax, patch.pmax);
  return pmax;
}

// The patch nearest to (or furthest beyond) the surface's shakedown limit.
double WorstFatigueIndex(const WheelRailResult& r, bool rail) {
  double worst = kNaN;
  for (const PatchResult& patch : r.patches) {
    const double fi = rail ? patch.fi_surf_rail : patch.fi_surf_wheel;
    if (!std::isnan(fi)) worst = std::isnan(worst) ? fi : std::max(worst, fi);
  }
  return worst;
}

double ContactLocation(const WheelRailResult& r, bool want_y) {
  if (r.has_force_location) return want_y ? r.contact_y : r.contact_angle;
  // The resultant's line of action missed the rail profile (rare: nearly horizontal force);
  // the main patch's reference is the closest stand-in and keeps the table finite.
  const PatchResult* main = MainPatch(r);
  if (main == nullptr) return kNaN;
  return want_y ? main->reference_rail(0) : main->contact_angle;
}

// Where the patch carrying the largest normal force lies on the wheel: its rolling radius, or
// its lateral position on the wheel profile (the wheel's side of the contact-point functions).
double MainPatchOnWheel(const WheelRailResult& r, bool radius) {
  const PatchResult* main = MainPatch(r);
  if (main == nullptr) return kNaN;
  return radius ? main->rolling_radius : main->reference_wheel(1);
}

// The output of a solve in contact. Every name of kOutputQuantities has its line here.
double SolvedValue(std::string_view name, const WheelRailResult& r) {
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
  if (name == "contact_y") return ContactLocation(r, true);
  if (name == "contact_angle") return ContactLocation(r, false);
  if (name == "pmax") return LargestPmax(r);
  if (name == "z") return r.z;
  if (name == "t_gamma") return TGamma(r);
  if (name == "frictional_power") return FrictionalPower(r);
  if (name == "t_gamma_slip") return TGammaSlip(r);
  if (name == "fi_surf_rail") return WorstFatigueIndex(r, true);
  if (name == "fi_surf_wheel") return WorstFatigueIndex(r, false);
  if (name == "rolling_radius") return MainPatchOnWheel(r, true);
  if (name == "wheel_contact_y") return MainPatchOnWheel(r, false);
  throw std::logic_error("OutputValue: no value for the output '" + std::string(name) + "'");
}

}  // namespace

double OutputValue(std::string_view name, const WheelRailResult& result) {
  const OutputQuantity* quantity = FindOutputQuantity(name);
  if (quantity == nullptr) {
    throw std::logic_error("OutputValue: '" + std::string(name) + "' is not a table output");
  }
  if (result.status != SolverStatus::kNoContact) return SolvedValue(name, result);
  switch (quantity->at_no_contact) {
    case AtNoContact::kZero:
      return 0.0;
    case AtNoContact::kUndefined:
      return kNaN;
    case AtNoContact::kSolved:
      return SolvedValue(name, result);
  }
  return kNaN;
}

double TGamma(const PatchResult& patch) {
  return -(patch.cksi * patch.fx + patch.ceta * patch.fs + patch.cphi * patch.mn);
}

double SurfaceFatigueIndex(const PatchResult& patch, double shear_yield) {
  if (!(patch.fn > 0.0) || !(patch.pmax > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  const double traction = std::hypot(patch.fx, patch.fs) / patch.fn;
  return traction - shear_yield / patch.pmax;  // NaN when k is NaN
}

double FrictionalPower(const PatchResult& patch, double velocity) {
  return -1e-3 * velocity * patch.t_gamma_slip;  // N·mm/s to W
}

double FrictionalPower(const WheelRailResult& result) {
  double sum = 0.0;
  for (const PatchResult& patch : result.patches) sum += FrictionalPower(patch, result.velocity);
  return sum;
}

double TGammaSlip(const WheelRailResult& result) {
  double sum = 0.0;
  for (const PatchResult& patch : result.patches) sum += patch.t_gamma_slip;
  return sum;
}

double TGamma(const WheelRailResult& result) {
  double sum = 0.0;
  for (const PatchResult& patch : result.patches) sum += TGamma(patch);
  return sum;
}

}  // namespace wrc
