// `wrc study dynamics TABLE.h5... --out DIR`: a wheelset simulated with its contact forces from
// the table and from full solves (studies/dynamics): trajectories, hunting frequency and growth
// rate against speed, critical speeds, and what each costs.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "studies/dynamics/analysis.h"
#include "studies/dynamics/bogie.h"
#include "studies/dynamics/curving.h"
#include "studies/dynamics/forces.h"
#include "studies/dynamics/model.h"
#include "studies/shipped_files.h"
#include "studies/study_commands.h"
#include "studies/study_common.h"
#include "tools/wrc/commands.h"
#include "tools/wrc/gnuplot.h"
#include "tools/wrc/output_text.h"
#include "tools/wrc/verify.h"
#include "wrc/core/errors.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;
using dynamics::Hunting;
using dynamics::Parameters;
using dynamics::Trajectory;

struct DynamicsOptions {
  std::vector<std::string> tables;
  std::string out = "study-dynamics";
  std::string model;           // empty: the shipped tables/wheelset_dynamics.toml, compiled in
  std::vector<double> speeds;  // m/s, table sweep
  std::vector<double> solver_speeds;  // m/s; empty: 0.8 and 1.2 times the table's critical speed
  int solver_bisections = 2;
  bool no_solver = false;
  bool linear_only = false;
  bool no_runs = false;        // linearisation, stability and curves, no time integration
  double solver_elements = 0;  // mm, dx = ds of the solver source; 0: the table's own
  double linear_speed = 50.0;  // m/s, of the linearised contact
  double tolerance = 0.05;     // m/s, of the table's bisection
  std::string vehicle;         // a vehicle file: the bogie's linear stability from both sources
  std::string interpolation = "linear";  // of the table: linear or cubic
};

// The linearised contact's y derivative: the least-squares slope over ±kWheelWindow (mm) of
// each wheel's lateral position on its rail, kWheelSamples evenly spaced on each side. At 0.5 mm
// elements the solver's wheelset Fy on the Manchester pair departs from a smooth curve by 30 N
// RMS (peaks of 80 N, 0.15 % of the wheel load) as the patches cross elements: a central
// difference over ±0.25 mm reads a different part of that ripple in each source, a fit over
// ±0.5 mm averages it, though not to 1 % of ∂Fy/∂y (the solver's own slope over ±0.5, ±1 and
// ±2 mm spreads by 6 %; the study's centred.csv shows it). The window is also the amplitude at
// which the bogie hunts near its critical speed.
constexpr double kWheelWindow = 0.5;
constexpr int kWheelSamples = 10;

// Extrema before this are the transient of the initial disturbance, not hunting.
constexpr double kSettle = 0.1;  // s

// One run of one source at one speed.
struct Row {
  std::string source;
  double speed = 0.0;  // m/s
  Hunting hunting;
  int flags = 0;
  double seconds = 0.0;
  int steps = 0;
  std::string failure;  // why a solver run stopped
};

// Four significant digits: the derivatives span eight decades, and their ratios are what is read.
std::string Significant(double v) {
  if (std::isnan(v)) return "–";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}

std::string FlagNames(int flags) {
  std::string s;
  if (flags & WRC_FLAG_CLAMPED) s += "clamped ";
  if (flags & WRC_FLAG_STATUS) s += "status ";
  if (flags & WRC_FLAG_FIXED) s += "fixed ";
  if (s.empty()) return "–";
  s.pop_back();
  return s;
}

// Sum of wall time and steps of a source's runs: cost per step and real-time factor.
struct Cost {
  double seconds = 0.0, cpu_seconds = 0.0, simulated = 0.0;
  long steps = 0;
  void Add(const Trajectory& run, double dt) {
    seconds += run.seconds;
    cpu_seconds += run.cpu_seconds;
    steps += run.steps;
    simulated += run.steps * dt;
  }
};

// The wheelset of `--model`, or the shipped one (the Manchester benchmark's vehicle 1,
// tables/wheelset_dynamics.toml) compiled in, so that the study runs from any directory.
Parameters LoadModel(const std::string& path) {
  if (!path.empty()) return dynamics::LoadParameters(path);
  for (const ShippedFile& f : ShippedFiles()) {
    if (f.name == "wheelset_dynamics.toml") {
      return dynamics::ParseParameters(std::string(f.bytes), "wheelset_dynamics.toml (shipped)");
    }
  }
  throw std::logic_error("wheelset_dynamics.toml is not compiled in");
}

// ---- the study of one table ---------------------------------------------------------------

// The bogie's quasi-static curving in one curve on each source.
struct Curving {
  dynamics::CurveCase curve;
  dynamics::CurvingResult table;
  std::optional<dynamics::CurvingResult> solver;
  std::string failure;  // why the solver gave no equilibrium
};

class TableStudy {
 public:
  TableStudy(const DynamicsOptions& options, const fs::path& table_path, const fs::path& out)
      : options_(options), out_(out), table_(table_path.string()) {
    table_.set_interpolation(options.interpolation == "cubic" ? Interpolation::kCubic
                                                              : Interpolation::kLinear);
    parameters_ = LoadModel(options.model);
    if (!options.vehicle.empty()) {
      // The contact is linearised at the vehicle's own wheel load.
      vehicle_ = dynamics::LoadBogieParameters(options.vehicle);
      parameters_.wheel_load = vehicle_->WheelLoad();
    }
    stored_ = LoadStoredScene(table_path);
    solver_scene_ = stored_->scene.base;
    if (options.solver_elements > 0.0) {
      // A reference finer than the table's own: how far the solver moves with its elements.
      solver_scene_.grid.dx = options.solver_elements;
      solver_scene_.grid.ds = options.solver_elements;
    }
    geometry_ = dynamics::SceneGeometry(stored_->scene.base, parameters_.wheel_load);
    table_forces_ = std::make_unique<dynamics::TableForces>(table_, geometry_);
    table_name_ = table_path.filename().string();
  }

  int Run();

