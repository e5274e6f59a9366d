#pragma once
/// @file wheelrail.h
/// One wheel on one rail (docs/reference/case-files.md, `type = "wheel-rail"`): contact search,
/// contact patches with a planar or curved reference (paper §2.6 and §3), normal and tangential
/// solution per patch, and the total forces on the rail (docs/reference/json.md).

#include <Eigen/Dense>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "wrc/core/case.h"
#include "wrc/core/grid.h"
#include "wrc/core/normal_solver.h"
#include "wrc/core/tangential_solver.h"

namespace wrc {

/// What a caller solving many cases of one wheel–rail pair (a table's grid, a sweep) lets the
/// solver keep from one case to the next: the contact search of the last poses (successive
/// grid points often differ in load and creepage only, and the search depends on the pose
/// alone) and the placement check at the nominal pose (the same for every case of the pair).
/// Entries are matched on every input they depend on, so a result never depends on whether a
/// cache was passed or what it holds. One per thread: not safe for concurrent solves.
class WheelRailCache {
 public:
  WheelRailCache();
  ~WheelRailCache();
  WheelRailCache(const WheelRailCache&) = delete;
  WheelRailCache& operator=(const WheelRailCache&) = delete;
  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// Options of a wheel–rail solve.
struct WheelRailOptions {
  NormalOptions normal;
  TangentialOptions tangential;
  /// Prescribed vertical force met to this relative tolerance. Every output scales about
  /// linearly with the load, so 1e-6 leaves them within 1e-6 relative of the exact-load solution:
  /// two orders below CONTACT's printed 4 digits and four below the 1 % reference gate. (1e-7
  /// costs a third full solve, normal and tangential, in most Manchester cases.)
  double fz_tolerance = 1e-6;
  int max_fz_iterations = 100;
  /// Keep the grids and fields of each patch in the result (for `wrc solve --out`).
  bool keep_fields = false;
  /// Largest potential contact area of one patch, in elements: a guard against grids that
  /// cannot be solved in reasonable time (the tangential solver's cost grows with the square
  /// of the contact size). 200 000 elements is 40 × 40 mm at 0.1 mm.
  int max_patch_elements = 200000;
  /// Solve each patch on the bounding box of its interpenetration instead of the whole
  /// potential contact area: the same solution for identical bodies (contact needs h < 0),
  /// at a fraction of the cost. Off only to test exactly that.
  bool solve_box = true;
  /// With a prescribed fz: a wheelset height to start the iteration from (e.g. the solution of
  /// a neighbouring point of a sweep); NaN starts from first contact.
  double z_guess = std::numeric_limits<double>::quiet_NaN();
  /// Work kept between solves of related cases (may be null); see WheelRailCache.
  WheelRailCache* cache = nullptr;
};

/// One contact patch, in its contact reference frame (x along the track, s lateral along the
/// reference surface, n into the rail).
struct PatchResult {
  double fn = 0.0, fx = 0.0, fs = 0.0, mn = 0.0;  ///< Forces on the rail N, spin moment N·mm.
  double pmax = 0.0;                              ///< N/mm².
  int n_contact = 0, n_slip = 0, n_adhesion = 0, n_pot = 0;
  /// Extent of the elements in contact: columns (along x) and rows (along s) they span.
  int contact_columns = 0, contact_rows = 0;
  /// Pressure on an outermost row or column of the potential contact area: the patch may
  /// continue beyond its grid.
  bool contact_at_border = false;
  double contact_angle = 0.0;                                 ///< Reference angle δ, rad.
  Eigen::Vector3d reference_T = Eigen::Vector3d::Zero();      ///< Contact reference, track frame.
  Eigen::Vector2d reference_rail = Eigen::Vector2d::Zero();   ///< (y_r, z_r).
  Eigen::Vector3d reference_wheel = Eigen::Vector3d::Zero();  ///< (x_w, y_w, z_w).
  double rolling_radius = 0.0;  ///< Wheel radius at the reference, mm (nominal + z_w).
  double approach = 0.0;        ///< Largest interpenetration of the undeformed surfaces, mm.
  double cksi = 0.0, ceta = 0.0, cphi = 0.0;  ///< Creepages at the reference (planar).
  /// Tγ from the local fields, −∫ p·s dA (tractions on the rail, its relative slip), N: the
  /// frictional work per unit rolling distance; TGamma() is the same from the creepages and
  /// forces. FrictionalPower() turns it into W.
  double t_gamma_slip = 0.0;
  double contact_area = 0.0;  ///< Elements in contact times the element area, mm².
  /// SurfaceFatigueIndex for the rail's and the wheel's `shear_yield` (NaN where not given).
  double fi_surf_rail = std::numeric_limits<double>::quiet_NaN();
  double fi_surf_wheel = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d force_T = Eigen::Vector3d::Zero();   ///< Force on the rail, track frame.
  Eigen::Vector3d moment_T = Eigen::Vector3d::Zero();  ///< About the reference, track frame.
  SolverStatus status = SolverStatus::kConverged;
  int normal_iterations = 0, tangential_iterations = 0;

