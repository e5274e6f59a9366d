#pragma once
/// @file forces.h
/// Force sources of the wheelset model: a table through the runtime's wheelset API, full
/// solves of both wheels, and a linear creep-force model with a known solution.
///
/// Both contact sources see the same state (model.h) and return the resultant on the wheelset
/// about its centre. The solver is given the velocities as they are (vy, vyaw). A table without
/// vy and vyaw axes (tables/mbench.toml has yaw and spin instead) is read at the pose with the
/// same creepages: the lateral creepage of a wheel is vy/V − ψ, so vy enters as the yaw angle
/// ψ − vy/V; the yaw rate adds ±b·vyaw/V to the longitudinal creepage of the wheel at ±b, which
/// a change of the wheel's spin (its rotation relative to free rolling) gives alike. The spin
/// then differs between the wheels, so each wheel is read from its own wheelset state.

#include <Eigen/Dense>
#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "studies/dynamics/model.h"
#include "wrc/core/case.h"
#include "wrc/runtime.hpp"

namespace wrc::dynamics {

/// The roll angle at which both wheels carry the wheel load at the same wheelset height, as a
/// function of the lateral position: tabulated on a y grid, linear in between, odd in y.
class RollCurve {
 public:
  RollCurve() = default;
  /// `height(side, y, roll)` gives the wheelset height (z, mm) at which the wheel on `side`
  /// (WRC_LEFT / WRC_RIGHT) carries the load. Roots are sought in [roll_min, roll_max]; where
  /// none lies there the end nearest to one is taken and counted in clamped().
  RollCurve(const std::function<double(int, double, double)>& height, double y_max, double dy,
            double roll_min, double roll_max);
  double operator()(double y) const;
  /// The wheelset position y at which each wheel's lateral position on its rail, y − r0·roll(y),
  /// is `wheel_y` (mm): the roll adds about 2 % to a step in y on the Manchester pair.
  double WheelsetY(double wheel_y, double nominal_radius) const;
  int clamped() const { return clamped_; }
  const std::vector<double>& y() const { return y_; }
  const std::vector<double>& roll() const { return roll_; }

 private:
  std::vector<double> y_, roll_;  // y >= 0
  int clamped_ = 0;
};

/// The y spacing of both sources' roll curves, mm: the same for both, so that the linearised
/// contact sees the same roll in each; a coarser solver curve put ∂Fy/∂y at centred running 8 %
/// apart on the Manchester vehicle's table.
constexpr double kRollCurveStep = 0.25;

/// Per-wheel contact results assembled into the resultant about the wheelset centre at
/// lateral position y, and each wheel's Y, Q and Tγ. force/moment: on the rail, moments about
/// the rail origin o = (o_y, o_z); a rail's field side is the side of its origin.
ContactLoads AssembleLoads(const double (&force)[2][3], const double (&moment)[2][3],
                           const double (&t_gamma)[2], const double (&origin)[2][2], double y);

/// Geometry both contact sources need.
struct ContactGeometry {
  double wheel_load = 0.0;      ///< N per rail.
  double nominal_radius = 460;  ///< mm, r0.
  double semi_spacing = 750;    ///< mm, b: nominal rolling circles from the centre.
  double origin[2][2] = {};     ///< Rail origins (o_y, o_z) per side, as the solver places them.
};

/// The table source: wrc::WheelsetTable over one table (both wheels; the other side mirrored).
class TableForces {
 public:
  /// Builds the roll curve from the table's z output. Throws InputError when the table cannot
  /// serve the model (no fz axis or fixed load other than the wheel load, no z output).
  /// The roll curve spans |y| <= y_max (mm), every kRollCurveStep.
  TableForces(const wrc::Table& table, const ContactGeometry& geometry, double y_max = 10.0);
  ContactLoads operator()(const State& s, double velocity) const;
  const RollCurve& roll_curve() const { return roll_; }
  /// The wheelset height of one wheel at its load (the roll curve's input).
  double Height(int side, double y, double roll) const;

 private:
  const wrc::Table& table_;
  wrc::WheelsetTable wheelset_;
  ContactGeometry geometry_;
  RollCurve roll_;
};

/// The solver source: both wheels solved with the table's scene at every evaluation, the
/// wheelset height of each warm-started from its previous solve.
class SolverForces {
 public:
  /// The roll curve spans |y| <= y_max (mm), every kRollCurveStep.
  SolverForces(Case base, const ContactGeometry& geometry, double y_max = 10.0);
  ContactLoads operator()(const State& s, double velocity);
  const RollCurve& roll_curve() const { return roll_; }
  double Height(int side, double y, double roll);
  long solves() const { return solves_; }

 private:
  Case Wheel(int side, const State& s, double roll, double velocity) const;
  Case base_;
  ContactGeometry geometry_;
  RollCurve roll_;
  double z_guess_[2] = {NAN, NAN};
  long solves_ = 0;
};

/// The rail origins the solver places for a scene (right from a solve, left mirrored).
ContactGeometry SceneGeometry(const Case& base, double wheel_load);

/// The derivatives ∂(F_y, M_z)/∂(y, ψ, vy, vyaw) of a force source at a state: the linearised
/// coupling of wheelset and track that decides the hunting frequency and the critical speed, to
/// compare sources term by term. Coordinate j is sampled at n_j evenly spaced offsets on each
/// side, out to ±h_j (same order), and its derivative is the least-squares slope through them;
/// n_j = 1 is the central difference with step h_j.
Eigen::Matrix<double, 2, 4> LinearisedLoads(const ForceSource& source, const State& at,
                                            double velocity, const Eigen::Vector4d& h,
                                            const Eigen::Vector4i& n = Eigen::Vector4i::Ones());

/// Linear contact: creep forces −f·creepage with Kalker-type coefficients f11 (longitudinal)
/// and f22 (lateral) per wheel, conicity λ, and a gravitational stiffness k_g (N/mm).
struct LinearContact {
  double f11 = 0.0, f22 = 0.0;  ///< N.
  double conicity = 0.0;
  double semi_spacing = 750.0;    ///< mm.
  double nominal_radius = 460.0;  ///< mm.
  double gravity_stiffness = 0.0;
  ContactLoads operator()(const State& s, double velocity) const;
};

/// The system matrix A of ẋ = A x, x = (y, ψ, vy, vyaw), of the model with linear contact.
Eigen::Matrix4d LinearSystem(const Parameters& p, const LinearContact& c, double velocity);

/// The linear critical speed: where the largest real part of A's eigenvalues crosses zero,
/// bisected in [v_low, v_high] (mm/s); NaN when it does not change sign there.
double LinearCriticalSpeed(const Parameters& p, const LinearContact& c, double v_low,
                           double v_high);

}  // namespace wrc::dynamics
