// Scene files (docs/reference/case-files.md, scenes): a case plus [table]. The table is checked
// completely before any point is solved, because a mistake found hours into `wrc generate` wastes
// the whole run.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <tuple>

#include "core/io/case_parser.h"
#include "wrc/core/errors.h"
#include "wrc/core/scene.h"
#include "wrc/table_limits.h"

namespace wrc {
namespace io {
namespace {

// Guards against typos such as step = 1e-9 that would ask for billions of solves.
constexpr std::size_t kMaxValuesPerAxis = 1'000'000;
constexpr double kMaxPointCount = 1e9;

// A step range includes `to` when it lies this close (relative to the step) to a grid value.
constexpr double kStepEndTolerance = 1e-9;

// The names a scene may use, in the registry's order (wrc/quantities.h).
std::vector<std::string_view> SceneAxisNames() {
  std::vector<std::string_view> names;
  for (const StateQuantity& q : kStateQuantities) {
    if (q.scene_axis) names.push_back(q.name);
  }
  return names;
}

std::vector<std::string_view> SceneOutputNames() {
  std::vector<std::string_view> names;
  for (const OutputQuantity& q : kOutputQuantities) names.push_back(q.name);
  return names;
}

std::string QuotedList(const std::vector<std::string_view>& names) {
  std::string joined;
  for (std::string_view name : names) {
    if (!joined.empty()) joined += ", ";
    joined += "\"" + std::string(name) + "\"";
  }
  return joined;
}

/// Why `value` cannot be used for axis `name`; empty when it can. Shared by the file check
/// and CaseAtPoint so that sampled points obey the same rules as the grid.
std::string AxisValueProblem(std::string_view name, double value) {
  if (!std::isfinite(value)) return "must be a finite number";
  if (std::abs(value) > WRC_AXIS_MAX_MAGNITUDE) return "is beyond the ±1e30 a table axis may hold";
  if (name == "mu" && value < 0.0) return "must not be negative";
  if (name == "fz" && !(value > 0.0)) return "must be positive";
  return {};
}

/// The [state] / [friction] keys that an axis replaces; giving both is ambiguous.
std::vector<std::pair<std::string_view, std::string_view>> KeysReplacedByAxis(
    std::string_view axis) {
  if (axis == "z" || axis == "fz") return {{"state", "z"}, {"state", "fz"}};
  if (axis == "spin" || axis == "omega") return {{"state", "spin"}, {"state", "omega"}};
  if (axis == "mu") return {{"friction", "mu"}, {"friction", "alpha_deg"}};
  if (axis == "y_wheel") return {{"state", "y"}};
  return {{"state", axis}};
}

std::vector<double> ReadExplicitValues(const SourceFile& file, const toml::array& array,
                                       std::string_view axis, const std::string& path) {
  if (array.empty()) file.Fail(&array, path, "must list at least one value");
  std::vector<double> values;
  for (std::size_t i = 0; i < array.size(); ++i) {
    const toml::node& element = *array.get(i);
    const std::string element_path = path + "[" + std::to_string(i) + "]";
    const double value = ReadNumber(file, element, element_path);
    const std::string problem = AxisValueProblem(axis, value);
    if (!problem.empty()) file.Fail(&element, element_path, problem);
    if (!values.empty() && !(value > values.back())) {
      file.Fail(&element, element_path,
                "axis values must be strictly ascending (previous value " +
                    DescribeValue(*array.get(i - 1)) + ")");
    }
    if (!values.empty() && !AxisStepIsResolvable(values.back(), value)) {
      file.Fail(&element, element_path,
                "is too close to the previous value " + DescribeValue(*array.get(i - 1)) +
                    " for a table axis (steps of at least 1e-30 and 1e-9 of the values)");
    }
    values.push_back(value);
  }
  return values;
}

std::vector<double> ReadRangeValues(const SourceFile& file, const toml::table& range,
                                    std::string_view axis, const std::string& path) {
  const std::vector<std::string_view> range_keys = {"from", "to", "step", "count"};
  for (const auto& [key, node] : range) {
    if (std::find(range_keys.begin(), range_keys.end(), key.str()) == range_keys.end()) {
      std::string problem = "unknown key";
      const std::string suggestion = SuggestName(key.str(), range_keys);
      if (!suggestion.empty()) problem += " (did you mean " + path + "." + suggestion + "?)";
      problem += "; a range has from, to and either step or count";
      file.Fail(&node, path + "." + std::string(key.str()), problem);
    }
  }
  const toml::node* from_node = range.get("from");
  const toml::node* to_node = range.get("to");
  const toml::node* step_node = range.get("step");
  const toml::node* count_node = range.get("count");
  if (from_node == nullptr) file.FailAt(range.source().begin, path + ".from", "missing");
  if (to_node == nullptr) file.FailAt(range.source().begin, path + ".to", "missing");
  if ((step_node == nullptr) == (count_node == nullptr)) {
    file.FailAt(range.source().begin, path,
                "give exactly one of " + path + ".step and " + path + ".count");
  }
  const double from = ReadNumber(file, *from_node, path + ".from");
  const double to = ReadNumber(file, *to_node, path + ".to");
  // Values ascend, so the limits decide whether all of them are allowed.
  for (const auto& [limit, limit_node, limit_key] :
       {std::tuple{from, from_node, ".from"}, std::tuple{to, to_node, ".to"}}) {
    const std::string problem = AxisValueProblem(axis, limit);
    if (!problem.empty()) file.Fail(limit_node, path + limit_key, problem);
  }
  if (to < from) {
    file.Fail(to_node, path + ".to",
              "empty range: must not be less than " + path +
                  ".from = " + DescribeValue(*from_node) + " (axis values ascend)");
  }

  std::vector<double> values;
  if (step_node != nullptr) {
    const double step = ReadNumber(file, *step_node, path + ".step");
    if (!(step > 0.0)) file.Fail(step_node, path + ".step", "must be positive");
    const double intervals = (to - from) / step;
    if (intervals + 1.0 > static_cast<double>(kMaxValuesPerAxis)) {
      file.Fail(step_node, path + ".step",
                "gives more than " + std::to_string(kMaxValuesPerAxis) + " values");
    }
    // A step beyond the range would leave only `from`, silently dropping `to`.
    if (to > from && intervals + kStepEndTolerance < 1.0) {
      file.Fail(step_node, path + ".step",
                "is larger than to - from = " + FormatNumber(to - from) +
                    ": the range would hold only its start; use a smaller step or count = 2");
    }
    const auto last = static_cast<std::size_t>(std::floor(intervals + kStepEndTolerance));
    for (std::size_t i = 0; i <= last; ++i) values.push_back(from + static_cast<double>(i) * step);
    // `to` on the grid: store it exactly as written rather than with rounding noise.
    if (std::abs(intervals - static_cast<double>(last)) <= kStepEndTolerance) values.back() = to;
  } else {
    // A whole number written as a float (count = 3.0) is the count the user means.
    const auto* count_integer = count_node->as_integer();
    const auto* count_float = count_node->as_floating_point();
    const bool whole = count_float != nullptr && std::isfinite(count_float->get()) &&
                       count_float->get() == std::floor(count_float->get()) &&
                       std::abs(count_float->get()) <= 1e15;
    if (count_integer == nullptr && !whole) {
      file.Fail(count_node, path + ".count", "must be a whole number");
    }
    const std::int64_t count = count_integer != nullptr
                                   ? count_integer->get()
                                   : static_cast<std::int64_t>(count_float->get());
    if (count < 1) file.Fail(count_node, path + ".count", "must be at least 1");
    if (count > static_cast<std::int64_t>(kMaxValuesPerAxis)) {
      file.Fail(count_node, path + ".count",
                "must not exceed " + std::to_string(kMaxValuesPerAxis));
    }
    if (count == 1 && to != from) {
      file.Fail(count_node, path + ".count", "1 value needs from = to; use count >= 2 for a range");
    }
    if (count >= 2 && !(to > from)) {
      file.Fail(count_node, path + ".count", "needs from < to for more than one value");
    }
    for (std::int64_t i = 0; i < count; ++i) {
      values.push_back(count == 1 ? from
                                  : from + (to - from) * static_cast<double>(i) /
                                               static_cast<double>(count - 1));
    }
    values.back() = to;
  }
  // Rounding could, in principle, make two neighbours equal for a tiny step on large values.
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (!(values[i] > values[i - 1]) || !AxisStepIsResolvable(values[i - 1], values[i])) {
      file.FailAt(range.source().begin, path, "step is too small to give distinct values");
    }
  }
  return values;
}

std::vector<double> ReadAxisValues(const SourceFile& file, const Section& table,
                                   std::string_view name) {
  const std::string path = table.Path(name);
  const toml::node* node = table.Find(name);
  if (node == nullptr) {
    table.FailMissing(name,
                      "axis \"" + std::string(name) +
                          "\" is listed in table.axes but has no values; give {from, to, step}, "
                          "{from, to, count} or a list");
  }
  std::vector<double> values;
  if (const toml::array* array = node->as_array()) {
    values = ReadExplicitValues(file, *array, name, path);
  } else if (const toml::table* range = node->as_table()) {
    values = ReadRangeValues(file, *range, name, path);
  } else {
    file.Fail(node, path,
              "must be {from = ..., to = ..., step = ...}, {from = ..., to = ..., count = ...} or "
              "a list of values");
  }
  return values;
}

/// `table.axes`: a non-empty list of distinct axis names.
std::vector<std::string> ReadAxisNames(const SourceFile& file, const Section& table) {
  const toml::node* node = table.Find("axes");
  if (node == nullptr) {
    table.FailMissing("axes", "list the varied quantities, e.g. axes = [\"y\", \"yaw\"]");
  }
  const toml::array* array = node->as_array();
  if (array == nullptr) file.Fail(node, "table.axes", "must be an array of axis names");
  if (array->empty()) file.Fail(node, "table.axes", "must list at least one axis");
  const std::vector<std::string_view> allowed = SceneAxisNames();
  std::vector<std::string> names;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    const std::string path = "table.axes[" + std::to_string(i) + "]";
    const auto* text = element.as_string();
    if (text == nullptr) file.Fail(&element, path, "must be a string (an axis name)");
    const std::string& name = text->get();
    if (!IsSceneAxisName(name)) {
      std::string problem = "unknown axis";
      const std::string suggestion = SuggestName(name, allowed);
      if (!suggestion.empty()) problem += " (did you mean \"" + suggestion + "\"?)";
      file.Fail(&element, path, problem + "; allowed axes: " + QuotedList(allowed));
    }
    if (std::find(names.begin(), names.end(), name) != names.end()) {
      file.Fail(&element, path, "axis listed twice");
    }
    names.push_back(name);
  }
  const auto listed = [&names](std::string_view name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  if (listed("z") && listed("fz")) {
    file.Fail(node, "table.axes",
              "z and fz cannot both be axes: one is prescribed, the other solved for");
  }
  if (listed("y") && listed("y_wheel")) {
    file.Fail(node, "table.axes", "y and y_wheel cannot both be axes: y_wheel determines y");
  }
  if (listed("spin") && listed("omega")) {
    file.Fail(node, "table.axes", "spin and omega cannot both be axes: spin determines omega");
  }
  return names;
}

/// Rejects ranges for quantities that are not listed in table.axes: the user meant to vary
/// them, and silently ignoring the range would produce the wrong table.
void CheckUnlistedRanges(const Section& table, const std::vector<std::string>& axis_names) {
  for (std::string_view name : SceneAxisNames()) {
    if (table.Has(name) &&
        std::find(axis_names.begin(), axis_names.end(), name) == axis_names.end()) {
      table.Fail(name, "values given for an axis that is not listed in table.axes");
    }
  }
}

std::vector<std::string> ReadOutputs(const SourceFile& file, const Section& table,
                                     const Case& base) {
  const bool fz_prescribed = base.state.force_prescribed();
  const toml::node* node = table.Find("outputs");
  if (node == nullptr) return DefaultSceneOutputs(fz_prescribed);
  const toml::array* array = node->as_array();
  if (array == nullptr) file.Fail(node, "table.outputs", "must be an array of output names");
  if (array->empty()) file.Fail(node, "table.outputs", "must list at least one output");
  const std::vector<std::string_view> allowed = SceneOutputNames();
  std::vector<std::string> outputs;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& element = *array->get(i);
    const std::string path = "table.outputs[" + std::to_string(i) + "]";
    const auto* text = element.as_string();
    if (text == nullptr) file.Fail(&element, path, "must be a string (an output name)");
    const std::string& name = text->get();
    if (FindOutputQuantity(name) == nullptr) {
      std::string problem = "unknown output";
      const std::string suggestion = SuggestName(name, allowed);
      if (!suggestion.empty()) problem += " (did you mean \"" + suggestion + "\"?)";
      file.Fail(&element, path, problem + "; allowed outputs: " + QuotedList(allowed));
    }
    if (name == "z" && !fz_prescribed) {
      file.Fail(&element, path,
                "z is an output only when fz is prescribed (state.fz or an fz axis); here z "
                "is an input");
    }
    const double k = name == "fi_surf_rail"    ? base.rail_material.shear_yield
                     : name == "fi_surf_wheel" ? base.wheel_material.shear_yield
                                               : 0.0;
    if (std::isnan(k)) {
      file.Fail(&element, path,
                name + " needs the body's yield limit in shear: material.shear_yield");
    }
    if (std::find(outputs.begin(), outputs.end(), name) != outputs.end()) {
      file.Fail(&element, path, "output listed twice");
    }
    outputs.push_back(name);
  }
  return outputs;
}

std::int64_t ReadInteger(const Section& section, std::string_view key, std::int64_t fallback,
                         std::int64_t min, std::int64_t max) {
  const toml::node* node = section.Find(key);
  if (node == nullptr) return fallback;
  const auto* integer = node->as_integer();
  if (integer == nullptr) section.Fail(key, "must be an integer");
  const std::int64_t value = integer->get();
  if (value < min || value > max) {
    section.Fail(key, "must be between " + std::to_string(min) + " and " + std::to_string(max));
  }
  return value;
}

/// `{name = number, ...}` with names from `allowed`, each number positive.
std::map<std::string, double, std::less<>> ReadPositiveByName(
    const Section& section, std::string_view key, const std::vector<std::string_view>& allowed,
    std::string_view what) {
  const Section sub(section, key);
  std::map<std::string, double, std::less<>> values;
  if (!sub.exists()) return values;
  for (const auto& [name, node] : *sub.table()) {
    if (std::find(allowed.begin(), allowed.end(), name.str()) == allowed.end()) {
      sub.Fail(name.str(),
               "not " + std::string(what) + " of this scene; allowed: " + QuotedList(allowed));
    }
    const double value = ReadNumber(section.file(), node, sub.Path(name.str()));
    if (!(value > 0.0)) sub.Fail(name.str(), "must be positive");
    values[std::string(name.str())] = value;
  }
  return values;
}

const std::vector<std::string_view> kRefineKeys = {
    "target",     "absolute", "outputs", "interpolation", "quantile", "max_points",
    "max_passes", "samples",  "seed",    "min_step",      "slope"};
const std::vector<std::string_view> kSlopeKeys = {"target", "at", "step", "window", "axes"};

void RejectUnknownKeys(const Section& section, const std::vector<std::string_view>& allowed) {
  for (const auto& [key, node] : *section.table()) {
    if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
    std::string problem = "unknown key";
    const std::string suggestion = SuggestName(key.str(), allowed);
    if (!suggestion.empty()) problem += " (did you mean " + section.Path(suggestion) + "?)";
    section.Fail(key.str(), problem + "; allowed: " + QuotedList(allowed));
  }
}

/// `{name = number, ...}` with names from `allowed`, each number finite.
std::map<std::string, double, std::less<>> ReadNumbersByName(
    const Section& section, std::string_view key, const std::vector<std::string_view>& allowed) {
  const Section sub(section, key);
  std::map<std::string, double, std::less<>> values;
  if (!sub.exists()) return values;
  for (const auto& [name, node] : *sub.table()) {
    if (std::find(allowed.begin(), allowed.end(), name.str()) == allowed.end()) {
      sub.Fail(name.str(), "not an axis of this scene; allowed: " + QuotedList(allowed));
    }
    values[std::string(name.str())] = ReadNumber(section.file(), node, sub.Path(name.str()));
  }
  return values;
}

// A central difference over 1/80 of the range: an amplitude small against the range (the
// slope at the state, not a secant across the table) yet wide against the solver's own
// convergence noise (its tolerances are 1e-6 of the load, so slopes over steps down to 1e-4
// of the range stay within 1 % of the load's slope scale).
constexpr double kDefaultSlopeStepFraction = 1.0 / 80.0;
// Solves a slope may take on each side of its state: a least-squares fit through a hundred
// samples averages a discretisation ripple as well as it will; more only costs.
constexpr int kMaxSlopeSamples = 100;

// A slope's window: a whole number of steps (up to kMaxSlopeSamples a side), inside the axis.
void CheckSlopeWindow(const Section& slope, const SceneAxis& axis, double x, double step,
                      double window) {
  const double n = std::round(window / step);
  if (!(n >= 1.0 && n <= kMaxSlopeSamples && std::fabs(window - n * step) <= 1e-9 * window)) {
    slope.Fail("window", axis.name + " = " + FormatNumber(window) + " must be 1 to " +
                             std::to_string(kMaxSlopeSamples) + " times its step (" +
                             FormatNumber(step) + ")");
  }
  const std::vector<double>& v = axis.values;
  if (!(x - window >= v.front() && x + window <= v.back())) {
    slope.Fail(window == step ? "step" : "window", axis.name + " ± " + FormatNumber(window) +
                                                       " around " + FormatNumber(x) +
                                                       " leaves the axis range");
  }
}

/// `[table.refine.slope]`: the state (every axis at 0 unless given in `at`, and a node there),
/// the steps and windows, and which axes' slopes are targets (all but fz unless `axes` lists
/// them).
RefineSettings::Slope ReadSlopeTarget(const Section& slope, const Scene& scene) {
  RejectUnknownKeys(slope, kSlopeKeys);
  RefineSettings::Slope target;
  target.fraction = slope.Number("target", target.fraction);
  if (!(target.fraction >= 1e-4 && target.fraction < 1.0)) {
    slope.Fail("target", "must be a fraction of the slope between 1e-4 and 1");
  }
  std::vector<std::string_view> names;
  for (const SceneAxis& axis : scene.axes) names.push_back(axis.name);
  const auto at = ReadNumbersByName(slope, "at", names);
  const auto steps = ReadPositiveByName(slope, "step", names, "an axis");
  const auto windows = ReadPositiveByName(slope, "window", names, "an axis");
  std::vector<std::string> targeted;
  if (const toml::node* list = slope.Find("axes")) {
    const toml::array* array = list->as_array();
    if (array == nullptr || array->empty()) slope.Fail("axes", "must list axis names");
    for (std::size_t i = 0; i < array->size(); ++i) {
      const auto* text = array->get(i)->as_string();
      if (text == nullptr || std::find(names.begin(), names.end(), text->get()) == names.end()) {
        slope.file().Fail(array->get(i), slope.Path("axes") + "[" + std::to_string(i) + "]",
                          "must be an axis name; allowed: " + QuotedList(names));
      }
      targeted.push_back(text->get());
    }
  } else {
    for (const SceneAxis& axis : scene.axes) {
      if (axis.name != "fz") targeted.push_back(axis.name);
    }
  }
  for (const SceneAxis& axis : scene.axes) {
    const std::vector<double>& v = axis.values;
    const auto given = at.find(axis.name);
    const double x = given != at.end() ? given->second : 0.0;
    if (std::find(v.begin(), v.end(), x) == v.end()) {
      slope.Fail("at", "the state must be a node of every axis: " + axis.name + " = " +
                           FormatNumber(x) + " is not among table." + axis.name +
                           "'s starting values (give its value in " + slope.Path("at") + ")");
    }
    target.at.push_back(x);
    double h = 0.0;
    if (std::find(targeted.begin(), targeted.end(), axis.name) != targeted.end()) {
      const auto s = steps.find(axis.name);
      h = s != steps.end() ? s->second : (v.back() - v.front()) * kDefaultSlopeStepFraction;
    }
    const auto given_window = windows.find(axis.name);
    const double w = given_window != windows.end() ? given_window->second : h;
    if (h > 0.0) {
      CheckSlopeWindow(slope, axis, x, h, w);
    } else if (given_window != windows.end()) {
      slope.Fail("window", axis.name + "'s slope is not a target (see " + slope.Path("axes") + ")");
    }
    target.step.push_back(h);
    target.window.push_back(h > 0.0 ? w : 0.0);
  }
  return target;
}

/// `[table.refine]`, checked against the scene's axes and outputs.
RefineSettings ReadRefineSettings(const Section& refine, const Scene& scene) {
  RejectUnknownKeys(refine, kRefineKeys);
  RefineSettings settings;
  settings.load_fraction = refine.Number("target", settings.load_fraction);
  // Below 1e-6 of the load the solver's own tolerances (1e-6 on fz) decide, not the table.
  if (!(settings.load_fraction >= 1e-6 && settings.load_fraction < 1.0)) {
    refine.Fail("target", "must be a fraction of the wheel load between 1e-6 and 1");
  }
  std::vector<std::string_view> outputs(scene.outputs.begin(), scene.outputs.end());
  std::vector<std::string_view> non_force;
  for (std::string_view name : outputs) {
    if (!IsForceOutput(name)) non_force.push_back(name);
  }
  if (refine.Has("absolute")) {
    settings.absolute = ReadPositiveByName(refine, "absolute", non_force, "a non-force output");
  } else if (std::find(outputs.begin(), outputs.end(), "z") != outputs.end()) {
    settings.absolute["z"] = 0.003;  // mm: a tenth of the 30 µm a simulator's z may be off
  }
  const toml::node* list = refine.Find("outputs");
  if (list != nullptr) {
    const toml::array* array = list->as_array();
    if (array == nullptr || array->empty()) refine.Fail("outputs", "must list output names");
    for (std::size_t i = 0; i < array->size(); ++i) {
      const auto* text = array->get(i)->as_string();
      const std::string path = refine.Path("outputs") + "[" + std::to_string(i) + "]";
      if (text == nullptr) refine.file().Fail(array->get(i), path, "must be an output name");
      const std::string& name = text->get();
      if (std::find(outputs.begin(), outputs.end(), name) == outputs.end()) {
        refine.file().Fail(array->get(i), path, "not among table.outputs");
      }
      if (!IsForceOutput(name) && settings.absolute.count(name) == 0) {
        refine.file().Fail(array->get(i), path,
                           "has no target: give it one in " + refine.Path("absolute"));
      }
      settings.outputs.push_back(name);
    }
  } else {
    for (const std::string& name : scene.outputs) {
      if (IsForceOutput(name) || settings.absolute.count(name) != 0) {
        settings.outputs.push_back(name);
      }
    }
  }
  if (settings.outputs.empty()) {
    refine.Fail("outputs", "no output to refine on: store a force or give an absolute target");
  }
  const bool force_targets =
      std::any_of(settings.outputs.begin(), settings.outputs.end(),
                  [](const std::string& name) { return IsForceOutput(name); });
  if (force_targets && !scene.base.state.force_prescribed() &&
      std::find(outputs.begin(), outputs.end(), "fz") == outputs.end()) {
    refine.Fail("target",
                "the force target is relative to the wheel load, which a prescribed-z scene "
                "only knows when fz is among table.outputs");
  }
  settings.interpolation = refine.Choice("interpolation",
                                         {{"linear", RefineSettings::Interpolation::kLinear},
                                          {"cubic", RefineSettings::Interpolation::kCubic}},
                                         settings.interpolation);
  settings.quantile = refine.Number("quantile", settings.quantile);
  // Below a half the "typical" error would be a median; 1 keeps every midpoint within target.
  if (!(settings.quantile >= 0.5 && settings.quantile <= 1.0)) {
    refine.Fail("quantile", "must be a share of the states between 0.5 and 1");
  }
  const std::int64_t points = static_cast<std::int64_t>(scene.PointCount());
  settings.max_points = static_cast<std::size_t>(
      ReadInteger(refine, "max_points", std::max<std::int64_t>(points, 1'000'000), points,
                  static_cast<std::int64_t>(kMaxPointCount)));
  settings.max_passes = static_cast<int>(ReadInteger(refine, "max_passes", 40, 0, 100));
  settings.samples = static_cast<int>(ReadInteger(refine, "samples", 24, 1, 10'000));
  settings.seed = static_cast<std::uint64_t>(
      ReadInteger(refine, "seed", 1, 0, std::numeric_limits<std::int64_t>::max()));
  std::vector<std::string_view> axis_names;
  for (const SceneAxis& axis : scene.axes) axis_names.push_back(axis.name);
  settings.min_step = ReadPositiveByName(refine, "min_step", axis_names, "an axis");
  const Section slope(refine, "slope");
  if (slope.exists()) settings.slope = ReadSlopeTarget(slope, scene);
  return settings;
}

void ApplyAxisValue(Case& point, std::string_view axis, double value) {
  WheelsetState& state = point.state;
  if (axis == "y") {
    state.y = value;
  } else if (axis == "z") {
    state.z = value;
    state.fz.reset();
  } else if (axis == "fz") {
    state.fz = value;
    state.z.reset();
  } else if (axis == "roll") {
    state.roll = value;
  } else if (axis == "yaw") {
    state.yaw = value;
  } else if (axis == "spin") {
    state.spin = value;
    state.omega = OmegaFromSpin(value, state.velocity, point.wheelset.nominal_radius);
  } else if (axis == "omega") {
    state.omega = value;
    state.spin.reset();
  } else if (axis == "vy") {
    state.vy = value;
  } else if (axis == "vyaw") {
    state.vyaw = value;
  } else if (axis == "mu") {
    point.friction = Friction::Constant(value);
  } else if (axis == "y_wheel") {
    // Applied after every other axis (ApplyAxisValues), so that roll is final here.
    state.y = value + point.wheelset.nominal_radius * state.roll;
  } else {
    throw std::invalid_argument("unknown scene axis \"" + std::string(axis) + "\"");
  }
}

/// Sets every axis quantity of a point; y_wheel last, because it depends on roll.
void ApplyAxisValues(Case& point, const std::vector<SceneAxis>& axes,
                     const std::vector<double>& values) {
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (axes[i].name != "y_wheel") ApplyAxisValue(point, axes[i].name, values[i]);
  }
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (axes[i].name == "y_wheel") ApplyAxisValue(point, axes[i].name, values[i]);
  }
}

// The state at every corner of the axes' box passes the case file's range checks
// (CheckWheelsetState): the bounds are on magnitudes and on ratios of quantities that are
// linear along each axis, so the corners bound the whole box.
void CheckStateAtCorners(const Section& table, const Scene& scene) {
  const auto has_axis = [&scene](std::string_view name) {
    return std::any_of(scene.axes.begin(), scene.axes.end(),
                       [name](const SceneAxis& a) { return a.name == name; });
  };
  const bool omega_axis = has_axis("omega");
  const std::size_t n = scene.axes.size();
  for (std::size_t corner = 0; corner < (std::size_t{1} << n); ++corner) {
    std::vector<double> values;
    std::string where;
    for (std::size_t a = 0; a < n; ++a) {
      const SceneAxis& axis = scene.axes[a];
      values.push_back((corner >> a) & 1 ? axis.values.back() : axis.values.front());
      where += (a ? ", " : "") + axis.name + " = " + FormatNumber(values.back());
    }
    Case point = scene.base;
    ApplyAxisValues(point, scene.axes, values);
    CheckWheelsetState(point.state, point.wheelset, omega_axis,
                       [&](std::string_view key, const std::string& message) {
                         table.Fail(has_axis(key) ? key : std::string_view("axes"),
                                    "at the corner " + where + " of the axes, state." +
                                        std::string(key) + " " + message);
                       });
  }
}

Scene ReadScene(std::string_view text, const std::filesystem::path& base_dir,
                const SourceFile& file, bool check_files_exist) {
  const toml::table root = file.Parse(text);
  if (ReadCaseType(root, file) != CaseType::kWheelRail) {
    Section(file, root, "problem")
        .Fail("type",
              "scenes need wheel-rail problems (table axes and outputs are wheel-rail "
              "quantities)");
  }
  const Section table(file, root, "table");
  if (!table.exists()) {
    file.FailAt(
        toml::source_position{0, 0}, "[table]",
        "missing: a scene file needs a [table] section with axes (docs/reference/case-files.md)");
  }

  const std::vector<std::string> axis_names = ReadAxisNames(file, table);
  // Unknown keys in [table]: typos of axis names or of outputs.
  std::vector<std::string_view> table_keys = {"axes", "outputs", "refine"};
  for (std::string_view name : SceneAxisNames()) table_keys.push_back(name);
  for (const auto& [key, node] : *root.get("table")->as_table()) {
    const std::string_view name = key.str();
    if (std::find(table_keys.begin(), table_keys.end(), name) != table_keys.end()) continue;
    std::string problem = "unknown key";
    const std::string suggestion = SuggestName(name, table_keys);
    if (!suggestion.empty()) problem += " (did you mean table." + suggestion + "?)";
    file.Fail(&node, "table." + std::string(name),
              problem + "; [table] has axes, outputs, refine and one range per axis");
  }
  CheckUnlistedRanges(table, axis_names);

  // A quantity is either fixed in the case or varied on an axis, never both.
  for (const std::string& axis : axis_names) {
    for (const auto& [section_name, key] : KeysReplacedByAxis(axis)) {
      const Section section(file, root, std::string(section_name));
      if (section.Has(key)) {
        section.Fail(key, "also varied by table axis \"" + axis +
                              "\"; remove one of them (quantities on an axis come from the table)");
      }
    }
  }

  Scene scene;
  for (const std::string& name : axis_names) {
    scene.axes.push_back(SceneAxis{name, ReadAxisValues(file, table, name)});
  }
  double point_count = 1.0;
  for (const SceneAxis& axis : scene.axes) point_count *= static_cast<double>(axis.values.size());
  if (point_count > kMaxPointCount) {
    file.Fail(table.Find("axes"), "table.axes",
              "the table would have " + FormatNumber(point_count) +
                  " points, more than the limit of " + FormatNumber(kMaxPointCount));
  }

  CaseParseOptions options;
  options.check_files_exist = check_files_exist;
  options.allow_table_section = true;
  options.axis_names.insert(axis_names.begin(), axis_names.end());
  scene.base = ReadCase(root, file, base_dir, options);
  scene.base.source_text = std::string(text);
  CheckStateAtCorners(table, scene);
  std::vector<double> first;
  for (const SceneAxis& axis : scene.axes) first.push_back(axis.values.front());
  ApplyAxisValues(scene.base, scene.axes, first);

  scene.outputs = ReadOutputs(file, table, scene.base);
  const Section refine(table, "refine");
  if (refine.exists()) scene.refine = ReadRefineSettings(refine, scene);
  return scene;
}

}  // namespace
}  // namespace io

