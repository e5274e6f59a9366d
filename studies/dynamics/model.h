#pragma once
/// @file model.h
/// A single wheelset running on straight track, held by primary springs and dampers to a frame
/// that moves at constant speed V along the track: the smallest model with a hunting
/// instability, to compare force sources (tables against full solves) in the time domain.
///
/// Degrees of freedom: the lateral displacement y and the yaw angle ψ of the wheelset, each
/// with its velocity. Vertical position and roll are not integrated: the wheel loads are
/// constant (half the axle load on each rail, the frame carries the rest) and the roll follows
/// the lateral position quasi-statically (the roll at which both wheels carry their load at the
/// same wheelset height). The vertical and roll modes of a wheelset on its primary suspension
/// lie far above the hunting frequency (tens of Hz against a few), so they follow the lateral
/// motion without lag; and a table with a prescribed-load axis is made for exactly this.
///
/// Units: mm, rad, s, N, N·mm inside the model; kg and kg·m² for the inertias as published.

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace wrc::dynamics {

/// The wheelset and its suspension (see tables/wheelset_dynamics.toml for the sources).
struct Parameters {
  double mass = 0.0;                    ///< kg.
  double yaw_inertia = 0.0;             ///< kg·m².
  double lateral_stiffness = 0.0;       ///< N/mm per axlebox (two axleboxes).
  double lateral_damping = 0.0;         ///< N·s/mm per axlebox.
  double longitudinal_stiffness = 0.0;  ///< N/mm per axlebox.
  double longitudinal_damping = 0.0;    ///< N·s/mm per axlebox.
  double spring_semi_spacing = 0.0;     ///< mm, lateral distance of the axleboxes from the centre.
  double wheel_load = 0.0;              ///< N, vertical force on each rail.
  double initial_y = 0.0;               ///< mm, the disturbance at t = 0 (ψ, velocities 0).
  double time_step = 1e-3;              ///< s.
  double duration = 2.0;                ///< s.

  /// Yaw stiffness and damping of the suspension about the wheelset centre, N·mm/rad, N·mm·s/rad.
  double YawStiffness() const;
  double YawDamping() const;
};

/// Reads the [wheelset], [suspension] and [simulation] sections of a parameter file. Throws
/// InputError naming the file, line and key for a missing, misspelt or out-of-range value.
Parameters LoadParameters(const std::filesystem::path& path);
Parameters ParseParameters(const std::string& toml_text, const std::string& display_name);

/// The integrated state.
struct State {
  double y = 0.0;     ///< mm.
  double yaw = 0.0;   ///< rad.
  double vy = 0.0;    ///< mm/s.
  double vyaw = 0.0;  ///< rad/s.
};

/// One wheel's contact as the track sees it, the quantities of curving and wear assessment.
struct WheelContact {
  double lateral = 0.0;   ///< N, Y: on the rail, positive towards its field side.
  double vertical = 0.0;  ///< N, Q: on the rail, positive downwards.
  double t_gamma = 0.0;   ///< N, Tγ: frictional power per distance rolled.
};

/// What a force source returns: the resultant of both contacts on the wheelset, about its
/// centre, in track coordinates, and each wheel's contact (zero where a source has no wheels,
/// as the linear models).
struct ContactLoads {
  double fy = 0.0;        ///< N.
  double mz = 0.0;        ///< N·mm.
  int flags = 0;          ///< The runtime's WRC_FLAG_* bits (0 for exact solves).
  WheelContact wheel[2];  ///< [WRC_LEFT], [WRC_RIGHT].
};

/// Contact forces on the wheelset at a state and speed (mm/s). Throws on failure.
using ForceSource = std::function<ContactLoads(const State&, double velocity)>;

/// Time derivative of the state.
State Derivative(const Parameters& p, const State& s, const ContactLoads& loads);

/// One classical fourth-order Runge–Kutta step of length h (four force evaluations).
/// `flags` collects the force flags of the four evaluations.
State Rk4Step(const Parameters& p, const ForceSource& forces, const State& s, double velocity,
              double h, int* flags);

/// A simulated run: samples at every step, t = 0 included.
struct Trajectory {
  std::vector<double> t, y, yaw;
  int flags = 0;             ///< Or of all force flags.
  double seconds = 0.0;      ///< Wall time of the run.
  double cpu_seconds = 0.0;  ///< CPU time of the thread that ran it (one core).
  int steps = 0;
};

/// CPU time of the calling thread, s: on a shared machine the wall time also counts the time the
/// thread waited for a core.
double ThreadCpuSeconds();

/// The wall time and the CPU time of the calling thread since a run started (its construction).
class RunClock {
 public:
  RunClock() : wall_start_(std::chrono::steady_clock::now()), cpu_start_(ThreadCpuSeconds()) {}
  double WallSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
  }
  double CpuSeconds() const { return ThreadCpuSeconds() - cpu_start_; }

 private:
  std::chrono::steady_clock::time_point wall_start_;
  double cpu_start_;
};

/// Integrates from the parameters' initial disturbance over their duration at `velocity`.
Trajectory Simulate(const Parameters& p, const ForceSource& forces, double velocity);

}  // namespace wrc::dynamics
