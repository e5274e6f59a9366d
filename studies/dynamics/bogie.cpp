// The bogie model of bogie.h: parameters, equations of motion, linear stability, integration.

#include "studies/dynamics/bogie.h"

#include <cmath>

#include "studies/dynamics/parameter_file.h"
#include "tools/angles.h"
#include "wrc/core/errors.h"
#include "wrc/core/toml_reader.h"

namespace wrc::dynamics {
namespace {

using io::Section;

// Standard gravity, m/s² (the wheel load from the published masses).
constexpr double kGravity = 9.81;

const ParameterSchema& Schema() {
  static const ParameterSchema schema = {
      {"wheelset", {"mass", "yaw_inertia"}},
      {"frame", {"mass", "yaw_inertia", "semi_wheelbase"}},
      {"body", {"mass", "bogie_semi_spacing"}},
      {"primary",
       {"lateral_stiffness", "longitudinal_stiffness", "lateral_damping", "longitudinal_damping",
        "semi_spacing"}},
      {"secondary",
       {"lateral_stiffness", "longitudinal_stiffness", "lateral_damping", "yaw_damping",
        "semi_spacing"}},
      {"simulation", {"time_step", "duration", "initial_y"}},
      {"curving", {"radii", "cant", "cant_deficiency", "rail_spacing"}},
  };
  return schema;
}

// [curving]: every key but rail_spacing required once the section is there, the radii positive
// (NumberArray refuses an empty list).
CurvingSettings ReadCurving(const Section& s) {
  CurvingSettings c;
  if (!s.exists()) return c;
  for (const io::NumberAt& r : s.NumberArray("radii")) {
    if (!(r.value > 0.0)) s.Fail("radii", r.path + " must be positive");
    c.radii.push_back(r.value);
  }
  c.cant = CheckedNumber(s, "cant", true, NAN);
  c.cant_deficiency = CheckedNumber(s, "cant_deficiency", true, NAN);
  c.rail_spacing = CheckedNumber(s, "rail_spacing", false, c.rail_spacing);
  return c;
}

// Indices into the state: positions 0–5 (y1, ψ1, y2, ψ2, y_f, ψ_f), velocities 6–11.
constexpr int kFrameY = 4, kFrameYaw = 5, kVelocities = 6;

// The axleboxes' longitudinal position: leading wheelset at +a, trailing at −a.
double AxlePosition(const BogieParameters& p, int k) {
  return k == 0 ? p.semi_wheelbase : -p.semi_wheelbase;
}

}  // namespace

double BogieParameters::WheelLoad() const {
  return (0.5 * body_mass + frame_mass + 2.0 * wheelset_mass) * kGravity / 4.0;
}

BogieParameters ParseBogieParameters(const std::string& toml_text, const std::string& name) {
  const io::SourceFile file(name);
  const toml::table root = file.Parse(toml_text);
  CheckParameterNames(root, file, Schema());
  const Section ws(file, root, "wheelset"), fr(file, root, "frame"), body(file, root, "body"),
      pri(file, root, "primary"), sec(file, root, "secondary"), sim(file, root, "simulation"),
      curving(file, root, "curving");
  auto required = [](const Section& s, std::string_view key) {
    return CheckedNumber(s, key, false, NAN);
  };
  auto optional = [](const Section& s, std::string_view key) {
    return CheckedNumber(s, key, true, 0.0);
  };
  BogieParameters p;
  p.wheelset_mass = required(ws, "mass");
  p.wheelset_yaw_inertia = required(ws, "yaw_inertia");
  p.frame_mass = required(fr, "mass");
  p.frame_yaw_inertia = required(fr, "yaw_inertia");
  p.semi_wheelbase = required(fr, "semi_wheelbase");
  p.body_mass = required(body, "mass");
  p.bogie_semi_spacing = optional(body, "bogie_semi_spacing");
  p.primary_lateral_stiffness = required(pri, "lateral_stiffness");
  p.primary_longitudinal_stiffness = required(pri, "longitudinal_stiffness");
  p.primary_lateral_damping = optional(pri, "lateral_damping");
  p.primary_longitudinal_damping = optional(pri, "longitudinal_damping");
  p.primary_semi_spacing = required(pri, "semi_spacing");
  p.secondary_lateral_stiffness = required(sec, "lateral_stiffness");
  p.secondary_longitudinal_stiffness = required(sec, "longitudinal_stiffness");
  p.secondary_lateral_damping = optional(sec, "lateral_damping");
  p.secondary_yaw_damping = optional(sec, "yaw_damping");
  p.secondary_semi_spacing = required(sec, "semi_spacing");
  const SimulationSettings run = ReadSimulation(sim, 3.0, 1.0);
  p.time_step = run.time_step;
  p.duration = run.duration;
  p.initial_y = run.initial_y;
  p.curving = ReadCurving(curving);
  return p;
}

BogieParameters LoadBogieParameters(const std::filesystem::path& path) {
  return ParseBogieParameters(ReadParameterFile(path, "vehicle parameter"), path.string());
}

State WheelsetOf(const BogieVector& x, int k) {
  return {x(2 * k), x(2 * k + 1), x(kVelocities + 2 * k), x(kVelocities + 2 * k + 1)};
}

// Newton–Euler for the five bodies' lateral and yaw motion. Per wheelset k at x_k = ±a: the
// primary suspension's lateral deflection is y_k − y_f − x_k ψ_f (two axleboxes), its yaw
// deflection ψ_k − ψ_f (longitudinal springs at ±b1). The frame carries the reactions and the
// secondary suspension to the body (lateral springs and dampers, longitudinal springs and yaw
// dampers at ±b2). Masses in kg and mm/s² give N through the factor 1000; N·mm against kg·m²
// likewise. In a curve of curvature κ the centre line at x_k lies x_k²κ/2 inwards of the frame
// centre's tangent and turns by x_k κ, which the primary deflections subtract; every body feels
// the unbalanced acceleration.
BogieVector BogieDerivative(const BogieParameters& p, const BogieVector& x,
                            const ContactLoads (&loads)[2], const BogieTrack& track) {
  const double b1 = p.primary_semi_spacing, b2 = p.secondary_semi_spacing;
  const double k_yaw1 = 2.0 * p.primary_longitudinal_stiffness * b1 * b1;
  const double c_yaw1 = 2.0 * p.primary_longitudinal_damping * b1 * b1;
  const auto v = [&x](int i) { return x(kVelocities + i); };
  BogieVector d;
  d.head<6>() = x.tail<6>();
  double frame_force = 0.0, frame_moment = 0.0;
  for (int k = 0; k < 2; ++k) {
    const double a = AxlePosition(p, k);
    const double lateral = x(2 * k) - x(kFrameY) - a * x(kFrameYaw) - 0.5 * a * a * track.curvature;
    const double lateral_rate = v(2 * k) - v(kFrameY) - a * v(kFrameYaw);
    const double f =
        -2.0 * (p.primary_lateral_stiffness * lateral + p.primary_lateral_damping * lateral_rate);
    const double m = -k_yaw1 * (x(2 * k + 1) - x(kFrameYaw) - a * track.curvature) -
                     c_yaw1 * (v(2 * k + 1) - v(kFrameYaw));
    d(kVelocities + 2 * k) =
        1000.0 * (loads[k].fy + f) / p.wheelset_mass + track.unbalanced_acceleration;
    d(kVelocities + 2 * k + 1) = (loads[k].mz + m) / (1000.0 * p.wheelset_yaw_inertia);
    frame_force -= f;
    frame_moment -= m + a * f;
  }
  frame_force -= 2.0 * (p.secondary_lateral_stiffness * (x(kFrameY) - track.body_y) +
                        p.secondary_lateral_damping * v(kFrameY));
  frame_moment -= 2.0 * b2 * b2 *
                  (p.secondary_longitudinal_stiffness * (x(kFrameYaw) - track.body_yaw) +
                   p.secondary_yaw_damping * v(kFrameYaw));
  d(kVelocities + kFrameY) = 1000.0 * frame_force / p.frame_mass + track.unbalanced_acceleration;
  d(kVelocities + kFrameYaw) = frame_moment / (1000.0 * p.frame_yaw_inertia);
  return d;
}

ContactLoads LinearisedContact::operator()(const State& s, double velocity) const {
  // Creepages hold the velocities as vy/V and vyaw/V: the velocity columns scale with V0/V.
  const double scale = speed / velocity;
  const Eigen::Vector4d x(s.y, s.yaw, scale * s.vy, scale * s.vyaw);
  const Eigen::Vector2d f = jacobian * x;
  ContactLoads loads;
  loads.fy = f(0);
  loads.mz = f(1);
  return loads;
}

BogieMatrix BogieLinearSystem(const BogieParameters& p, const LinearisedContact& contact,
                              double velocity) {
  // Columns: the derivative of each unit state (the linearised model is linear).
  BogieMatrix a;
  for (int j = 0; j < 12; ++j) {
    const BogieVector x = BogieVector::Unit(j);
    const ContactLoads loads[2] = {contact(WheelsetOf(x, 0), velocity),
                                   contact(WheelsetOf(x, 1), velocity)};
    a.col(j) = BogieDerivative(p, x, loads);
  }
  return a;
}

std::complex<double> DominantEigenvalue(const BogieMatrix& a) {
  const Eigen::Matrix<std::complex<double>, 12, 1> e =
      Eigen::EigenSolver<BogieMatrix>(a, false).eigenvalues();
  int k = 0;
  for (int i = 1; i < 12; ++i) {
    if (e(i).real() > e(k).real()) k = i;
  }
  return e(k);
}

double FrequencyOf(std::complex<double> eigenvalue) {
  return std::fabs(eigenvalue.imag()) / (2.0 * tools::kPi);
}

double BogieCriticalSpeed(const BogieParameters& p, const LinearisedContact& contact, double v_low,
                          double v_high) {
  const auto growth = [&](double v) {
    return DominantEigenvalue(BogieLinearSystem(p, contact, v)).real();
  };
  // Scan for the first sign change, then bisect within it.
  double lo = v_low, g_lo = growth(lo);
  if (g_lo >= 0.0) return v_low;
  for (double hi = lo * 1.01;; hi = std::min(v_high, hi * 1.01)) {
    const double g_hi = growth(hi);
    if (g_hi >= 0.0) {
      while (hi - lo > 1e-6 * v_high) {
        const double mid = 0.5 * (lo + hi);
        (growth(mid) < 0.0 ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    }
    if (hi >= v_high) return NAN;
    lo = hi;
  }
}

Trajectory BogieTrajectory::Leading() const {
  Trajectory run;
  run.t = t;
  run.y = y;
  run.yaw = yaw;
  run.flags = flags;
  run.seconds = seconds;
  run.cpu_seconds = cpu_seconds;
  run.steps = steps;
  return run;
}

namespace {

BogieVector Slope(const BogieParameters& p, const ForceSource (&forces)[2], const BogieVector& x,
                  double velocity, int* flags) {
  ContactLoads loads[2];
  for (int k = 0; k < 2; ++k) {
    loads[k] = forces[k](WheelsetOf(x, k), velocity);
    *flags |= loads[k].flags;
  }
  return BogieDerivative(p, x, loads);
}

}  // namespace

BogieTrajectory SimulateBogie(const BogieParameters& p, const ForceSource (&forces)[2],
                              double velocity) {
  const RunClock clock;
  BogieTrajectory run;
  const int steps = static_cast<int>(std::lround(p.duration / p.time_step));
  const double h = p.time_step;
  BogieVector x = BogieVector::Zero();
  x(0) = p.initial_y;
  for (int i = 0;; ++i) {
    run.t.push_back(i * h);
    run.y.push_back(x(0));
    run.yaw.push_back(x(1));
    run.frame_y.push_back(x(kFrameY));
    if (i == steps) break;
    // The classical fourth-order Runge–Kutta step, as Rk4Step for the wheelset.
    const BogieVector k1 = Slope(p, forces, x, velocity, &run.flags);
    const BogieVector k2 = Slope(p, forces, x + 0.5 * h * k1, velocity, &run.flags);
    const BogieVector k3 = Slope(p, forces, x + 0.5 * h * k2, velocity, &run.flags);
    const BogieVector k4 = Slope(p, forces, x + h * k3, velocity, &run.flags);
    x += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  run.steps = steps;
  run.seconds = clock.WallSeconds();
  run.cpu_seconds = clock.CpuSeconds();
  return run;
}

}  // namespace wrc::dynamics