  // Fields, when WheelRailOptions::keep_fields: the grid in (x, s) relative to the reference,
  // per element undeformed distance, pressure, tractions, slip and state; for the curved
  // reference also the reference curve (y, z, angle per grid column, track frame).
  Grid grid;
  std::vector<double> h, pn, px, ps, sx, ss;
  std::vector<double> wx, ws;  ///< Relative rigid slip per element (tangential cases), -.
  std::vector<ElementState> state;
  std::vector<double> curve_y, curve_z, curve_angle;
};

/// Where the time of a solve went, s (summed over all patches and vertical force iterations).
struct WheelRailTimings {
  double profiles = 0.0;    ///< Reading, repairing and placing the profiles.
  double search = 0.0;      ///< Contact search along the rail.
  double geometry = 0.0;    ///< Patch references, grids, undeformed distance, rigid slip.
  double influence = 0.0;   ///< Influence coefficients and FFT plans.
  double normal = 0.0;      ///< Normal problems.
  double tangential = 0.0;  ///< Tangential problems.
  double total = 0.0;
};

/// Result of a wheel–rail solve (docs/reference/json.md).
struct WheelRailResult {
  SolverStatus status = SolverStatus::kConverged;
  std::string message;
  double y = 0.0, z = 0.0, roll = 0.0, yaw = 0.0, omega = 0.0;  ///< Wheelset state used.
  double velocity = 0.0;                               ///< Forward velocity V of the state, mm/s.
  Eigen::Vector3d force_T = Eigen::Vector3d::Zero();   ///< Total force on the rail, track frame.
  Eigen::Vector3d moment_T = Eigen::Vector3d::Zero();  ///< About the rail origin, track frame.
  Eigen::Vector3d rail_origin_T = Eigen::Vector3d::Zero();  ///< The rail profile's origin.
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();  ///< Total force on the rail, wheelset frame.
  std::vector<PatchResult> patches;                   ///< Field side first.
  int fz_iterations = 0;
  WheelRailTimings timings;
  /// Where the total force acts with the smallest moment (paper Eq. 25–27), moved along the
  /// force onto the rail surface; track frame. Valid when `has_force_location`.
  Eigen::Vector3d force_location_T = Eigen::Vector3d::Zero();
  bool has_force_location = false;
  double contact_y =
      0.0;  ///< Rail profile y of force_location_T, mm (docs/reference/table-layout.md).
  double contact_angle = 0.0;  ///< Rail inclination there, track frame, rad.
  /// Where the state is extreme but solved: what of the model's assumptions it strains (e.g. a
  /// patch too curved for the half-space influence coefficients). Empty for ordinary states.
  std::vector<std::string> warnings;
};

/// The frictional power of a patch per unit rolling distance, Tγ = −(ξ·fx + η·fs + φ·mn), N:
/// the creepages at the patch's reference times its forces and spin moment on the rail (the
/// minus because the rail's forces oppose the wheel's slip). The energy the patch dissipates
/// per mm rolled, in N·mm/mm, as the Tγ wear models (Archard-type wear numbers, the RCF damage
/// function) use it. 0 for a frictionless (normal only) solve.
double TGamma(const PatchResult& patch);
/// Tγ summed over the patches of a solve, N.
double TGamma(const WheelRailResult& result);
/// The patches' t_gamma_slip summed, N.
double TGammaSlip(const WheelRailResult& result);
/// Ekberg's surface-fatigue index of a patch for a body of yield limit in pure shear k (N/mm²):
/// FI_surf = f − k/p0, with f = √(fx² + fs²)/fn the traction coefficient and p0 the peak
/// pressure, here the solved one (pmax). For a Hertzian patch that is Ekberg's
/// f − 2πabk/(3Fz); on the non-elliptic patches of conformal and flange contact the peak the
/// surface carries is the solved one (a Hertzian patch of the same load and area would put it
/// 1–43 % lower on the Manchester and heavy-haul reference cases). Above 0 the load lies beyond
/// the surface's shakedown limit: surface-initiated rolling contact fatigue is to be expected.
/// A. Ekberg, E. Kabo, H. Andersson, An engineering model for prediction of rolling contact
/// fatigue of railway wheels, Fatigue Fract. Engng Mater. Struct. 25 (2002) 899–909. NaN
/// without contact or k.
double SurfaceFatigueIndex(const PatchResult& patch, double shear_yield);
/// The frictional power of a patch, W: ∫ p·ṡ dA with the tractions on the rail and its slip
/// velocity relative to the wheel, ṡ = V·s (`velocity` V in mm/s), from the local fields;
/// negative when it dissipates, as CONTACT prints FRIC.POWER. Equal to −V·t_gamma_slip.
double FrictionalPower(const PatchResult& patch, double velocity);
/// FrictionalPower summed over the patches of a solve at its velocity, W.
double FrictionalPower(const WheelRailResult& result);

/// The value of the table output `name` (kOutputQuantities of wrc/quantities.h) for a solve that
/// converged or found no contact; without contact, what the registry says (0, NaN, or the
/// solver's z or fz). Throws std::logic_error for a name that is not an output, or an output
/// without its line here: adding an output is its registry entry and its line in OutputValue.
double OutputValue(std::string_view name, const WheelRailResult& result);

/// Solves a `type = "wheel-rail"` case: reads the profiles, places them, finds the contact
/// patches and solves them; with `state.fz` it finds the wheelset height z that gives that
/// vertical force on the rail. Throws InputError for bad input (unreadable profiles, a pose
/// that puts the wheel outside the rail profile, a patch too large to solve, an fz that no
/// solvable height carries); no contact is a status, not an error. The depth of the
/// interpenetration is not bounded: deep flange contact is solved, with `warnings` where the
/// contact reaches an end of a profile or strains the half-space model.
WheelRailResult SolveWheelRail(const Case& c, const WheelRailOptions& options = {});

}  // namespace wrc