 private:
  Trajectory Simulated(double speed_m_s, const std::function<dynamics::ForceSource()>& make);
  double TimeStep() const { return vehicle_ ? vehicle_->time_step : parameters_.time_step; }
  // The --interpolation option as a user would repeat it, empty for the default.
  // The options that change what the study measures, as they were given.
  std::string MeasuringFlags() const {
    std::string flags;
    if (options_.interpolation != "linear") flags += " --interpolation " + options_.interpolation;
    if (options_.solver_elements > 0.0) {
      flags += " --solver-elements " + Significant(options_.solver_elements);
    }
    return flags;
  }
  bool RunsTime() const { return !options_.linear_only && !options_.no_runs; }
  Trajectory TableRun(double speed_m_s);
  double TableRate(double speed_m_s);
  void SweepTable();
  void BisectTable();
  void RunSolver();
  void PrepareSolver();
  std::optional<Trajectory> SolverRun(double speed_m_s);
  void CompareAt(double speed_m_s, const Trajectory& solver);
  void WriteSpeedsCsv() const;
  // Draws out_/stem.png from `script` (out_/stem.gp), or says that gnuplot is missing.
  void Draw(const std::string& stem, const std::string& script) const {
    DrawOrSay(out_, stem + ".gp", script,
              "wrc study dynamics: gnuplot is not installed: no " + stem + ".png");
  }
  void WriteHuntingPlot() const;
  void WriteSummary() const;
  void WriteRunsSummary(std::ostream& md) const;
  void Linearise();
  void WriteRollCsv(const dynamics::RollCurve& table, const dynamics::RollCurve& solver) const;
  void SampleCentredPath(const dynamics::ForceSource (&sources)[2]);
  void WriteCentredPlot() const;
  void WriteCentredSummary(std::ostream& md) const;
  void WriteLinearSummary(std::ostream& md) const;
  void AnalyseVehicle();
  void WriteVehicleSummary(std::ostream& md) const;
  void CurveVehicle();
  void WriteCurvingCsv() const;
  void WriteCurvingPlot() const;
  void WriteCurvingSummary(std::ostream& md) const;

  const DynamicsOptions& options_;
  fs::path out_;
  wrc::Table table_;
  std::unique_ptr<StoredScene> stored_;
  Case solver_scene_;  ///< The stored scene, at --solver-elements where given.
  Parameters parameters_;
  dynamics::ContactGeometry geometry_;
  std::unique_ptr<dynamics::TableForces> table_forces_;
  std::unique_ptr<dynamics::SolverForces> solver_forces_;
  std::string table_name_;
  std::vector<Row> rows_;
  Cost table_cost_, solver_cost_;
  double table_critical_ = NAN, solver_critical_ = NAN;
  double table_critical_at_solver_speeds_ = NAN;  // interpolated as the solver's is
  int table_bisections_ = 0;
  struct Comparison {
    double speed;
    dynamics::RunDifference d;
    Hunting table, solver;
  };
  std::vector<Comparison> comparisons_;
  // Linearised contact per source ("table", "solver") and lateral position (mm).
  struct Linearisation {
    std::string source;
    double y;
    Eigen::Matrix<double, 2, 4> d;
  };
  std::vector<Linearisation> linear_;
  // Both sources' resultant along y at centred running (no yaw, no velocities), densely.
  struct CentredPath {
    std::vector<double> y;
    std::vector<double> fy[2], mz[2];  // [table, solver]
  };
  CentredPath centred_;
  // The vehicle's bogie on each source's linearised contact at y = 0.
  std::optional<dynamics::BogieParameters> vehicle_;
  struct VehicleStability {
    std::string source;
    dynamics::LinearisedContact contact;         // at y = 0
    double critical = NAN;                       // m/s
    std::vector<double> speeds, hertz, damping;  // m/s, Hz, 1/s of the dominant eigenvalue
  };
  std::vector<VehicleStability> vehicle_stability_;
  std::vector<Curving> curving_;  // per curve of the vehicle file
  double solver_roll_seconds_ = 0.0;
  long solver_roll_solves_ = 0;
  std::mutex mutex_;  // rows_, solver_cost_ and messages while solver runs share the study
};

// One run at `speed_m_s`: the wheelset, or with --vehicle the bogie, whose leading wheelset's
// trajectory is returned (each wheelset on a source of its own from `make`, so that a solver
// source warm-starts from its own wheelset's previous solve).
Trajectory TableStudy::Simulated(double speed_m_s,
                                 const std::function<dynamics::ForceSource()>& make) {
  if (!vehicle_) return dynamics::Simulate(parameters_, make(), 1000.0 * speed_m_s);
  const dynamics::ForceSource forces[2] = {make(), make()};
  return dynamics::SimulateBogie(*vehicle_, forces, 1000.0 * speed_m_s).Leading();
}

Trajectory TableStudy::TableRun(double speed_m_s) {
  Trajectory run = Simulated(speed_m_s, [this] {
    return [this](const dynamics::State& s, double v) { return (*table_forces_)(s, v); };
  });
  table_cost_.Add(run, TimeStep());
  return run;
}

double TableStudy::TableRate(double speed_m_s) {
  const Trajectory run = TableRun(speed_m_s);
  Row row{"table",   speed_m_s, dynamics::MeasureHunting(run, kSettle), run.flags, run.seconds,
          run.steps, ""};
  rows_.push_back(row);
  return row.hunting.growth_rate;
}

void TableStudy::SweepTable() {
  for (double v : options_.speeds) {
    TableRate(v);
    std::cerr << "wrc study dynamics: table, " << v << " m/s: growth "
              << Fixed(rows_.back().hunting.growth_rate, 3) << " 1/s\n";
  }
}

// Bisection on V between the first pair of sweep speeds where decay turns into growth.
void TableStudy::BisectTable() {
  std::vector<Row> sweep = rows_;
  std::sort(sweep.begin(), sweep.end(),
            [](const Row& a, const Row& b) { return a.speed < b.speed; });
  for (std::size_t i = 0; i + 1 < sweep.size(); ++i) {
    if (!(sweep[i].hunting.growth_rate < 0.0 && sweep[i + 1].hunting.growth_rate >= 0.0)) continue;
    double lo = sweep[i].speed, hi = sweep[i + 1].speed;
    while (hi - lo > options_.tolerance) {
      const double mid = 0.5 * (lo + hi);
      (TableRate(mid) < 0.0 ? lo : hi) = mid;
      ++table_bisections_;
    }
    table_critical_ = 0.5 * (lo + hi);
    return;
  }
}

void TableStudy::PrepareSolver() {
  if (solver_forces_) return;
  const auto t0 = std::chrono::steady_clock::now();
  solver_forces_ = std::make_unique<dynamics::SolverForces>(solver_scene_, geometry_);
  solver_roll_seconds_ = SecondsSince(t0);
  solver_roll_solves_ = solver_forces_->solves();
}