int RefineSettings::Slope::SamplesPerSide(std::size_t a) const {
  return step[a] > 0.0 ? static_cast<int>(std::lround(window[a] / step[a])) : 0;
}

std::size_t Scene::PointCount() const {
  std::size_t count = 1;
  for (const SceneAxis& axis : axes) count *= axis.values.size();
  return count;
}

std::vector<std::size_t> Scene::Shape() const {
  std::vector<std::size_t> shape;
  for (const SceneAxis& axis : axes) shape.push_back(axis.values.size());
  return shape;
}

std::vector<std::string> DefaultSceneOutputs(bool fz_prescribed) {
  std::vector<std::string> outputs;
  for (const OutputQuantity& q : kOutputQuantities) {
    if (q.default_output == DefaultOutput::kYes ||
        (q.default_output == DefaultOutput::kWithPrescribedFz && fz_prescribed)) {
      outputs.emplace_back(q.name);
    }
  }
  return outputs;
}

bool AxisStepIsResolvable(double a, double b) {
  const double step = b - a;
  return step >= WRC_AXIS_MIN_STEP &&
         step >= WRC_AXIS_MIN_RELATIVE_STEP * std::max(std::abs(a), std::abs(b));
}

namespace {

// The case's value of a state quantity (wrc/quantities.h), NaN where the case leaves it open.
double CaseStateValue(const Case& c, std::string_view name) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  const WheelsetState& s = c.state;
  if (name == "y") return s.y;
  if (name == "z") return s.z.value_or(kNaN);
  if (name == "fz") return s.fz.value_or(kNaN);
  if (name == "roll") return s.roll;
  if (name == "yaw") return s.yaw;
  if (name == "spin")
    return s.spin ? *s.spin : -s.omega * c.wheelset.nominal_radius / s.velocity - 1.0;
  if (name == "omega") return s.omega;
  if (name == "vy") return s.vy;
  if (name == "vroll") return s.vroll;
  if (name == "vyaw") return s.vyaw;
  if (name == "mu") return c.friction.is_constant() ? c.friction.mu.front() : kNaN;
  if (name == "y_wheel") return kNaN;  // follows from y and roll, never fixed on its own
  throw std::logic_error("FixedStateValue: '" + std::string(name) + "' is not a state quantity");
}

}  // namespace

