// Error-driven node placement: the split decisions on a synthetic function with a kink, a
// small real scene refined against exact solves, and resumed refinements equal to
// uninterrupted ones to the bit.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/common/numbers.h"
#include "generator/refine.h"
#include "generator/table_data.h"
#include "tests/generator/generator_test_util.h"
#include "wrc/core/scene.h"
#include "wrc/core/wheelrail.h"
#include "wrc/generator/generator.h"
#include "wrc/runtime.hpp"

namespace wrc::test {
namespace {

// Lateral force saturating at |yaw| = 1.5 mrad (a kink, as creep saturation makes one), plus
// terms linear in y that multilinear interpolation reproduces exactly.
constexpr double kKnee = 0.0015;
std::vector<double> Synthetic(const std::vector<double>& p) {
  const double y = p[0], yaw = p[1];
  const double fy = 3000.0 * std::clamp(yaw / kKnee, -1.0, 1.0) * (1.0 + 0.02 * y);
  return {200.0 * y, fy, 10000.0};
}

Scene SyntheticScene(const fs::path& dir) {
  const std::string table =
      "axes = [\"y\", \"yaw\"]\ny = {from = 0.0, to = 5.0, count = 3}\n"
      "yaw = {from = -0.01, to = 0.01, count = 5}\noutputs = [\"fx\", \"fy\", \"fz\"]\n"
      "[table.refine]\ntarget = 0.005\nsamples = 8\nmax_points = 5000\n";
  return ParseScene(TinyScene(table), dir, "synthetic.toml");
}

using Function = std::vector<double> (*)(const std::vector<double>&);

PointResult Exact(Function f, const std::vector<double>& point) {
  PointResult r;
  r.status = PointStatus::kOk;
  r.values = f(point);
  return r;
}

gen::TableData Fill(const std::vector<SceneAxis>& axes, Function f = Synthetic) {
  const std::size_t ny = axes[0].values.size(), nyaw = axes[1].values.size();
  gen::TableData data(ny * nyaw, 3);
  for (std::size_t i = 0; i < ny; ++i) {
    for (std::size_t j = 0; j < nyaw; ++j) {
      data.Store(i * nyaw + j, Exact(f, {axes[0].values[i], axes[1].values[j]}));
    }
  }
  return data;
}

std::vector<PointResult> Probes(const Scene& scene, Function f) {
  std::vector<PointResult> probes;
  if (!scene.refine->slope) return probes;
  for (const auto& point : gen::SlopeProbes(*scene.refine->slope)) {
    probes.push_back(Exact(f, point));
  }
  return probes;
}

// The refinement's passes on a function in place of the solver, until a pass adds no node.
std::vector<SceneAxis> RefineOn(const Scene& scene, Function f) {
  std::vector<SceneAxis> axes = scene.axes;
  const std::vector<PointResult> probes = Probes(scene, f);
  for (int pass = 0; pass < 40; ++pass) {
    const gen::TableData data = Fill(axes, f);
    const std::vector<gen::RefineSample> samples =
        gen::DrawRefineSamples(axes, *scene.refine, pass);
    std::vector<PointResult> results;
    for (const gen::RefineSample& s : samples) results.push_back(Exact(f, s.point));
    const gen::RefineDecision decision =
        gen::DecideRefinement(scene, axes, data, samples, results, probes);
    if (decision.next[1].values.size() == axes[1].values.size() &&
        decision.next[0].values.size() == axes[0].values.size()) {
      break;
    }
    axes = decision.next;
  }
  return axes;
}

// Largest and 95th-percentile |fy error| at random points (fixed seed).
std::pair<double, double> FyErrors(const std::vector<SceneAxis>& axes, const gen::TableData& data) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> y(0.0, 5.0), yaw(-0.01, 0.01);
  std::vector<double> errors;
  for (int k = 0; k < 2000; ++k) {
    const std::vector<double> p = {y(rng), yaw(rng)};
    errors.push_back(std::fabs(gen::InterpolateLinear(axes, data, 1, p) - Synthetic(p)[1]));
  }
  std::sort(errors.begin(), errors.end());
  return {errors.back(), errors[errors.size() * 95 / 100]};
}

TEST(Refine, SplitsWhereTheKinkIsAndNowhereElse) {
  ScratchDir dir("refine_synthetic");
  const Scene scene = SyntheticScene(dir.path());
  std::vector<SceneAxis> axes = scene.axes;
  const auto [start_max, start_p95] = FyErrors(axes, Fill(axes));
  axes = RefineOn(scene, Synthetic);
  const auto [end_max, end_p95] = FyErrors(axes, Fill(axes));
  // The target is 0.5 % of the 10 kN load: 50 N at interval midpoints. Away from midpoints
  // the error is smaller, so p95 stays under it; the largest error sits in the two cells with
  // the kink, whose sides are at most min_step·2 wide (20/512 mrad... here 0.02/512 rad).
  EXPECT_LT(end_p95, 50.0) << "start p95 " << start_p95;
  EXPECT_LT(end_max, 50.0);
  EXPECT_GT(start_max, 20.0 * end_max);
  // fy and fx are linear in y at fixed yaw, so y keeps its three nodes.
  EXPECT_EQ(axes[0].values.size(), 3u);
  // The smallest yaw steps lie next to the knees, the largest where fy is flat.
  const std::vector<double>& yaw = axes[1].values;
  double smallest = 1.0, at = 0.0, largest = 0.0;
  for (std::size_t i = 1; i < yaw.size(); ++i) {
    const double h = yaw[i] - yaw[i - 1];
    if (h < smallest) {
      smallest = h;
      at = 0.5 * (yaw[i] + yaw[i - 1]);
    }
    largest = std::max(largest, h);
  }
  EXPECT_NEAR(std::fabs(at), kKnee, 4.0 * smallest);
  EXPECT_GE(largest, 0.005 - 1e-12);  // the flat outer intervals are never split
}

// Creep saturation without a kink: smooth everywhere, curved around yaw = 0 over a few mrad.
std::vector<double> Saturating(const std::vector<double>& p) {
  const double y = p[0], yaw = p[1];
  return {200.0 * y, 3000.0 * std::tanh(yaw / 0.003) * (1.0 + 0.02 * y), 10000.0};
}

Scene SaturatingScene(const fs::path& dir, const std::string& interpolation) {
  const std::string table =
      "axes = [\"y\", \"yaw\"]\ny = {from = 0.0, to = 5.0, count = 3}\n"
      "yaw = {from = -0.01, to = 0.01, count = 5}\noutputs = [\"fx\", \"fy\", \"fz\"]\n"
      "[table.refine]\ntarget = 0.0005\nsamples = 8\nmax_points = 5000\ninterpolation = \"" +
      interpolation + "\"\n";
  return ParseScene(TinyScene(table), dir, "saturating.toml");
}

// |fy error| at random points (fixed seed) of a table of `data` on `axes` read by the runtime.
std::vector<double> RuntimeFyErrors(const Scene& scene, const std::vector<SceneAxis>& axes,
                                    const gen::TableData& data, Interpolation mode,
                                    const fs::path& path) {
  Scene refined = scene;
  refined.axes = axes;
  gen::TableProvenance provenance;
  provenance.rail_sha256 = provenance.wheel_sha256 = std::string(64, '0');
  provenance.created = gen::IsoTimestampUtc();
  gen::WriteTableFile(path, refined, data, provenance);
  Table table(path.string());
  table.set_interpolation(mode);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> y(0.0, 5.0), yaw(-0.01, 0.01);
  std::vector<double> errors;
  for (int k = 0; k < 2000; ++k) {
    const std::vector<double> p = {y(rng), yaw(rng)};
    errors.push_back(std::fabs(table.eval(p)[1] - Saturating(p)[1]));
  }
  std::sort(errors.begin(), errors.end());
  return errors;
}

// The target measured for the interpolation the table will be read with: for cubic lookups the
// midpoints are judged by the runtime's cubic, whose error falls as h⁴ where linear's falls as
// h², so the same 5 N target (0.05 % of the load) takes under half the yaw nodes; read by the
// runtime each table meets it at random points (not midpoints: within a few per cent of it).
TEST(Refine, ACubicTargetTakesFewerNodesForTheSameError) {
  ScratchDir dir("refine_cubic");
  const Scene linear = SaturatingScene(dir.path(), "linear");
  const Scene cubic = SaturatingScene(dir.path(), "cubic");
  ASSERT_EQ(cubic.refine->interpolation, RefineSettings::Interpolation::kCubic);
  const std::vector<SceneAxis> linear_axes = RefineOn(linear, Saturating);
  const std::vector<SceneAxis> cubic_axes = RefineOn(cubic, Saturating);
  const std::size_t linear_nodes = linear_axes[1].values.size();
  const std::size_t cubic_nodes = cubic_axes[1].values.size();
  EXPECT_LT(2 * cubic_nodes, linear_nodes) << cubic_nodes << " against " << linear_nodes;
  const std::vector<double> linear_errors =
      RuntimeFyErrors(linear, linear_axes, Fill(linear_axes, Saturating), Interpolation::kLinear,
                      dir / "linear.h5");
  const std::vector<double> cubic_errors = RuntimeFyErrors(
      cubic, cubic_axes, Fill(cubic_axes, Saturating), Interpolation::kCubic, dir / "cubic.h5");
  EXPECT_LT(linear_errors.back(), 1.05 * 5.0);
  EXPECT_LT(cubic_errors.back(), 1.05 * 5.0);
  // Read linearly, the cubic table's nodes are too few: the target is the interpolation's.
  const std::vector<double> misread = RuntimeFyErrors(
      cubic, cubic_axes, Fill(cubic_axes, Saturating), Interpolation::kLinear, dir / "misread.h5");
  EXPECT_GT(misread.back(), 2.0 * 5.0);
  EXPECT_THROW(SaturatingScene(dir.path(), "spline"), InputError);
}

// A lateral force that bends sharply around centred running (as the gravitational and creep
// terms do where the contact point jumps), gently elsewhere; linear in yaw.
constexpr double kBend = 0.4;  // mm
std::vector<double> Bend(const std::vector<double>& p) {
  const double y = p[0], yaw = p[1];
  return {200.0 * y, (100.0 * y + 300.0 * std::tanh(y / kBend)) * (1.0 + 10.0 * yaw), 10000.0};
}

Scene BendScene(const fs::path& dir, const std::string& slope) {
  const std::string table =
      "axes = [\"y\", \"yaw\"]\ny = {from = -5.0, to = 5.0, count = 3}\n"
      "yaw = {from = -0.01, to = 0.01, count = 5}\noutputs = [\"fx\", \"fy\", \"fz\"]\n"
      "[table.refine]\ntarget = 0.05\nsamples = 8\nmax_points = 5000\n" +
      slope;
  return ParseScene(TinyScene(table), dir, "bend.toml");
}

TEST(Refine, ASlopeTargetPlacesNodesAtTheStatePlusAndMinusItsStep) {
  ScratchDir dir("refine_slope");
  // 5 % of the load pointwise: the three starting y nodes already meet it (150 N at ±2.5 mm).
  const Scene plain = BendScene(dir.path(), "");
  EXPECT_EQ(RefineOn(plain, Bend)[0].values.size(), 3u);
  const Scene scene =
      BendScene(dir.path(), "[table.refine.slope]\ntarget = 0.01\nstep = {y = 0.1}\n");
  ASSERT_TRUE(scene.refine->slope);
  const std::vector<SceneAxis> axes = RefineOn(scene, Bend);
  // The table's central difference at y = 0 against the function's own (an independent
  // computation, not the refinement's): within the 1 % target.
  const gen::TableData data = Fill(axes, Bend);
  const double h = 0.1;
  const double table = (gen::InterpolateLinear(axes, data, 1, {h, 0.0}) -
                        gen::InterpolateLinear(axes, data, 1, {-h, 0.0})) /
                       (2.0 * h);
  const double exact = (Bend({h, 0.0})[1] - Bend({-h, 0.0})[1]) / (2.0 * h);
  EXPECT_NEAR(table, exact, 0.01 * std::fabs(exact)) << axes[0].values.size() << " y nodes";
  // Before: the secant across [0, 5 mm], a fifth of the slope.
  EXPECT_LT((Bend({5.0, 0.0})[1] - Bend({-5.0, 0.0})[1]) / 10.0, 0.25 * exact);
  // The nodes it added: the state ± step, nothing else on y.
  EXPECT_EQ(axes[0].values, (std::vector<double>{-5.0, -h, 0.0, h, 5.0}));
  EXPECT_EQ(axes[1].values.size(), 5u);  // linear in yaw: the yaw slope is exact
  EXPECT_LE(gen::SlopeErrors(scene, axes, data, Probes(scene, Bend))[0], 1.0);
}

// Bend with a ripple of ±3 N and period 0.09 mm in fy, as a solver's discretisation leaves one.
std::vector<double> RippledBend(const std::vector<double>& p) {
  std::vector<double> v = Bend(p);
  v[1] += 3.0 * std::sin(2.0 * wrc::kPi * p[0] / 0.09);
  return v;
}

// The least-squares slope in y of output k at yaw 0 through the samples ±k·h, k = 1 … n.
template <typename F>
double FittedSlope(F f, int n, double h) {
  double num = 0.0, den = 0.0;
  for (int k = 1; k <= n; ++k) {
    const double x = k * h;
    num += x * (f(x) - f(-x));
    den += 2.0 * x * x;
  }
  return num / den;
}

TEST(Refine, AWindowedSlopeTargetMatchesTheFittedSlopeAcrossARipple) {
  ScratchDir dir("refine_window");
  const Scene scene = BendScene(
      dir.path(), "[table.refine.slope]\ntarget = 0.01\nstep = {y = 0.05}\nwindow = {y = 0.5}\n");
  ASSERT_EQ(scene.refine->slope->SamplesPerSide(0), 10);
  const std::vector<SceneAxis> axes = RefineOn(scene, RippledBend);
  const gen::TableData data = Fill(axes, RippledBend);
  // Fitted independently of the refinement: the table's and the function's slopes agree
  // within the 1 % target.
  const double table = FittedSlope(
      [&](double y) {
        return gen::InterpolateLinear(axes, data, 1, {y, 0.0});
      },
      10, 0.05);
  const double exact = FittedSlope([](double y) { return RippledBend({y, 0.0})[1]; }, 10, 0.05);
  EXPECT_NEAR(table, exact, 0.01 * std::fabs(exact)) << axes[0].values.size() << " y nodes";
  // The nodes it added are samples of the window: multiples of the step within ±0.5 mm.
  for (const double y : axes[0].values) {
    if (std::fabs(y) == 5.0 || y == 0.0) continue;
    EXPECT_LE(std::fabs(y), 0.5 + 1e-12) << y;
    EXPECT_NEAR(y / 0.05, std::round(y / 0.05), 1e-9) << y;
  }
  // Fewer than the 21 samples: the fit does not need every one.
  EXPECT_LT(axes[0].values.size(), 3u + 20u);
}

TEST(Refine, ASlopeTargetNeedsItsStateOnTheNodes) {
  ScratchDir dir("refine_slope_bad");
  try {
    BendScene(dir.path(), "[table.refine.slope]\nat = {y = 0.3}\n");
    FAIL() << "accepted a slope state between nodes";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("table.refine.slope.at"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("y = 0.3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(BendScene(dir.path(), "[table.refine.slope]\nstep = {y = 6.0}\n"), InputError);
  // A window of a whole number of steps, inside the axis, on a targeted axis.
  for (const char* bad :
       {"step = {y = 0.1}\nwindow = {y = 0.33}\n", "step = {y = 1.0}\nwindow = {y = 6.0}\n",
        "axes = [\"yaw\"]\nwindow = {y = 1.0}\n"}) {
    try {
      BendScene(dir.path(), std::string("[table.refine.slope]\n") + bad);
      FAIL() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("table.refine.slope.window"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(BendScene(dir.path(), "[table.refine.slope]\nstpe = {y = 1.0}\n"), InputError);
  EXPECT_THROW(BendScene(dir.path(), "[table.refine.slope]\naxes = [\"x\"]\n"), InputError);
}

// A 1-D refinement of the Manchester pair across the tread-to-flange transition.
std::string RealTable(const std::string& refine) {
  return "axes = [\"y\"]\ny = {from = 2.0, to = 8.0, count = 3}\n"
         "outputs = [\"fx\", \"fy\", \"fz\", \"n_patches\", \"z\"]\n[table.refine]\n" +
         refine;
}

GenerateOptions Quiet(const fs::path& output) {
  GenerateOptions options;
  options.output = output;
  options.threads = 2;
  options.progress = ProgressMode::kOff;
  return options;
}

// |fy error| / load at random points against exact solves, through the runtime.
double MaxRelativeError(const Scene& scene, const fs::path& table_path,
                        Interpolation mode = Interpolation::kLinear) {
  Table table(table_path.string());
  table.set_interpolation(mode);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> y(2.0, 8.0);
  double worst = 0.0;
  for (int k = 0; k < 12; ++k) {
    const double point = y(rng);
    const WheelRailResult exact = SolveWheelRail(CaseAtPoint(scene, {point}));
    const std::vector<double> looked_up = table.eval(std::vector<double>{point});
    worst = std::max(worst, std::fabs(looked_up[1] - exact.force_T(1)) / 10000.0);
  }
  return worst;
}

TEST(Refine, RealSceneGetsCloserToTheSolver) {
  ScratchDir dir("refine_real");
  const fs::path coarse_scene =
      WriteFile(dir / "coarse.toml", TinyScene(RealTable("max_passes = 0\n")));
  const fs::path fine_scene =
      WriteFile(dir / "fine.toml", TinyScene(RealTable("target = 0.005\nsamples = 1\n")));
  const Scene coarse = LoadScene(coarse_scene), fine = LoadScene(fine_scene);
  ASSERT_TRUE(GenerateTable(coarse, Quiet(dir / "coarse.h5")).complete);
  const GenerateSummary summary = GenerateTable(fine, Quiet(dir / "fine.h5"));
  ASSERT_TRUE(summary.complete);
  EXPECT_GT(summary.axes[0].values.size(), 3u);
  EXPECT_FALSE(fs::exists(dir / "fine.h5.refine"));  // the work directory is cleaned up
  const double before = MaxRelativeError(coarse, dir / "coarse.h5");
  const double after = MaxRelativeError(fine, dir / "fine.h5");
  EXPECT_LT(after, 0.25 * before) << before << " → " << after;
  EXPECT_LT(after, 0.02);  // twice the midpoint target: random points are not midpoints
  // The table says how it was refined.
  Table table((dir / "fine.h5").string());
  EXPECT_NE(table.attribute("refine_target").find("\"load_fraction\":0.005"), std::string::npos);
  EXPECT_NE(table.attribute("refine_stop").find("target met"), std::string::npos);
}

// Across the tread-to-flange transition: refined for cubic lookups and read cubically, as close
// to exact solves as a linear table read linearly is required to be. (At the jump the limiter
// makes cubic lookups about as good as linear ones, so here they take as many nodes: 59 against
// 57; the gain is on smooth stretches.)
TEST(Refine, RealSceneRefinedForCubicLookups) {
  ScratchDir dir("refine_real_cubic");
  const std::string refine = "target = 0.005\nsamples = 1\n";
  const Scene cubic = LoadScene(
      WriteFile(dir / "cubic.toml", TinyScene(RealTable(refine + "interpolation = \"cubic\"\n"))));
  const GenerateSummary cubic_run = GenerateTable(cubic, Quiet(dir / "cubic.h5"));
  ASSERT_TRUE(cubic_run.complete);
  EXPECT_GT(cubic_run.axes[0].values.size(), 3u);
  EXPECT_LT(MaxRelativeError(cubic, dir / "cubic.h5", Interpolation::kCubic), 0.02);
  Table table((dir / "cubic.h5").string());
  EXPECT_NE(table.attribute("refine_target").find("\"interpolation\":\"cubic\""),
            std::string::npos);
  EXPECT_NE(table.attribute("refine_estimated_error").find("\"p95\""), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "cubic.h5.refine"));  // its check table went with it
}

TEST(Refine, RealSceneMeetsItsSlopeTarget) {
  ScratchDir dir("refine_real_slope");
  const fs::path path = WriteFile(
      dir / "slope.toml",
      TinyScene(RealTable("target = 0.05\nsamples = 1\n[table.refine.slope]\nat = {y = 5.0}\n"
                          "step = {y = 0.25}\n")));
  const Scene scene = LoadScene(path);
  const GenerateSummary summary = GenerateTable(scene, Quiet(dir / "slope.h5"));
  ASSERT_TRUE(summary.complete);
  // The table's central difference of fy at y = 5 mm against exact solves (through the
  // runtime, not the refinement's own bookkeeping), within the 1 % target.
  Table table((dir / "slope.h5").string());
  const auto fy = [&](double y) { return table.eval(std::vector<double>{y})[1]; };
  const auto exact = [&](double y) { return SolveWheelRail(CaseAtPoint(scene, {y})).force_T(1); };
  const double table_slope = (fy(5.25) - fy(4.75)) / 0.5;
  const double solver_slope = (exact(5.25) - exact(4.75)) / 0.5;
  EXPECT_NEAR(table_slope, solver_slope, 0.01 * std::fabs(solver_slope));
  const std::string estimate = table.attribute("refine_estimated_error");
  EXPECT_NE(estimate.find("\"slope\":{\"y\":"), std::string::npos) << estimate;
}

// The share of states within the target, estimated at random states independently of the
// refinement's own check (another seed, through the runtime): the p-quantile of |fy error| / load.
double QuantileRelativeError(const Scene& scene, const fs::path& table_path, double q) {
  Table table(table_path.string());
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> y(2.0, 8.0);
  std::vector<double> errors;
  for (int k = 0; k < 400; ++k) {
    const double point = y(rng);
    const WheelRailResult exact = SolveWheelRail(CaseAtPoint(scene, {point}));
    const std::vector<double> looked_up = table.eval(std::vector<double>{point});
    errors.push_back(std::fabs(looked_up[1] - exact.force_T(1)) / 10000.0);
  }
  std::sort(errors.begin(), errors.end());
  return errors[static_cast<std::size_t>(q * errors.size())];
}

// Across the tread-to-flange transition, whose jump no interval ever meets the target across:
// the midpoint rule (quantile 1) splits down to the smallest step there; the quantile stop ends
// once 95 % of the states are within the target, with fewer nodes, and an independent sample
// agrees. With --keep-passes every pass's grid is a table of its own.
TEST(Refine, AQuantileStopMeetsTheShareOfStatesWithFewerNodes) {
  ScratchDir dir("refine_quantile");
  const std::string refine = "target = 0.005\nsamples = 1\n";
  const Scene quantile = LoadScene(WriteFile(dir / "quantile.toml", TinyScene(RealTable(refine))));
  const Scene midpoints = LoadScene(
      WriteFile(dir / "midpoints.toml", TinyScene(RealTable(refine + "quantile = 1.0\n"))));
  ASSERT_EQ(quantile.refine->quantile, 0.95);
  GenerateOptions options = Quiet(dir / "quantile.h5");
  options.keep_passes = true;
  const GenerateSummary by_quantile = GenerateTable(quantile, options);
  const GenerateSummary by_midpoints = GenerateTable(midpoints, Quiet(dir / "midpoints.h5"));
  ASSERT_TRUE(by_quantile.complete && by_midpoints.complete);
  EXPECT_LT(by_quantile.points, by_midpoints.points);
  EXPECT_LE(QuantileRelativeError(quantile, dir / "quantile.h5", 0.95), 0.005);
  Table table((dir / "quantile.h5").string());
  EXPECT_NE(table.attribute("refine_stop").find("target met: 95 % of 1000 random states"),
            std::string::npos)
      << table.attribute("refine_stop");
  EXPECT_EQ(Table((dir / "midpoints.h5").string()).attribute("refine_stop").find("random"),
            std::string::npos);
  // Every pass kept, with its grid's points; CPU time grows pass by pass.
  ASSERT_GE(by_quantile.passes.size(), 2u);
  for (std::size_t p = 0; p < by_quantile.passes.size(); ++p) {
    const Table pass((dir / ("quantile.h5.pass" + std::to_string(p) + ".h5")).string());
    EXPECT_EQ(pass.axis_values(0).size(), by_quantile.passes[p].points) << p;
    if (p > 0) {
      EXPECT_GT(by_quantile.passes[p].cpu_seconds, by_quantile.passes[p - 1].cpu_seconds);
    }
  }
  EXPECT_EQ(
      Table((dir / ("quantile.h5.pass" + std::to_string(by_quantile.passes.size() - 1) + ".h5"))
                .string())
          .axis_values(0),
      table.axis_values(0));
  EXPECT_GT(by_quantile.cpu_seconds, 0.0);
}

TEST(Refine, ResumedRunsGiveTheSameBits) {
  ScratchDir dir("refine_resume");
  const fs::path scene_path = WriteFile(
      dir / "scene.toml",
      TinyScene("axes = [\"yaw\", \"y\"]\nyaw = [0.0, 0.004]\ny = {from = 2.0, to = 8.0, count = "
                "3}\noutputs = [\"fx\", \"fy\", \"fz\", \"z\"]\n[table.refine]\ntarget = "
                "0.01\nsamples = 2\nmax_passes = 3\n"));
  const Scene scene = LoadScene(scene_path);
  ASSERT_TRUE(GenerateTable(scene, Quiet(dir / "whole.h5")).complete);
  // Stopped inside grid passes and inside the midpoint solves, then resumed until done.
  for (std::size_t budget : {5u, 9u, 17u}) {
    const fs::path output = dir / ("resumed" + std::to_string(budget) + ".h5");
    GenerateOptions options = Quiet(output);
    options.max_points = budget;
    GenerateSummary summary = GenerateTable(scene, options);
    int runs = 1;
    while (!summary.complete && runs < 50) {
      EXPECT_TRUE(summary.interrupted);
      EXPECT_TRUE(fs::exists(fs::path(output.string() + ".refine")));
      options.resume = true;
      summary = GenerateTable(scene, options);
      ++runs;
    }
    ASSERT_TRUE(summary.complete);
    EXPECT_GT(runs, 2) << "budget " << budget << " should interrupt more than once";
    ExpectIdenticalTables(dir / "whole.h5", output);
  }
  // Without --resume, an interrupted refinement is not thrown away.
  GenerateOptions options = Quiet(dir / "again.h5");
  options.max_points = 3;
  ASSERT_FALSE(GenerateTable(scene, options).complete);
  options.max_points = 0;
  EXPECT_THROW(GenerateTable(scene, options), InputError);
}

}  // namespace
}  // namespace wrc::test