// A solver run on its own copy of the solver source (the copies share the roll curve, each
// warm-starts its own wheelset heights), so that runs may go on separate threads.
std::optional<Trajectory> TableStudy::SolverRun(double speed_m_s) {
  PrepareSolver();
  const auto make = [this]() -> dynamics::ForceSource {
    auto forces = std::make_shared<dynamics::SolverForces>(*solver_forces_);
    return [forces](const dynamics::State& s, double v) { return (*forces)(s, v); };
  };
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::cerr << "wrc study dynamics: solver, " << speed_m_s << " m/s ...\n";
  }
  Row row{"solver", speed_m_s, {}, 0, 0.0, 0, ""};
  std::optional<Trajectory> result;
  try {
    Trajectory run = Simulated(speed_m_s, make);
    row.hunting = dynamics::MeasureHunting(run, kSettle);
    row.seconds = run.seconds;
    row.steps = run.steps;
    result = std::move(run);
  } catch (const InputError& e) {
    row.failure = e.what();
    row.hunting.growth_rate = row.hunting.frequency = NAN;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  if (result) solver_cost_.Add(*result, TimeStep());
  if (!row.failure.empty()) {
    std::cerr << "wrc study dynamics: warning: solver run at " << speed_m_s
              << " m/s stopped: " << row.failure << "\n";
  }
  rows_.push_back(row);
  return result;
}

// Trajectories of both sources at one speed: CSV, PNG and their differences.
void TableStudy::CompareAt(double speed_m_s, const Trajectory& solver) {
  const Trajectory table = TableRun(speed_m_s);
  comparisons_.push_back({speed_m_s, dynamics::CompareRuns(table, solver, kSettle),
                          dynamics::MeasureHunting(table, kSettle),
                          dynamics::MeasureHunting(solver, kSettle)});
  const std::string stem = "run_" + Fixed(speed_m_s, 1) + "ms";
  OutputText csv(out_ / (stem + ".csv"));
  csv << "t_s,y_table_mm,yaw_table_rad,y_solver_mm,yaw_solver_rad\n";
  csv.precision(9);
  for (std::size_t i = 0; i < table.t.size() && i < solver.t.size(); ++i) {
    csv << table.t[i] << ',' << table.y[i] << ',' << table.yaw[i] << ',' << solver.y[i] << ','
        << solver.yaw[i] << '\n';
  }
  csv.Commit();
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1000,700 font ',10'\nset output '" << stem << ".png'\n"
     << "set datafile separator ','\nset multiplot layout 2,1 title '"
     << (vehicle_ ? "Leading wheelset of the bogie" : "Wheelset") << " at " << Fixed(speed_m_s, 1)
     << " m/s (" << table_name_ << "): forces from the table and from full solves' noenhanced\n"
     << "set grid\nset xlabel 't, s'\nset ylabel 'y, mm'\n"
     << "plot '" << stem
     << ".csv' skip 1 using 1:2 with lines lw 2 title 'table', '' skip 1 using 1:4 with lines dt 2 "
        "lw 2 title 'solver'\n"
     << "set ylabel 'yaw, mrad'\n"
     << "plot '" << stem
     << ".csv' skip 1 using 1:($3*1000) with lines lw 2 title 'table', '' skip 1 using 1:($5*1000) "
        "with lines dt 2 lw 2 title 'solver'\n"
     << "unset multiplot\n";
  Draw(stem, gp.str());
}

// The adjacent (speed, growth rate) pairs whose growth changes sign from negative, sorting
// `rates` by speed; none when no pair does.
std::optional<std::pair<std::pair<double, double>, std::pair<double, double>>> GrowthBracket(
    std::vector<std::pair<double, double>>& rates) {
  std::sort(rates.begin(), rates.end());
  for (std::size_t i = 0; i + 1 < rates.size(); ++i) {
    if (rates[i].second < 0.0 && rates[i + 1].second >= 0.0)
      return std::pair{rates[i], rates[i + 1]};
  }
  return std::nullopt;
}

// The speed where the growth rate crosses zero, linear between the runs that bracket it; NaN
// when none do.
double ZeroGrowthSpeed(std::vector<std::pair<double, double>> rates) {
  const auto b = GrowthBracket(rates);
  if (!b) return NAN;
  const auto [lo, hi] = *b;
  return lo.first + (hi.first - lo.first) * (-lo.second) / (hi.second - lo.second);
}

void TableStudy::RunSolver() {
  std::vector<double> speeds = options_.solver_speeds;
  if (speeds.empty() && !std::isnan(table_critical_)) {
    speeds = {std::round(0.8 * table_critical_), std::round(1.2 * table_critical_)};
  }
  // (speed, growth rate) of the solver runs, for its own critical speed.
  std::vector<std::pair<double, double>> rates;
  // The first runs side by side, one thread each: a solver run is hundreds of CPU seconds.
  PrepareSolver();
  std::vector<std::optional<Trajectory>> runs(speeds.size());
  RunParallel(
      speeds.size(), static_cast<int>(speeds.size()),
      [this, &runs, &speeds](std::size_t k) { runs[k] = SolverRun(speeds[k]); },
      "wrc study dynamics");
  for (std::size_t k = 0; k < speeds.size(); ++k) {
    if (!runs[k]) continue;
    CompareAt(speeds[k], *runs[k]);
    rates.emplace_back(speeds[k], dynamics::MeasureHunting(*runs[k], kSettle).growth_rate);
  }
  // Bisection with the solver inside the bracket its own runs give; then linear in the rate.
  for (int k = 0; k < options_.solver_bisections; ++k) {
    const auto b = GrowthBracket(rates);
    if (!b) break;
    const double mid = 0.5 * (b->first.first + b->second.first);
    const std::optional<Trajectory> run = SolverRun(mid);
    if (!run) break;
    const Row& row = rows_.back();
    rates.emplace_back(mid, row.hunting.growth_rate);
    CompareAt(mid, *run);
  }
  solver_critical_ = ZeroGrowthSpeed(rates);
  // The table's runs at the same speeds, read the same way: the like-for-like comparison when
  // the solver's bracket is wide (its linear interpolation is then coarser than the bisection).
  std::vector<std::pair<double, double>> table_rates;
  for (const Comparison& c : comparisons_) table_rates.emplace_back(c.speed, c.table.growth_rate);
  table_critical_at_solver_speeds_ = ZeroGrowthSpeed(table_rates);
}