double FixedStateValue(const Scene& scene, std::string_view name) {
  const double value = CaseStateValue(scene.base, name);
  // spin and omega are one quantity in two forms; y follows from y_wheel and roll.
  auto varied_by = [](std::string_view axis, std::string_view quantity) {
    if (axis == quantity) return true;
    if ((axis == "spin" || axis == "omega") && (quantity == "spin" || quantity == "omega")) {
      return true;
    }
    return axis == "y_wheel" && quantity == "y";
  };
  for (const SceneAxis& axis : scene.axes) {
    if (varied_by(axis.name, name)) return std::numeric_limits<double>::quiet_NaN();
  }
  return value;
}

Case CaseAtPoint(const Scene& scene, const std::vector<double>& axis_values) {
  if (axis_values.size() != scene.axes.size()) {
    throw std::invalid_argument("CaseAtPoint: " + std::to_string(axis_values.size()) +
                                " values for " + std::to_string(scene.axes.size()) + " axes");
  }
  Case point = scene.base;
  for (std::size_t i = 0; i < axis_values.size(); ++i) {
    const std::string& name = scene.axes[i].name;
    const std::string problem = io::AxisValueProblem(name, axis_values[i]);
    if (!problem.empty()) {
      throw InputError(scene.base.source_name + ": table axis " + name + " = " +
                       io::FormatNumber(axis_values[i]) + ": " + problem);
    }
  }
  io::ApplyAxisValues(point, scene.axes, axis_values);
  return point;
}

Case CaseAtIndex(const Scene& scene, const std::vector<std::size_t>& indices) {
  if (indices.size() != scene.axes.size()) {
    throw std::out_of_range("CaseAtIndex: " + std::to_string(indices.size()) + " indices for " +
                            std::to_string(scene.axes.size()) + " axes");
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < indices.size(); ++i) {
    values.push_back(scene.axes[i].values.at(indices[i]));
  }
  return CaseAtPoint(scene, values);
}

Scene ParseScene(std::string_view toml_text, const std::filesystem::path& base_dir,
                 std::string_view display_name) {
  const io::SourceFile file{std::string(display_name)};
  return io::ReadScene(toml_text, base_dir, file, /*check_files_exist=*/false);
}

Scene LoadScene(const std::filesystem::path& path) {
  const std::string text = io::ReadTextFile(path);
  const io::SourceFile file{path.string()};
  return io::ReadScene(text, std::filesystem::absolute(path).parent_path(), file,
                       /*check_files_exist=*/true);
}

}  // namespace wrc
