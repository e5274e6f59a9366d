// Force sources of the wheelset model (forces.h).

#include "studies/dynamics/forces.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "wrc/core/errors.h"
#include "wrc/core/wheelrail.h"

namespace wrc::dynamics {
namespace {

constexpr int kSides[2] = {WRC_LEFT, WRC_RIGHT};

// The root of g in [a, b] by regula falsi with the Illinois modification (superlinear, and
// bracketing: safe where g is only piecewise smooth); the nearer end when g keeps its sign.
double Root(const std::function<double(double)>& g, double a, double b, double tolerance,
            bool* clamped) {
  double ga = g(a), gb = g(b);
  if (ga * gb > 0.0) {
    *clamped = true;
    return std::fabs(ga) < std::fabs(gb) ? a : b;
  }
  for (int i = 0; i < 100 && std::fabs(b - a) > tolerance; ++i) {
    const double c = (a * gb - b * ga) / (gb - ga), gc = g(c);
    if (gc == 0.0) return c;
    if (gc * gb < 0.0) {
      a = b;
      ga = gb;
    } else {
      ga *= 0.5;  // the end a kept again: halve its weight so that it moves too (Illinois)
    }
    b = c;
    gb = gc;
  }
  return b;
}

}  // namespace

RollCurve::RollCurve(const std::function<double(int, double, double)>& height, double y_max,
                     double dy, double roll_min, double roll_max) {
  const int n = static_cast<int>(std::ceil(y_max / dy - 1e-9));
  for (int i = 0; i <= n; ++i) {
    const double y = std::min(i * dy, y_max);
    // The wheel carries its load at a height that grows as it runs onto a larger radius; the
    // rigid wheelset rolls until both heights agree.
    const auto mismatch = [&](double roll) {
      return height(WRC_RIGHT, y, roll) - height(WRC_LEFT, y, roll);
    };
    bool clamped = false;
    // At y = 0 the pair is symmetric: roll 0 without solving.
    roll_.push_back(i == 0 ? 0.0 : Root(mismatch, roll_min, roll_max, 1e-8, &clamped));
    y_.push_back(y);
    clamped_ += clamped ? 1 : 0;
  }
}

double RollCurve::operator()(double y) const {
  if (y_.empty()) return 0.0;
  const double a = std::fabs(y);
  const double sign = y < 0.0 ? -1.0 : 1.0;
  if (a >= y_.back()) return sign * roll_.back();
  const auto it = std::upper_bound(y_.begin(), y_.end(), a);
  const std::size_t k = static_cast<std::size_t>(it - y_.begin());
  const double t = (a - y_[k - 1]) / (y_[k] - y_[k - 1]);
  return sign * ((1.0 - t) * roll_[k - 1] + t * roll_[k]);
}

double RollCurve::WheelsetY(double wheel_y, double nominal_radius) const {
  // Fixed point y = wheel_y + r0·roll(y): a contraction, as r0·|roll'| is a few hundredths.
  double y = wheel_y;
  for (int i = 0; i < 50; ++i) {
    const double next = wheel_y + nominal_radius * (*this)(y);
    if (std::fabs(next - y) < 1e-12) return next;
    y = next;
  }
  return y;
}

ContactLoads AssembleLoads(const double (&force)[2][3], const double (&moment)[2][3],
                           const double (&t_gamma)[2], const double (&origin)[2][2], double y) {
  ContactLoads loads;
  double fx = 0.0, mz_origin = 0.0;
  for (int side : kSides) {
    const double field = origin[side][0] < 0.0 ? -1.0 : 1.0;
    loads.wheel[side] = {field * force[side][1], force[side][2], t_gamma[side]};
    fx -= force[side][0];
    loads.fy -= force[side][1];
    // Moment on the wheelset about the track origin, −Σ (M + o × F), z component.
    mz_origin -= moment[side][2] - origin[side][0] * force[side][0];
  }
  // Moved to the wheelset centre (0, y, ·): M_c = M_o − c × F.
  loads.mz = mz_origin + y * fx;
  return loads;
}

// ---- table ------------------------------------------------------------------------------

TableForces::TableForces(const wrc::Table& table, const ContactGeometry& geometry, double y_max)
    : table_(table), wheelset_(table), geometry_(geometry) {
  for (int side : kSides)
    wheelset_.set_rail_origin(side, geometry.origin[side][0], geometry.origin[side][1]);
  if (wrc_table_output_index(table.get(), "z") < 0 || wrc_table_axis_index(table.get(), "fz") < 0) {
    throw InputError(
        "wrc study dynamics: the table needs an fz axis and a z output (a table made with the "
        "wheel load prescribed) for the quasi-static roll");
  }
  double roll_min = 0.0, roll_max = 0.0;
  if (const int a = wrc_table_axis_index(table.get(), "roll"); a >= 0) {
    roll_min = table.axis_values(a).front();
    roll_max = table.axis_values(a).back();
  }
  roll_ = RollCurve([this](int side, double y, double roll) { return Height(side, y, roll); },
                    y_max, kRollCurveStep, roll_min, roll_max);
}

double TableForces::Height(int side, double y, double roll) const {
  // The wheel on the other side than the table's is its mirror image (y, roll change sign).
  const double mirror = side == WRC_RIGHT ? 1.0 : -1.0;
  std::vector<double> point(table_.num_axes(), 0.0);
  for (int a = 0; a < table_.num_axes(); ++a) {
    const std::string name = table_.axis_name(a);
    if (name == "y")
      point[a] = mirror * y;
    else if (name == "y_wheel")
      point[a] = mirror * (y - geometry_.nominal_radius * roll);
    else if (name == "roll")
      point[a] = mirror * roll;
    else if (name == "fz")
      point[a] = geometry_.wheel_load;
    else if (name != "yaw" && name != "spin")
      throw InputError("wrc study dynamics: table axis '" + name + "' is not supported");
  }
  return table_.eval(point)[table_.output_index("z")];
}

ContactLoads TableForces::operator()(const State& s, double velocity) const {
  // One evaluation of both wheels: the wheelset API reads vy and vyaw on the yaw and spin axes
  // (the poses of equal creepage) where the table has no axes for them.
  wrc::WheelsetTable::State w;
  w.y = s.y;
  w.roll = roll_(s.y);
  w.yaw = s.yaw;
  w.vy = s.vy;
  w.vyaw = s.vyaw;
  w.velocity = velocity;
  w.omega = -velocity / geometry_.nominal_radius;
  w.fz[0] = w.fz[1] = geometry_.wheel_load;
  wrc_wheelset_result r;
  const int flags = wheelset_.eval(w, r);  // throws wrc::TableError on errors
  double force[2][3], moment[2][3], t_gamma[2];
  for (int side : kSides) {
    for (int i = 0; i < 3; ++i) {
      force[side][i] = r.wheel[side].force[i];
      moment[side][i] = r.wheel[side].moment[i];
    }
    t_gamma[side] = r.wheel[side].t_gamma;  // NaN when the table has no t_gamma output
  }
  ContactLoads loads = AssembleLoads(force, moment, t_gamma, geometry_.origin, s.y);
  loads.flags = flags;
  return loads;
}

// ---- solver -----------------------------------------------------------------------------

SolverForces::SolverForces(Case base, const ContactGeometry& geometry, double y_max)
    : base_(std::move(base)), geometry_(geometry) {
  roll_ = RollCurve([this](int side, double y, double roll) { return Height(side, y, roll); },
                    y_max, std::min(kRollCurveStep, y_max), -0.01, 0.01);
}

Case SolverForces::Wheel(int side, const State& s, double roll, double velocity) const {
  Case c = base_;
  c.wheelset.side = side == WRC_LEFT ? WheelSide::kLeft : WheelSide::kRight;
  WheelsetState& st = c.state;
  st.y = s.y;
  st.roll = roll;
  st.yaw = s.yaw;
  st.vy = s.vy;
  st.vroll = 0.0;
  st.vyaw = s.vyaw;
  st.velocity = velocity;
  st.omega = -velocity / geometry_.nominal_radius;  // free rolling on the nominal radius
  st.spin.reset();
  st.z.reset();
  st.fz = geometry_.wheel_load;
  return c;
}

double SolverForces::Height(int side, double y, double roll) {
  State s;
  s.y = y;
  WheelRailOptions options;
  options.z_guess = z_guess_[side];
  const WheelRailResult r = SolveWheelRail(Wheel(side, s, roll, base_.state.velocity), options);
  ++solves_;
  if (r.status != SolverStatus::kConverged) {
    throw InputError("wrc study dynamics: the solve at y = " + FormatNumber(y) +
                     " mm, roll = " + FormatNumber(roll) + " rad did not converge");
  }
  z_guess_[side] = r.z;
  return r.z;
}

ContactLoads SolverForces::operator()(const State& s, double velocity) {
  const double roll = roll_(s.y);
  double force[2][3], moment[2][3], t_gamma[2];
  for (int side : kSides) {
    WheelRailOptions options;
    options.z_guess = z_guess_[side];
    const WheelRailResult r = SolveWheelRail(Wheel(side, s, roll, velocity), options);
    ++solves_;
    if (r.status != SolverStatus::kConverged) {
      throw InputError("wrc study dynamics: the solve at y = " + FormatNumber(s.y) +
                       " mm, yaw = " + FormatNumber(s.yaw) + " rad did not converge");
    }
    z_guess_[side] = r.z;
    for (int i = 0; i < 3; ++i) {
      force[side][i] = r.force_T(i);
      moment[side][i] = r.moment_T(i);
    }
    t_gamma[side] = TGamma(r);
  }
  return AssembleLoads(force, moment, t_gamma, geometry_.origin, s.y);
}

ContactGeometry SceneGeometry(const Case& base, double wheel_load) {
  Case c = base;
  c.wheelset.side = WheelSide::kRight;
  c.state = WheelsetState{};
  c.state.y = 0.0;
  c.state.yaw = 0.0;
  c.state.velocity = base.state.velocity;
  c.state.omega = -base.state.velocity / base.wheelset.nominal_radius;
  c.state.fz = wheel_load;
  const WheelRailResult r = SolveWheelRail(c);
  ContactGeometry g;
  g.wheel_load = wheel_load;
  g.nominal_radius = base.wheelset.nominal_radius;
  g.semi_spacing = 0.5 * base.wheelset.flange_back_distance - base.wheelset.flange_back_position;
  g.origin[WRC_RIGHT][0] = r.rail_origin_T(1);
  g.origin[WRC_RIGHT][1] = r.rail_origin_T(2);
  g.origin[WRC_LEFT][0] = -r.rail_origin_T(1);
  g.origin[WRC_LEFT][1] = r.rail_origin_T(2);
  return g;
}

// ---- linear -----------------------------------------------------------------------------

Eigen::Matrix<double, 2, 4> LinearisedLoads(const ForceSource& source, const State& at,
                                            double velocity, const Eigen::Vector4d& h,
                                            const Eigen::Vector4i& n) {
  Eigen::Matrix<double, 2, 4> d = Eigen::Matrix<double, 2, 4>::Zero();
  for (int j = 0; j < 4; ++j) {
    if (n(j) < 1) throw std::invalid_argument("LinearisedLoads: fewer than one sample a side");
    // Offsets ±x_k symmetric about the state: the least-squares slope is
    // Σ x_k (f(+x_k) − f(−x_k)) / (2 Σ x_k²), and the state itself carries no weight.
    double sum_xx = 0.0;
    for (int k = 1; k <= n(j); ++k) {
      const double x = h(j) * k / n(j);
      State plus = at, minus = at;
      double* p[4] = {&plus.y, &plus.yaw, &plus.vy, &plus.vyaw};
      double* m[4] = {&minus.y, &minus.yaw, &minus.vy, &minus.vyaw};
      *p[j] += x;
      *m[j] -= x;
      const ContactLoads a = source(plus, velocity), b = source(minus, velocity);
      d(0, j) += x * (a.fy - b.fy);
      d(1, j) += x * (a.mz - b.mz);
      sum_xx += 2.0 * x * x;
    }
    d.col(j) /= sum_xx;
  }
  return d;
}

ContactLoads LinearContact::operator()(const State& s, double velocity) const {
  ContactLoads loads;
  loads.fy = -2.0 * f22 * (s.vy / velocity - s.yaw) - gravity_stiffness * s.y;
  loads.mz = -2.0 * f11 * semi_spacing *
             (semi_spacing * s.vyaw / velocity + conicity * s.y / nominal_radius);
  return loads;
}

Eigen::Matrix4d LinearSystem(const Parameters& p, const LinearContact& c, double velocity) {
  // Columns: the derivative of the state for each unit state (the model is linear).
  Eigen::Matrix4d a;
  for (int k = 0; k < 4; ++k) {
    State s;
    (k == 0 ? s.y : k == 1 ? s.yaw : k == 2 ? s.vy : s.vyaw) = 1.0;
    const State d = Derivative(p, s, c(s, velocity));
    a.col(k) << d.y, d.yaw, d.vy, d.vyaw;
  }
  return a;
}

namespace {
double LargestRealPart(const Eigen::Matrix4d& a) {
  return Eigen::EigenSolver<Eigen::Matrix4d>(a, false).eigenvalues().real().maxCoeff();
}
}  // namespace

double LinearCriticalSpeed(const Parameters& p, const LinearContact& c, double v_low,
                           double v_high) {
  const auto growth = [&](double v) { return LargestRealPart(LinearSystem(p, c, v)); };
  if (growth(v_low) * growth(v_high) > 0.0) return NAN;
  bool clamped = false;
  return Root(growth, v_low, v_high, 1e-6 * v_high, &clamped);
}

}  // namespace wrc::dynamics