// ∂(F_y, M_z)/∂(y, ψ, vy, vyaw) of both sources at y = 0 and at the initial disturbance.
// y: the fit of kWheelWindow, its window taken in each wheel's lateral position on its rail
// (through the roll a wheelset step moves each wheel about 2 % further on the Manchester pair).
// The others: central differences with 1e-4 of creepage (the creep forces bend within about
// 4e-4, hunting at 1 mm lives at about 1e-4), vyaw's step giving 1e-4 at the nominal b.
void TableStudy::Linearise() {
  PrepareSolver();
  const double v = 1000.0 * options_.linear_speed;
  const double r0 = geometry_.nominal_radius;
  dynamics::SolverForces solver = *solver_forces_;
  const dynamics::ForceSource sources[2] = {
      [this](const dynamics::State& s, double speed) { return (*table_forces_)(s, speed); },
      [&solver](const dynamics::State& s, double speed) { return solver(s, speed); }};
  const dynamics::RollCurve* rolls[2] = {&table_forces_->roll_curve(), &solver.roll_curve()};
  WriteRollCsv(*rolls[0], *rolls[1]);
  SampleCentredPath(sources);
  OutputText csv(out_ / "linear.csv");
  csv << "source,y_mm,speed_m_s,dfy_dy,dfy_dyaw,dfy_dvy,dfy_dvyaw,dmz_dy,dmz_dyaw,dmz_dvy,"
         "dmz_dvyaw\n";
  csv.precision(8);
  for (const double y : {0.0, parameters_.initial_y}) {
    for (int k = 0; k < 2; ++k) {
      dynamics::State at;
      at.y = y;
      const double wheel_y = y - r0 * (*rolls[k])(y);
      const double window = 0.5 * (rolls[k]->WheelsetY(wheel_y + kWheelWindow, r0) -
                                   rolls[k]->WheelsetY(wheel_y - kWheelWindow, r0));
      const Eigen::Vector4d h(window, 1e-4, 1e-4 * v, 1e-4 * v / geometry_.semi_spacing);
      const Eigen::Vector4i n(kWheelSamples, 1, 1, 1);
      const Linearisation l{k == 0 ? "table" : "solver", y,
                            dynamics::LinearisedLoads(sources[k], at, v, h, n)};
      csv << l.source << ',' << y << ',' << options_.linear_speed;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 4; ++j) csv << ',' << l.d(i, j);
      csv << '\n';
      linear_.push_back(l);
    }
  }
  csv.Commit();
}

// Both sources' quasi-static roll against y (on the same y grid, kRollCurveStep): the roll
// enters every derivative in y through the contact angles, so a gap there shows in ∂Fy/∂y.
void TableStudy::WriteRollCsv(const dynamics::RollCurve& table,
                              const dynamics::RollCurve& solver) const {
  OutputText csv(out_ / "roll.csv");
  csv << "y_mm,roll_table_rad,roll_solver_rad\n";
  csv.precision(10);
  for (std::size_t i = 0; i < table.y().size(); ++i)
    csv << table.y()[i] << ',' << table.roll()[i] << ',' << solver(table.y()[i]) << '\n';
  csv.Commit();
}

// The wheelset's Fy and Mz of both sources every kPathStep of y over ±kPathHalfWidth: what the
// linearisation's slope is fitted to, sampled finely enough to show the solver's discretisation
// ripple (its period, 0.1-0.5 mm of y, is not resolved by the fit's own samples).
constexpr double kPathStep = 0.01, kPathHalfWidth = 2.0;  // mm

void TableStudy::SampleCentredPath(const dynamics::ForceSource (&sources)[2]) {
  const double v = 1000.0 * options_.linear_speed;
  const int n = static_cast<int>(std::lround(kPathHalfWidth / kPathStep));
  OutputText csv(out_ / "centred.csv");
  csv << "y_mm,fy_table_n,mz_table_nmm,fy_solver_n,mz_solver_nmm\n";
  csv.precision(10);
  for (int i = -n; i <= n; ++i) {
    dynamics::State at;
    at.y = kPathStep * i;
    centred_.y.push_back(at.y);
    csv << at.y;
    for (int k = 0; k < 2; ++k) {
      const dynamics::ContactLoads loads = sources[k](at, v);
      centred_.fy[k].push_back(loads.fy);
      centred_.mz[k].push_back(loads.mz);
      csv << ',' << loads.fy << ',' << loads.mz;
    }
    csv << '\n';
  }
  csv.Commit();
}

namespace {

// Least-squares polynomial of `degree` through (x, f) where |x| <= half_width: coefficients
// from the constant term up, and the RMS of the residual.
std::pair<Eigen::VectorXd, double> FitPolynomial(const std::vector<double>& x,
                                                 const std::vector<double>& f, double half_width,
                                                 int degree) {
  std::vector<int> rows;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::fabs(x[i]) <= half_width + 1e-9) rows.push_back(static_cast<int>(i));
  Eigen::MatrixXd a(rows.size(), degree + 1);
  Eigen::VectorXd b(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (int p = 0; p <= degree; ++p) a(r, p) = std::pow(x[rows[r]], p);
    b(r) = f[rows[r]];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  return {c, std::sqrt((a * c - b).squaredNorm() / static_cast<double>(rows.size()))};
}

}  // namespace

void TableStudy::WriteCentredSummary(std::ostream& md) const {
  if (centred_.y.empty()) return;
  md << "### Along y at centred running\n\nThe wheelset's lateral force every " << kPathStep
     << " mm of y over ±" << kPathHalfWidth
     << " mm (centred.csv, centred.png): its least-squares slope over windows of growing width, "
        "and the RMS of each source's departure from a quintic over the whole range (the "
        "solver's discretisation ripple; the table's piecewise-linear interpolation of its "
        "nodes). A slope the solver resolves no better than its spread over the windows cannot "
        "be matched more closely than that.\n\n| | ±0.25 mm | ±0.5 mm | ±1 mm | ±2 mm | RMS "
        "about a quintic, N |\n|---|---|---|---|---|---|\n";
  for (int k = 0; k < 2; ++k) {
    md << "| ∂Fy/∂y " << (k == 0 ? "table" : "solver") << ", N/mm";
    for (const double w : {0.25, 0.5, 1.0, 2.0})
      md << " | " << Significant(FitPolynomial(centred_.y, centred_.fy[k], w, 1).first(1));
    md << " | " << Fixed(FitPolynomial(centred_.y, centred_.fy[k], kPathHalfWidth, 5).second, 1)
       << " |\n";
  }
  md << "\n![Fy and Mz along y](centred.png)\n\n";
}

void TableStudy::WriteCentredPlot() const {
  if (centred_.y.empty()) return;
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1000,800 font ',10'\nset output 'centred.png'\n"
     << "set datafile separator ','\nset grid\nset key top right\nset xlabel 'y, mm'\n"
     << "set multiplot layout 2,1 title 'The wheelset at centred running, " << options_.linear_speed
     << " m/s (" << table_name_ << ")' noenhanced\n"
     << "set ylabel 'F_y, N'\nplot 'centred.csv' skip 1 using 1:2 with lines lw 2 title 'table', "
        "'' skip 1 using 1:4 with lines title 'solver'\n"
     << "set ylabel 'M_z, N mm'\nplot 'centred.csv' skip 1 using 1:3 with lines lw 2 title "
        "'table', '' skip 1 using 1:5 with lines title 'solver'\nunset multiplot\n";
  Draw("centred", gp.str());
}

