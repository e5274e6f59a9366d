#pragma once
/// @file bogie.h
/// A bogie of a vehicle on straight track: the frame (lateral and yaw) on two wheelsets
/// (lateral and yaw each), held by the primary suspension, and carried by the secondary
/// suspension from a car body that moves at constant speed V without lateral or yaw motion.
/// The car body's own modes (a few tenths of a hertz to about 1 Hz) lie far below hunting and
/// barely couple into it; a body that does not move is the usual reduction for bogie hunting.
///
/// The wheelsets' vertical position and roll follow the lateral motion quasi-statically and
/// their loads are constant, as in the single-wheelset model (model.h), whose ContactLoads and
/// ForceSource each wheelset uses at its own state.
///
/// Generalised coordinates q = (y1, ψ1, y2, ψ2, y_f, ψ_f): leading wheelset at x = +a, trailing
/// at x = −a, frame; the state is x = (q, q̇), 12 entries. Units as in model.h: mm, rad, s, N,
/// N·mm, with masses in kg and inertias in kg·m² as published.

#include <Eigen/Dense>
#include <complex>
#include <filesystem>
#include <string>
#include <vector>

#include "studies/dynamics/model.h"

namespace wrc::dynamics {

/// The steady curves of the quasi-static curving study ([curving]): each radius at one cant and
/// one cant deficiency, which set the speed.
struct CurvingSettings {
  std::vector<double> radii;     ///< mm; empty: no curving study.
  double cant = 0.0;             ///< mm, the outer rail's height over the inner one.
  double cant_deficiency = 0.0;  ///< mm, the further cant that would balance the speed.
  double rail_spacing = 1500.0;  ///< mm, between the rails' centres: cant / spacing is its angle.
};

/// The vehicle: its bogie and the share of the body a bogie carries (tables/
/// manchester_vehicle.toml cites every value).
struct BogieParameters {
  double wheelset_mass = 0.0;                     ///< kg.
  double wheelset_yaw_inertia = 0.0;              ///< kg·m².
  double frame_mass = 0.0;                        ///< kg.
  double frame_yaw_inertia = 0.0;                 ///< kg·m².
  double body_mass = 0.0;                         ///< kg, carried by two bogies.
  double semi_wheelbase = 0.0;                    ///< mm, a.
  double primary_lateral_stiffness = 0.0;         ///< N/mm per axlebox (four per bogie).
  double primary_longitudinal_stiffness = 0.0;    ///< N/mm per axlebox.
  double primary_lateral_damping = 0.0;           ///< N·s/mm per axlebox.
  double primary_longitudinal_damping = 0.0;      ///< N·s/mm per axlebox.
  double primary_semi_spacing = 0.0;              ///< mm, axleboxes from the wheelset centre.
  double secondary_lateral_stiffness = 0.0;       ///< N/mm per side (two per bogie).
  double secondary_longitudinal_stiffness = 0.0;  ///< N/mm per side.
  double secondary_lateral_damping = 0.0;         ///< N·s/mm per side.
  double secondary_yaw_damping = 0.0;             ///< N·s/mm per side, longitudinal (yaw) damper.
  double secondary_semi_spacing = 0.0;            ///< mm, springs and yaw dampers from the centre.
  double bogie_semi_spacing = 0.0;                ///< mm, bogie centres from the body's centre.
  double initial_y = 0.0;                         ///< mm, leading wheelset's disturbance at t = 0.
  double time_step = 1e-3;                        ///< s.
  double duration = 3.0;                          ///< s.
  CurvingSettings curving;

  /// N on each wheel: half the body, the frame and both wheelsets over four wheels, g = 9.81.
  double WheelLoad() const;
};

/// Reads a vehicle file ([wheelset], [frame], [body], [primary], [secondary], [simulation]).
/// Throws InputError naming the file, line and key for a missing, misspelt or negative value.
BogieParameters ParseBogieParameters(const std::string& toml_text, const std::string& name);
BogieParameters LoadBogieParameters(const std::filesystem::path& path);

using BogieVector = Eigen::Matrix<double, 12, 1>;
using BogieMatrix = Eigen::Matrix<double, 12, 12>;

/// The state of wheelset k (0 leading, 1 trailing) within a bogie state.
State WheelsetOf(const BogieVector& x, int k);

/// The track under the bogie: straight (the default) or a steady curve, and where the car body
/// stands over the bogie centre. Each body's y and ψ are taken from the track's centre line and
/// tangent at its own centre, so a bogie running radially has every coordinate zero.
struct BogieTrack {
  /// 1/mm, 1/R. The curve's centre lies on the −y side: the rail at +y is the outer one.
  double curvature = 0.0;
  /// mm/s², towards +y in the track plane: V²/R less the cant's share of gravity.
  double unbalanced_acceleration = 0.0;
  double body_y = 0.0;    ///< mm, the car body's lateral position over the bogie centre.
  double body_yaw = 0.0;  ///< rad, the car body's yaw relative to the track there.
};

/// Time derivative of the bogie state, given the contact loads on each wheelset.
BogieVector BogieDerivative(const BogieParameters& p, const BogieVector& x,
                            const ContactLoads (&loads)[2], const BogieTrack& track = {});

/// The contact linearised about centred running: the derivatives ∂(F_y, M_z)/∂(y, ψ, vy, vyaw)
/// at the speed `speed` (mm/s), as LinearisedLoads gives them. Creepages depend on the velocities
/// only through vy/V and vyaw/V, so the velocity columns scale with 1/V at other speeds.
struct LinearisedContact {
  Eigen::Matrix<double, 2, 4> jacobian = Eigen::Matrix<double, 2, 4>::Zero();
  double speed = 1.0;
  ContactLoads operator()(const State& s, double velocity) const;
};

/// The system matrix A of ẋ = A x with the linearised contact on both wheelsets, at V (mm/s).
BogieMatrix BogieLinearSystem(const BogieParameters& p, const LinearisedContact& contact,
                              double velocity);

/// The eigenvalue of A with the largest real part (1/s; its imaginary part/2π is the frequency).
std::complex<double> DominantEigenvalue(const BogieMatrix& a);

/// The frequency of an eigenvalue's oscillation, |Im λ| / 2π, Hz.
double FrequencyOf(std::complex<double> eigenvalue);

/// The lowest speed in [v_low, v_high] (mm/s) where the dominant eigenvalue's real part crosses
/// zero, bisected to 1e-6 of v_high after a scan in 1 % steps (the largest real part need not
/// be monotonic in V); NaN when it stays negative throughout.
double BogieCriticalSpeed(const BogieParameters& p, const LinearisedContact& contact, double v_low,
                          double v_high);

/// A simulated bogie run: samples of the leading wheelset's lateral position and yaw.
struct BogieTrajectory {
  std::vector<double> t;
  std::vector<double> y, yaw;  ///< Leading wheelset.
  std::vector<double> frame_y;
  int flags = 0;
  double seconds = 0.0, cpu_seconds = 0.0;
  int steps = 0;
  /// As a single-wheelset Trajectory of the leading wheelset, for MeasureHunting.
  Trajectory Leading() const;
};

/// Integrates from the leading wheelset's disturbance with the classical fourth-order Runge–
/// Kutta method at the parameters' step: `forces[k]` serves wheelset k (each its own, so that a
/// solver source warm-starts from its own wheelset's previous solve).
BogieTrajectory SimulateBogie(const BogieParameters& p, const ForceSource (&forces)[2],
                              double velocity);

}  // namespace wrc::dynamics
