#pragma once
/// @file curving.h
/// Quasi-static curving: the bogie of bogie.h in a steady curve, where every body runs at
/// constant speed along the track and the lateral and yaw positions balance the creep and
/// flange forces against the suspension and the unbalanced lateral acceleration.
///
/// The curve enters the contact as the wheelsets' yaw rate −V/R (each turns with the track):
/// on a straight rail that is the curve's difference in rolling distance between the wheels,
/// ±b/R of longitudinal creepage, and its share of spin. The car body stands over the bogie as
/// in a steady curve: its lateral position such that the secondary springs carry its share of
/// the unbalanced force, its yaw the chord between the bogie centres. The wheel loads are the
/// static ones (the model has no roll), so Q differs from the load only by what the solver's
/// patches share differently.

#include <Eigen/Dense>

#include "studies/dynamics/bogie.h"

namespace wrc::dynamics {

/// A steady curve and the speed through it.
struct CurveCase {
  double radius = 0.0;           ///< mm, > 0; the rail at +y is the outer one.
  double cant = 0.0;             ///< mm.
  double speed = 0.0;            ///< mm/s.
  double rail_spacing = 1500.0;  ///< mm.

  /// The speed of a cant deficiency (mm) at this radius and cant: V²/R = g (cant + deficiency)/s.
  static CurveCase WithDeficiency(double radius, const CurvingSettings& settings);
  /// V²/R − g·cant/s, mm/s² (the small-angle form, as cant deficiency is defined).
  double UnbalancedAcceleration() const;
};

/// The equilibrium of one force source in one curve.
struct CurvingResult {
  /// (y1, ψ1, y2, ψ2, y_f, ψ_f), mm and rad, each from its own centre's track line.
  Eigen::Matrix<double, 6, 1> position = Eigen::Matrix<double, 6, 1>::Zero();
  ContactLoads loads[2];  ///< Leading, trailing wheelset, with each wheel's Y, Q and Tγ.
  double body_y = 0.0;    ///< mm, the car body's lateral position over the bogie centre.
  /// Largest force residual (N) and moment residual over the wheelbase (N) at the result.
  double residual = 0.0;
  bool converged = false;
  int evaluations = 0;  ///< Of the bogie's contact (both wheelsets) and its Jacobian.
  double seconds = 0.0;
};

/// The residual below which an equilibrium counts as found, N (moments over the semi-wheelbase):
/// 1 N is 2·10⁻⁵ of the Manchester vehicle's wheel load, far below the 1 % compared.
constexpr double kCurvingResidual = 1.0;

/// Solves for the equilibrium by Powell's hybrid method (Eigen's HybridNonLinearSolver, a
/// trust region that stays stable where flange contact makes the forces steep) from centred
/// running, with the contact's Jacobian by central differences of `forces[k]` per wheelset and
/// the suspension's exactly; where that stops short of the residual, by continuation from
/// straight track in steps of curvature (the equilibrium at the flange of a low-conicity pair
/// lies behind a jump of the contact from the tread). Not converged is a status, not an error.
CurvingResult SolveCurving(const BogieParameters& p, const CurveCase& curve,
                           const ForceSource (&forces)[2]);

}  // namespace wrc::dynamics