void TableStudy::WriteLinearSummary(std::ostream& md) const {
  if (linear_.empty()) return;
  static const char* const kNames[2][4] = {
      {"∂Fy/∂y, N/mm", "∂Fy/∂ψ, N/rad", "∂Fy/∂vy, N·s/mm", "∂Fy/∂vyaw, N·s/rad"},
      {"∂Mz/∂y, N·mm/mm", "∂Mz/∂ψ, N·mm/rad", "∂Mz/∂vy, N·mm·s/mm", "∂Mz/∂vyaw, N·mm·s/rad"}};
  md << "## Linearised contact, table against solver\n\nThe resultant's derivatives at "
     << options_.linear_speed << " m/s (in y the least-squares slope over ±" << kWheelWindow
     << " mm of each wheel's "
     << "lateral position on its rail, " << 2 * kWheelSamples
     << " solves; in ψ, vy and vyaw central differences with 1e-4 of creepage), in linear.csv. "
        "Where the two sources part, so do their hunting "
        "frequency and critical speed.\n\n| derivative | y, mm | table | solver | table / solver "
        "|\n|---|---|---|---|---|\n";
  for (std::size_t k = 0; k + 1 < linear_.size(); k += 2) {
    const Linearisation &t = linear_[k], &s = linear_[k + 1];
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 4; ++j) {
        md << "| " << kNames[i][j] << " | " << Fixed(t.y, 2) << " | " << Significant(t.d(i, j))
           << " | " << Significant(s.d(i, j)) << " | " << Fixed(t.d(i, j) / s.d(i, j), 3) << " |\n";
      }
    }
  }
  md << "\n";
}

// The bogie's linear critical speed on each source's contact linearised at y = 0, and the
// hunting frequency and decay at 60 % and 80 % of the solver's critical speed (both sources at
// the same speeds, so that the frequencies compare like for like).
void TableStudy::AnalyseVehicle() {
  constexpr double kLowest = 1000.0, kHighest = 300000.0;  // mm/s: 1 to 300 m/s
  const double v0 = 1000.0 * options_.linear_speed;
  for (const Linearisation& l : linear_) {
    if (l.y != 0.0) continue;
    dynamics::LinearisedContact contact;
    contact.jacobian = l.d;
    contact.speed = v0;
    VehicleStability s;
    s.source = l.source;
    s.contact = contact;
    s.critical = 1e-3 * dynamics::BogieCriticalSpeed(*vehicle_, contact, kLowest, kHighest);
    vehicle_stability_.push_back(s);
  }
  const double reference = vehicle_stability_.back().critical;  // the solver's
  OutputText csv(out_ / "vehicle.csv");
  csv << "source,critical_speed_m_s,speed_m_s,frequency_hz,real_part_1_s\n";
  csv.precision(8);
  for (VehicleStability& s : vehicle_stability_) {
    for (const double fraction : {0.6, 0.8}) {
      const double v = fraction * reference;
      const std::complex<double> lambda = dynamics::DominantEigenvalue(
          dynamics::BogieLinearSystem(*vehicle_, s.contact, 1000.0 * v));
      s.speeds.push_back(v);
      s.hertz.push_back(dynamics::FrequencyOf(lambda));
      s.damping.push_back(lambda.real());
      csv << s.source << ',' << s.critical << ',' << v << ',' << s.hertz.back() << ','
          << s.damping.back() << '\n';
    }
  }
  csv.Commit();
}

void TableStudy::WriteVehicleSummary(std::ostream& md) const {
  if (vehicle_stability_.size() != 2) return;
  const VehicleStability &t = vehicle_stability_[0], &s = vehicle_stability_[1];
  md << "## The vehicle's bogie, linear stability\n\nThe bogie of `" << options_.vehicle
     << "` (wheel load " << Fixed(vehicle_->WheelLoad(), 0)
     << " N) on the contact of each source linearised at y = 0 (the table above): the speed "
        "where the dominant eigenvalue's real part crosses zero, and that eigenvalue below it "
        "(vehicle.csv).\n\n| | table | solver | table / solver |\n|---|---|---|---|\n"
     << "| linear critical speed, m/s | " << Fixed(t.critical, 2) << " | " << Fixed(s.critical, 2)
     << " | " << Fixed(t.critical / s.critical, 4) << " |\n";
  for (std::size_t k = 0; k < t.speeds.size(); ++k) {
    md << "| hunting frequency at " << Fixed(t.speeds[k], 1) << " m/s, Hz | "
       << Fixed(t.hertz[k], 3) << " | " << Fixed(s.hertz[k], 3) << " | "
       << Fixed(t.hertz[k] / s.hertz[k], 4) << " |\n"
       << "| real part there, 1/s | " << Fixed(t.damping[k], 3) << " | " << Fixed(s.damping[k], 3)
       << " | |\n";
  }
  md << "\n";
}

// ---- quasi-static curving ------------------------------------------------------------------

// The wheels of a curving result in the order a curving table lists them, each with the side
// (WRC_LEFT / WRC_RIGHT) it is on: the outer rail is the one at +y (curving.h).
struct CurvingWheel {
  const char* name;
  int wheelset;
  bool outer;
};
constexpr CurvingWheel kCurvingWheels[4] = {{"leading outer", 0, true},
                                            {"leading inner", 0, false},
                                            {"trailing outer", 1, true},
                                            {"trailing inner", 1, false}};

// A curve's result per source, in the order the tables list them; null where the solver gave none.
std::array<std::pair<const char*, const dynamics::CurvingResult*>, 2> Results(const Curving& c) {
  return {{{"table", &c.table}, {"solver", c.solver ? &*c.solver : nullptr}}};
}

int SideOf(const dynamics::ContactGeometry& g, bool outer) {
  const int plus = g.origin[WRC_RIGHT][0] > 0.0 ? WRC_RIGHT : WRC_LEFT;
  return outer ? plus : 1 - plus;
}

