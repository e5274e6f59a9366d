// The wheelset model of model.h: parameters, equations of motion and the integrator.

#include "studies/dynamics/model.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>
#include <utility>

#include "studies/dynamics/parameter_file.h"
#include "wrc/core/errors.h"
#include "wrc/core/toml_reader.h"

namespace wrc::dynamics {
namespace {

using io::Section;
using io::SourceFile;

// Sections and keys of a parameter file; anything else is a misspelling.
const ParameterSchema& Schema() {
  static const ParameterSchema schema = {
      {"wheelset", {"mass", "yaw_inertia", "wheel_load"}},
      {"suspension",
       {"lateral_stiffness", "lateral_damping", "longitudinal_stiffness", "longitudinal_damping",
        "semi_spacing"}},
      {"simulation", {"time_step", "duration", "initial_y"}},
  };
  return schema;
}

double Checked(const Section& s, std::string_view key, bool allow_zero, double fallback = NAN) {
  return CheckedNumber(s, key, allow_zero, fallback);
}

}  // namespace

double Parameters::YawStiffness() const {
  return 2.0 * longitudinal_stiffness * spring_semi_spacing * spring_semi_spacing;
}

double Parameters::YawDamping() const {
  return 2.0 * longitudinal_damping * spring_semi_spacing * spring_semi_spacing;
}

Parameters ParseParameters(const std::string& toml_text, const std::string& display_name) {
  const SourceFile file(display_name);
  const toml::table root = file.Parse(toml_text);
  CheckParameterNames(root, file, Schema());
  const Section ws(file, root, "wheelset"), su(file, root, "suspension"),
      sim(file, root, "simulation");
  Parameters p;
  p.mass = Checked(ws, "mass", false);
  p.yaw_inertia = Checked(ws, "yaw_inertia", false);
  p.wheel_load = Checked(ws, "wheel_load", false);
  p.lateral_stiffness = Checked(su, "lateral_stiffness", true);
  p.lateral_damping = Checked(su, "lateral_damping", true, 0.0);
  p.longitudinal_stiffness = Checked(su, "longitudinal_stiffness", true);
  p.longitudinal_damping = Checked(su, "longitudinal_damping", true, 0.0);
  p.spring_semi_spacing = Checked(su, "semi_spacing", false);
  const SimulationSettings run = ReadSimulation(sim, 2.0, 2.0);
  p.time_step = run.time_step;
  p.duration = run.duration;
  p.initial_y = run.initial_y;
  return p;
}

Parameters LoadParameters(const std::filesystem::path& path) {
  return ParseParameters(ReadParameterFile(path, "wheelset parameter"), path.string());
}

// m ÿ = F_y − k_y y − c_y ẏ, I ψ̈ = M_z − k_ψ ψ − c_ψ ψ̇, both axleboxes summed; the mass in kg
// and mm/s² give N only through the factor 1000 (likewise N·mm against kg·m²).
State Derivative(const Parameters& p, const State& s, const ContactLoads& loads) {
  const double fy = loads.fy - 2.0 * (p.lateral_stiffness * s.y + p.lateral_damping * s.vy);
  const double mz = loads.mz - p.YawStiffness() * s.yaw - p.YawDamping() * s.vyaw;
  return {s.vy, s.vyaw, 1000.0 * fy / p.mass, mz / (1000.0 * p.yaw_inertia)};
}

namespace {

State Advance(const State& s, const State& d, double h) {
  return {s.y + h * d.y, s.yaw + h * d.yaw, s.vy + h * d.vy, s.vyaw + h * d.vyaw};
}

State Slope(const Parameters& p, const ForceSource& forces, const State& s, double velocity,
            int* flags) {
  const ContactLoads loads = forces(s, velocity);
  *flags |= loads.flags;
  return Derivative(p, s, loads);
}

}  // namespace

State Rk4Step(const Parameters& p, const ForceSource& forces, const State& s, double velocity,
              double h, int* flags) {
  const State k1 = Slope(p, forces, s, velocity, flags);
  const State k2 = Slope(p, forces, Advance(s, k1, 0.5 * h), velocity, flags);
  const State k3 = Slope(p, forces, Advance(s, k2, 0.5 * h), velocity, flags);
  const State k4 = Slope(p, forces, Advance(s, k3, h), velocity, flags);
  State next = s;
  next = Advance(next, k1, h / 6.0);
  next = Advance(next, k2, h / 3.0);
  next = Advance(next, k3, h / 3.0);
  return Advance(next, k4, h / 6.0);
}

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

Trajectory Simulate(const Parameters& p, const ForceSource& forces, double velocity) {
  const RunClock clock;
  Trajectory run;
  const int steps = static_cast<int>(std::lround(p.duration / p.time_step));
  run.t.reserve(steps + 1);
  run.y.reserve(steps + 1);
  run.yaw.reserve(steps + 1);
  State s;
  s.y = p.initial_y;
  for (int i = 0;; ++i) {
    run.t.push_back(i * p.time_step);
    run.y.push_back(s.y);
    run.yaw.push_back(s.yaw);
    if (i == steps) break;
    s = Rk4Step(p, forces, s, velocity, p.time_step, &run.flags);
  }
  run.steps = steps;
  run.seconds = clock.WallSeconds();
  run.cpu_seconds = clock.CpuSeconds();
  return run;
}

}  // namespace wrc::dynamics