// Each curve of the vehicle file on the table, then on the solver (the curves side by side, one
// thread each: an equilibrium is a few hundred solves).
void TableStudy::CurveVehicle() {
  for (const double radius : vehicle_->curving.radii) {
    Curving c{dynamics::CurveCase::WithDeficiency(radius, vehicle_->curving), {}, {}, ""};
    const dynamics::ForceSource table = [this](const dynamics::State& s, double v) {
      return (*table_forces_)(s, v);
    };
    const dynamics::ForceSource forces[2] = {table, table};
    c.table = dynamics::SolveCurving(*vehicle_, c.curve, forces);
    curving_.push_back(c);
  }
  if (options_.no_solver) return;
  PrepareSolver();
  RunParallel(
      curving_.size(), 2,
      [this](std::size_t k) {
        Curving& c = curving_[k];
        dynamics::SolverForces leading = *solver_forces_, trailing = *solver_forces_;
        const dynamics::ForceSource forces[2] = {
            [&leading](const dynamics::State& s, double v) { return leading(s, v); },
            [&trailing](const dynamics::State& s, double v) { return trailing(s, v); }};
        try {
          c.solver = dynamics::SolveCurving(*vehicle_, c.curve, forces);
        } catch (const InputError& e) {
          c.failure = e.what();
        }
      },
      "wrc study dynamics");
  for (const Curving& c : curving_) {
    if (!c.failure.empty()) {
      std::cerr << "wrc study dynamics: warning: the solver's curving at R = "
                << Fixed(c.curve.radius / 1000.0, 0) << " m stopped: " << c.failure << "\n";
    }
  }
}

void TableStudy::WriteCurvingCsv() const {
  OutputText csv(out_ / "curving.csv");
  csv << "radius_m,speed_m_s,source,converged,residual_n,evaluations,seconds,y1_mm,yaw1_rad,y2_mm,"
         "yaw2_rad,frame_y_mm,frame_yaw_rad,wheel,lateral_y_n,vertical_q_n,y_over_q,t_gamma_n\n";
  csv.precision(9);
  for (const Curving& c : curving_) {
    for (const auto& [source, r] : Results(c)) {
      if (r == nullptr) continue;
      for (const CurvingWheel& w : kCurvingWheels) {
        const dynamics::WheelContact& wc = r->loads[w.wheelset].wheel[SideOf(geometry_, w.outer)];
        csv << c.curve.radius / 1000.0 << ',' << c.curve.speed / 1000.0 << ',' << source << ','
            << r->converged << ',' << r->residual << ',' << r->evaluations << ',' << r->seconds;
        for (int i = 0; i < 6; ++i) csv << ',' << r->position(i);
        csv << ',' << w.name << ',' << wc.lateral << ',' << wc.vertical << ','
            << wc.lateral / wc.vertical << ',' << wc.t_gamma << '\n';
      }
    }
  }
  csv.Commit();
}

void TableStudy::WriteCurvingPlot() const {
  const std::vector<double>& radii = vehicle_->curving.radii;
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1000,800 font ',10'\nset output 'curving.png'\n"
     << "set datafile separator ','\nset grid\nset key outside right\nset logscale x\n"
     << "set xrange [" << 0.5e-3 * *std::min_element(radii.begin(), radii.end()) << ":"
     << 2e-3 * *std::max_element(radii.begin(), radii.end()) << "]\n"
     << "set xlabel 'curve radius, m'\n"
     << "set multiplot layout 2,1 title 'The bogie in steady curves at "
     << Fixed(vehicle_->curving.cant_deficiency, 0) << " mm cant deficiency (" << table_name_
     << "): table (dots) and solver (circles)' noenhanced\n";
  // One panel: a column of curving.csv against the radius for each wheel, both sources.
  const auto panel = [&gp](const std::string& label, int column) {
    gp << "set ylabel '" << label << "'\nplot ";
    for (int w = 0; w < 4; ++w) {
      const std::string name = kCurvingWheels[w].name;
      const std::string pick = "(strcol(14) eq '" + name + "' && strcol(3) eq '";
      gp << (w ? ", " : "") << "'curving.csv' skip 1 using " << pick
         << "table' ? $1 : 1/0):" << column << " with points lc " << w + 1 << " pt 7 ps 1.2 title '"
         << name << "', '' skip 1 using " << pick << "solver' ? $1 : 1/0):" << column
         << " with points lc " << w + 1 << " pt 6 ps 2 notitle";
    }
    gp << "\n";
  };
  panel("Y/Q", 17);
  // Tγ where the table has it (a table made without the t_gamma output gives NaN).
  if (!std::isnan(curving_.front().table.loads[0].wheel[0].t_gamma)) panel("T{/Symbol g}, N", 18);
  gp << "unset multiplot\n";
  Draw("curving", gp.str());
}

void TableStudy::WriteCurvingSummary(std::ostream& md) const {
  if (curving_.empty()) return;
  const dynamics::CurvingSettings& s = vehicle_->curving;
  const double load = vehicle_->WheelLoad();
  md << "## The vehicle's bogie in steady curves\n\nEach curve at " << Fixed(s.cant, 0)
     << " mm cant and " << Fixed(s.cant_deficiency, 0)
     << " mm cant deficiency: the equilibrium of the bogie's lateral and yaw positions with the "
        "contact forces of each source (curving.csv, curving.png). ψ1 is the leading wheelset's "
        "angle of attack; Y is the wheel's lateral force on the rail, positive towards its field "
        "side, Q its vertical force, Tγ its frictional power; differences in Y and Q are in % of "
        "the wheel load ("
     << Fixed(load, 0) << " N), in Tγ in % of the solver's.\n\n"
     << "| R, m | V, m/s | source | y1, mm | ψ1, mrad | y2, mm | ψ2, mrad | frame y, mm | frame ψ, "
        "mrad | evaluations | s |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Curving& c : curving_) {
    for (const auto& [source, r] : Results(c)) {
      if (r == nullptr) continue;
      md << "| " << Fixed(c.curve.radius / 1000.0, 0) << " | " << Fixed(c.curve.speed / 1000.0, 1)
         << " | " << source << (r->converged ? "" : " (not converged)");
      for (int i = 0; i < 6; ++i)
        md << " | " << Fixed(i % 2 ? 1e3 * r->position(i) : r->position(i), 3);
      md << " | " << r->evaluations << " | " << Fixed(r->seconds, 2) << " |\n";
    }
  }
  md << "\n| R, m | wheel | Y table, N | Y solver, N | ΔY, % | Q table, N | Q solver, N | ΔQ, % | "
        "Y/Q table | Y/Q solver | Tγ table, N | Tγ solver, N | ΔTγ, % |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Curving& c : curving_) {
    if (!c.solver) continue;
    for (const CurvingWheel& w : kCurvingWheels) {
      const int side = SideOf(geometry_, w.outer);
      const dynamics::WheelContact& t = c.table.loads[w.wheelset].wheel[side];
      const dynamics::WheelContact& v = c.solver->loads[w.wheelset].wheel[side];
      md << "| " << Fixed(c.curve.radius / 1000.0, 0) << " | " << w.name << " | "
         << Fixed(t.lateral, 0) << " | " << Fixed(v.lateral, 0) << " | "
         << Fixed(100.0 * (t.lateral - v.lateral) / load, 2) << " | " << Fixed(t.vertical, 0)
         << " | " << Fixed(v.vertical, 0) << " | "
         << Fixed(100.0 * (t.vertical - v.vertical) / load, 2) << " | "
         << Fixed(t.lateral / t.vertical, 4) << " | " << Fixed(v.lateral / v.vertical, 4) << " | "
         << Fixed(t.t_gamma, 1) << " | " << Fixed(v.t_gamma, 1) << " | "
         << Fixed(100.0 * (t.t_gamma - v.t_gamma) / v.t_gamma, 2) << " |\n";
    }
  }
  md << "\n![curving](curving.png)\n\n";
}

void TableStudy::WriteSpeedsCsv() const {
  OutputText csv(out_ / "speeds.csv");
  csv << "source,speed_m_s,frequency_hz,growth_rate_1_s,max_abs_y_mm,flags,seconds,steps\n";
  csv.precision(8);
  for (const std::string source : {"table", "solver"}) {
    std::vector<Row> rows;
    for (const Row& r : rows_)
      if (r.source == source && r.failure.empty()) rows.push_back(r);
    std::sort(rows.begin(), rows.end(),
              [](const Row& a, const Row& b) { return a.speed < b.speed; });
    for (const Row& r : rows) {
      csv << r.source << ',' << r.speed << ',' << r.hunting.frequency << ','
          << r.hunting.growth_rate << ',' << r.hunting.max_abs_y << ',' << r.flags << ','
          << r.seconds << ',' << r.steps << '\n';
    }
  }
  csv.Commit();
}

void TableStudy::WriteHuntingPlot() const {
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1000,700 font ',10'\nset output 'hunting.png'\n"
     << "set datafile separator ','\nset grid\nset key left top\n"
     << "set multiplot layout 2,1 title 'Hunting against speed (" << table_name_
     << ")' noenhanced\n"
     << "set xlabel 'V, m/s'\nset ylabel 'growth rate, 1/s'\n"
     << "plot 'speeds.csv' using (strcol(1) eq 'table' ? $2 : 1/0):4 with linespoints pt 7 title "
        "'table', "
        "'' using (strcol(1) eq 'solver' ? $2 : 1/0):4 with points pt 5 ps 1.5 title 'solver', 0 "
        "notitle lc 'black'\n"
     << "set ylabel 'frequency, Hz'\n"
     << "plot 'speeds.csv' using (strcol(1) eq 'table' ? $2 : 1/0):3 with linespoints pt 7 title "
        "'table', "
        "'' using (strcol(1) eq 'solver' ? $2 : 1/0):3 with points pt 5 ps 1.5 title 'solver'\n"
     << "unset multiplot\n";
  Draw("hunting", gp.str());
}

void TableStudy::WriteSummary() const {
  OutputText md(out_ / "README.md");
  const Parameters& p = parameters_;
  if (vehicle_) {
    const dynamics::BogieParameters& b = *vehicle_;
    md << "# The vehicle's bogie on " << table_name_ << "\n\nGenerated by `wrc study dynamics "
       << table_name_ << " --vehicle " << options_.vehicle << MeasuringFlags() << "`. Wheel load "
       << Fixed(b.WheelLoad(), 0) << " N; RK4 at " << 1.0 / b.time_step << " Hz over " << b.duration
       << " s from y = " << b.initial_y
       << " mm of the leading wheelset; its trajectory is the one measured.\n\n";
    WriteLinearSummary(md);
    WriteCentredSummary(md);
    WriteVehicleSummary(md);
    WriteCurvingSummary(md);
    if (RunsTime()) WriteRunsSummary(md);
    md.Commit();
    return;
  }
  md << "# Wheelset dynamics on " << table_name_ << "\n\n"
     << "Generated by `wrc study dynamics " << table_name_
     << (options_.model.empty() ? std::string() : " --model " + options_.model) << MeasuringFlags()
     << "`. Wheelset " << p.mass << " kg, yaw inertia " << p.yaw_inertia << " kg·m², wheel load "
     << p.wheel_load << " N; primary suspension per axlebox " << p.lateral_stiffness
     << " N/mm lateral, " << p.longitudinal_stiffness << " N/mm longitudinal at ±"
     << p.spring_semi_spacing << " mm; RK4 at " << 1.0 / p.time_step << " Hz over " << p.duration
     << " s from y = " << p.initial_y << " mm.\n\n";
  WriteLinearSummary(md);
  WriteCentredSummary(md);
  if (RunsTime()) WriteRunsSummary(md);
  md.Commit();
}

// The runs of both sources: critical speeds by time integration, trajectories, cost.
void TableStudy::WriteRunsSummary(std::ostream& md) const {
  md << "## Critical speed by time integration\n\n| source | critical speed, m/s | how "
        "|\n|---|---|---|\n"
     << "| table | " << Fixed(table_critical_, 2) << " | bisection on V, " << table_bisections_
     << " runs after the sweep, to " << options_.tolerance << " m/s |\n"
     << "| solver | " << Fixed(solver_critical_, 2)
     << " | growth rate interpolated linearly between the solver runs that bracket zero |\n"
     << "| table, read as the solver | " << Fixed(table_critical_at_solver_speeds_, 2)
     << " | the table's runs at the solver's speeds, interpolated the same way |\n"
     << "| difference, solver − table (bisected; read as the solver) | "
     << Fixed(solver_critical_ - table_critical_, 2) << "; "
     << Fixed(solver_critical_ - table_critical_at_solver_speeds_, 2) << " | |\n\n";
  md << "## Trajectories, table against solver\n\n| V, m/s | f table, Hz | f solver, Hz | growth "
        "table, 1/s | growth solver, 1/s | max abs Δy, mm | max abs Δψ, mrad | phase lag, ° | plot "
        "|\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  for (const Comparison& c : comparisons_) {
    const std::string stem = "run_" + Fixed(c.speed, 1) + "ms";
    md << "| " << Fixed(c.speed, 1) << " | " << Fixed(c.table.frequency, 3) << " | "
       << Fixed(c.solver.frequency, 3) << " | " << Fixed(c.table.growth_rate, 3) << " | "
       << Fixed(c.solver.growth_rate, 3) << " | " << Fixed(c.d.max_dy, 3) << " | "
       << Fixed(1e3 * c.d.max_dyaw, 3) << " | " << Fixed(c.d.phase_deg, 1) << " | [" << stem
       << ".png](" << stem << ".png) |\n";
  }
  md << "\n## All runs\n\n| source | V, m/s | frequency, Hz | growth rate, 1/s | max abs y, mm | "
        "table flags | wall s |\n|---|---|---|---|---|---|---|\n";
  std::vector<Row> rows = rows_;
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    return a.source != b.source ? a.source > b.source : a.speed < b.speed;
  });
  for (const Row& r : rows) {
    md << "| " << r.source << " | " << Fixed(r.speed, 2) << " | " << Fixed(r.hunting.frequency, 3)
       << " | " << Fixed(r.hunting.growth_rate, 3) << " | " << Fixed(r.hunting.max_abs_y, 3)
       << " | " << (r.source == "table" ? FlagNames(r.flags) : "") << " | "
       << (r.failure.empty() ? Fixed(r.seconds, 3) : "stopped: " + r.failure) << " |\n";
  }
  md << "\n## Cost\n\nOne thread. CPU time is what the runs cost on one core; the wall time also "
        "counts the time they waited for a core on a shared machine.\n\n"
     << "| source | simulated, s | CPU s | wall s | CPU µs per step | real-time factor (CPU) | "
        "CPU s per simulated s |\n|---|---|---|---|---|---|---|\n";
  for (const auto& [name, cost] :
       {std::pair{"table", table_cost_}, std::pair{"solver", solver_cost_}}) {
    if (cost.steps == 0) continue;
    const double factor = cost.simulated / cost.cpu_seconds;
    md << "| " << name << " | " << Fixed(cost.simulated, 1) << " | " << Fixed(cost.cpu_seconds, 3)
       << " | " << Fixed(cost.seconds, 3) << " | " << Fixed(1e6 * cost.cpu_seconds / cost.steps, 2)
       << " | " << Fixed(factor, factor < 10 ? 4 : 0) << " | "
       << Fixed(cost.cpu_seconds / cost.simulated, 4) << " |\n";
  }
  if (solver_forces_) {
    md << "\nThe solver's roll curve took " << solver_roll_solves_ << " solves ("
       << Fixed(solver_roll_seconds_, 1) << " s). ";
  }
  md << "Roll curve of the table: " << table_forces_->roll_curve().clamped() << " of its "
     << table_forces_->roll_curve().y().size()
     << " points at the end of the roll axis.\n\n![hunting](hunting.png)\n";
}

int TableStudy::Run() {
  fs::create_directories(out_);
  if (!options_.no_solver) {
    Linearise();
    WriteCentredPlot();
  }
  if (vehicle_ && !linear_.empty()) AnalyseVehicle();
  if (vehicle_ && !options_.linear_only && !vehicle_->curving.radii.empty()) {
    CurveVehicle();
    WriteCurvingCsv();
    WriteCurvingPlot();
  }
  if (RunsTime()) {
    SweepTable();
    BisectTable();
    if (!options_.no_solver) RunSolver();
    WriteSpeedsCsv();
    WriteHuntingPlot();
  }
  WriteSummary();
  if (vehicle_stability_.size() == 2) {
    std::cerr << "wrc study dynamics: the vehicle's linear critical speed "
              << Fixed(vehicle_stability_[0].critical, 2) << " m/s (table), "
              << Fixed(vehicle_stability_[1].critical, 2) << " m/s (solver)\n";
  } else if (options_.linear_only) {
    std::cerr << "wrc study dynamics: linearised contact at " << linear_.size() / 2
              << " positions\n";
  }
  if (RunsTime()) {
    std::cerr << "wrc study dynamics: critical speed by time integration "
              << Fixed(table_critical_, 2) << " m/s (table), " << Fixed(solver_critical_, 2)
              << " m/s (solver)\n";
  }
  std::cerr << "wrc study dynamics: wrote " << (out_ / "README.md").string() << "\n";
  return kExitOk;
}

int RunDynamicsStudy(const DynamicsOptions& options) {
  for (const std::string& table : options.tables) {
    const fs::path out = options.tables.size() == 1
                             ? fs::path(options.out)
                             : fs::path(options.out) / fs::path(table).stem();
    TableStudy(options, table, out).Run();
  }
  return kExitOk;
}

}  // namespace

void AddDynamicsStudy(CLI::App& study, int* exit_code) {
  auto* cmd = study.add_subcommand(
      "dynamics", "A wheelset simulated with forces from the table and from full solves");
  auto options = std::make_shared<DynamicsOptions>();
  options->speeds = {10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120};
  cmd->add_option("tables", options->tables, "Tables (TABLE.h5) of one wheel with a z output")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options->out, "Output directory (CSV, PNG, README.md)");
  cmd->add_option("--model", options->model,
                  "Wheelset parameter file (TOML; default: the shipped "
                  "tables/wheelset_dynamics.toml)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--speeds", options->speeds, "Speeds of the table sweep, m/s")
      ->delimiter(',')
      ->check(GreaterThanZero());
  cmd->add_option("--solver-speeds", options->solver_speeds,
                  "Speeds of the solver runs, m/s (default: 0.8 and 1.2 times the table's "
                  "critical speed)")
      ->delimiter(',')
      ->check(GreaterThanZero());
  cmd->add_option("--solver-bisections", options->solver_bisections,
                  "Solver runs that narrow its critical speed")
      ->check(ZeroOrMore());
  cmd->add_flag("--no-solver", options->no_solver, "Table runs only");
  cmd->add_flag("--linear-only", options->linear_only,
                "Only the linearised contact of both sources (linear.csv, README.md)");
  cmd->add_flag("--no-runs", options->no_runs,
                "No time integrations: the linearised contact, the stability and the curves");
  cmd->add_option("--solver-elements", options->solver_elements,
                  "Element size (dx = ds, mm) of the solver source in place of the table's own: "
                  "how far the reference itself moves with its discretisation")
      ->check(GreaterThanZero());
  cmd->add_option("--linear-speed", options->linear_speed, "Speed of the linearised contact, m/s")
      ->check(GreaterThanZero())
      ->capture_default_str();
  cmd->add_option("--interpolation", options->interpolation,
                  "The table's interpolation between its nodes: linear or cubic")
      ->check(CLI::IsMember({"linear", "cubic"}))
      ->capture_default_str();
  cmd->add_option("--vehicle", options->vehicle,
                  "Vehicle file (TOML, e.g. the shipped tables/manchester_vehicle.toml): its "
                  "bogie in place of the wheelset, at the vehicle's wheel load: the linear "
                  "critical speed and hunting frequency on each source's linearised contact, "
                  "and the runs on both sources")
      ->check(CLI::ExistingFile);
  OnRun(cmd, exit_code, "wrc study dynamics", [options]() { return RunDynamicsStudy(*options); });
}

}  // namespace wrc::cli
