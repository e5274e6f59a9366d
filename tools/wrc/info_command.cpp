// `wrc info TABLE.h5 [--json]`: what a table holds and where it came from.

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "runtime/hdf5/table_schema.h"
#include "tools/wrc/commands.h"
#include "wrc/generator/generator.h"

namespace wrc::cli {
namespace {

using nlohmann::json;

const char* const kStatusNames[kPointStatusCount] = {"ok", "no_contact", "not_converged", "error"};

// NaN is not JSON: null instead.
json Number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string Attribute(const TableInfo& info, const std::string& name) {
  for (const auto& [key, value] : info.attributes) {
    if (key == name) return value;
  }
  return {};
}

nlohmann::json Refinement(const std::string& path, const TableInfo& info);

// Texts from the file (attributes, messages) need not be UTF-8: shown with U+FFFD in their place
// rather than ending the output with the JSON library's exception.
constexpr auto kReplaceInvalidUtf8 = nlohmann::json::error_handler_t::replace;

json InfoJson(const std::string& path, const TableInfo& info) {
  json axes = json::array();
  for (const TableInfo::Axis& axis : info.axes) {
    axes.push_back({{"name", axis.name},
                    {"unit", axis.unit},
                    {"size", axis.values.size()},
                    {"min", Number(axis.values.front())},
                    {"max", Number(axis.values.back())},
                    {"values", axis.values}});
  }
  json outputs = json::array();
  for (const TableInfo::Output& output : info.outputs) {
    outputs.push_back({{"name", output.name},
                       {"unit", output.unit},
                       {"min", Number(output.min)},
                       {"max", Number(output.max)}});
  }
  json status = json::object();
  for (int s = 0; s < kPointStatusCount; ++s) status[kStatusNames[s]] = info.status_counts[s];
  if (info.other_status > 0) status["invalid"] = info.other_status;
  json attributes = json::object();
  for (const auto& [name, value] : info.attributes) attributes[name] = value;
  // NaN (a quantity the table does not fix) as null: JSON has no NaN.
  for (const auto& [name, value] : info.numbers) {
    attributes[name] = std::isfinite(value) ? json(value) : json(nullptr);
  }
  json failures = json::array();
  for (const TableInfo::Failure& failure : info.failures) {
    json point = json::object();
    for (std::size_t a = 0; a < info.axes.size() && a < failure.indices.size(); ++a) {
      point[info.axes[a].name] = info.axes[a].values[failure.indices[a]];
    }
    failures.push_back({{"index", failure.index},
                        {"indices", failure.indices},
                        {"point", point},
                        {"message", failure.message}});
  }
  return {
      {"file", path},
      {"format", info.format},
      {"format_version", info.format_version},
      {"sealed", info.sealed},
      {"warnings_count", info.warnings_count >= 0 ? json(info.warnings_count) : json(nullptr)},
      {"points", info.points},
      {"axes", axes},
      {"outputs", outputs},
      {"status", status},
      {"failures", failures},
      {"solve_time_s",
       {{"total", info.solve_time_total_s},
        {"mean", info.points ? info.solve_time_total_s / static_cast<double>(info.points) : 0.0},
        {"max", info.solve_time_max_s}}},
      {"profiles",
       {{"rail", {{"name", info.rail_profile_name}, {"bytes", info.rail_profile_bytes}}},
        {"wheel", {{"name", info.wheel_profile_name}, {"bytes", info.wheel_profile_bytes}}}}},
      {"attributes", attributes},
      {"refinement", Refinement(path, info)}};
}

// A refine_* attribute: the JSON text wrc generate writes, of the kind given; anything else is
// refused by name rather than shown as invalid JSON or as a library's exception text.
nlohmann::json RefineAttribute(const std::string& path, const TableInfo& info,
                               const std::string& name, nlohmann::json::value_t kind) {
  nlohmann::json value =
      nlohmann::json::parse(Attribute(info, name), nullptr, /*allow_exceptions=*/false);
  if (value.type() != kind) {
    throw InputError(path + ":/@" + name + ": not the JSON " + nlohmann::json(kind).type_name() +
                     " wrc generate writes there; the table is damaged or was edited");
  }
  return value;
}

// The state the table was made at, as the wheelset API reads it: speed, radius, side, and the
// value of each state quantity that is not an axis ("-" where the table does not fix it).
void PrintFixedState(const TableInfo& info) {
  if (info.numbers.empty()) return;  // written before the fixed state was stored typed
  const auto number = [&info](const std::string& name) -> double {
    for (const auto& [key, value] : info.numbers) {
      if (key == name) return value;
    }
    return NAN;
  };
  std::cout << "  fixed state           " << Attribute(info, "wheelset_side") << " wheel, V "
            << number("wheelset_velocity") << " mm/s, r0 " << number("wheelset_nominal_radius")
            << " mm;";
  for (const StateQuantity& q : kStateQuantities) {
    const double value = number("fixed_" + std::string(q.name));
    if (std::isfinite(value)) std::cout << ' ' << q.name << ' ' << value;
  }
  std::cout << '\n';
}

// The refine_* attributes of a refined table as one JSON object (null for other tables).
nlohmann::json Refinement(const std::string& path, const TableInfo& info) {
  if (Attribute(info, schema::kRefineTarget).empty()) return nullptr;
  using Kind = nlohmann::json::value_t;
  nlohmann::json r = {{"target", RefineAttribute(path, info, schema::kRefineTarget, Kind::object)},
                      {"passes", RefineAttribute(path, info, schema::kRefinePasses, Kind::array)},
                      {"stop", Attribute(info, schema::kRefineStop)},
                      {"estimated_error",
                       RefineAttribute(path, info, schema::kRefineEstimatedError, Kind::object)}};
  // Tables refined before the CPU time was recorded have none.
  if (!Attribute(info, schema::kRefineCpuSeconds).empty()) {
    r["cpu_seconds"] = RefineAttribute(path, info, schema::kRefineCpuSeconds, Kind::array);
  }
  return r;
}

void PrintRefinement(const std::string& path, const TableInfo& info) {
  const nlohmann::json r = Refinement(path, info);
  if (r.is_null()) return;
  const nlohmann::json& target = r["target"];
  std::cout << "refinement: forces within " << 100 * target.value("load_fraction", 0.0)
            << " % of the local wheel load";
  if (target.contains("absolute")) {
    for (const auto& [name, value] : target["absolute"].items()) {
      std::cout << ", " << name << " within " << value.get<double>();
    }
  }
  // Tables refined before the target named its interpolation were refined for linear lookups.
  const bool cubic = target.value("interpolation", std::string("linear")) == "cubic";
  // Tables refined before the target named a quantile kept every sampled midpoint within it.
  const double quantile = target.value("quantile", 1.0);
  if (quantile < 1.0) {
    std::cout << " (at " << 100 * quantile << " % of random states, each output, ";
  } else {
    std::cout << " (at sampled interval midpoints, ";
  }
  std::cout << (cubic ? "cubic" : "multilinear") << " lookups); budget "
            << target.value("max_points", 0) << " points, " << target.value("max_passes", 0)
            << " passes\n";
  std::size_t pass = 0;
  for (const nlohmann::json& p : r["passes"]) {
    std::cout << "  pass " << pass << ": " << p.value("points", 0) << " points ("
              << p.value("new_points", 0) << " solved), ";
    if (p.value("samples", 0) == 0) {
      std::cout << "midpoints not sampled";  // the last pass: the stop rule needs none
    } else {
      std::cout << p.value("samples", 0) << " midpoint solves, "
                << p.value("intervals_above_target", 0) << " intervals above target, worst "
                << p.value("worst_midpoint_error", 0.0) << " × target";
    }
    if (p.contains("quantile_error") && p["quantile_error"].is_number()) {
      std::cout << "; random states: " << 100 * quantile << " % quantile "
                << p["quantile_error"].get<double>() << " × target";
    }
    if (r.contains("cpu_seconds") && pass < r["cpu_seconds"].size() &&
        r["cpu_seconds"][pass].is_number()) {
      std::cout << "; " << r["cpu_seconds"][pass].get<double>() << " CPU s so far";
    }
    std::cout << '\n';
    ++pass;
  }
  std::cout << "  stopped: " << r["stop"].get<std::string>() << '\n';
  const nlohmann::json& e = r["estimated_error"];
  if (e.is_object() && e["p95"].is_number()) {
    std::cout << "  estimated error at " << e.value("points", 0) << " random points ("
              << (cubic ? "cubic" : "multilinear") << "): p50 " << e["p50"].get<double>()
              << ", p95 " << e["p95"].get<double>() << ", max " << e["max"].get<double>()
              << " × target\n";
  }
  if (e.is_object() && e.contains("slope") && e["slope"].is_object()) {
    std::cout << "  slope errors at the slope state:";
    for (const auto& [axis, error] : e["slope"].items()) {
      std::ostringstream value;
      value << std::setprecision(3);
      if (error.is_number()) {
        value << error.get<double>();
      } else {
        value << "–";  // not solved
      }
      std::cout << ' ' << axis << ' ' << value.str();
    }
    std::cout << " × target\n";
  }
}

void PrintHuman(const std::string& path, const TableInfo& info) {
  std::cout << path << ": " << info.format << " version " << info.format_version << ", "
            << info.points << " points\n";
  const bool flat = info.format == kFlatTableFormat;
  if (flat) {
    std::cout << "  digest                intact (a SHA-256 of every byte after the header)\n"
                 "  a flat table (wrc export): solve times, failure messages and profiles are "
                 "in the HDF5 table it came from\n";
  } else {
    std::cout << (info.sealed ? "  seal                  intact (a SHA-256 of every byte, checked "
                                "before HDF5 reads the file)\n"
                              : "  seal                  none: written before seals, so damage is "
                                "only found as HDF5 reads it; seal it with `wrc upgrade`\n");
  }
  for (const char* name :
       {"wrc_version", "created", "rail_profile_sha256", "wheel_profile_sha256", "z_warm_start"}) {
    const std::string value = Attribute(info, name);
    if (!value.empty()) std::cout << "  " << std::left << std::setw(22) << name << value << '\n';
  }
  PrintFixedState(info);
  if (!flat) {
    std::cout << "  profiles: rail " << info.rail_profile_name << " (" << info.rail_profile_bytes
              << " bytes), wheel " << info.wheel_profile_name << " (" << info.wheel_profile_bytes
              << " bytes)\n";
  }
  std::cout << "axes:\n";
  for (const TableInfo::Axis& axis : info.axes) {
    std::cout << "  " << std::left << std::setw(14) << axis.name << std::right << std::setw(6)
              << axis.values.size() << " values  " << axis.values.front() << " to "
              << axis.values.back() << ' ' << axis.unit;
    double smallest = INFINITY, largest = 0.0;
    for (std::size_t i = 1; i < axis.values.size(); ++i) {
      smallest = std::min(smallest, axis.values[i] - axis.values[i - 1]);
      largest = std::max(largest, axis.values[i] - axis.values[i - 1]);
    }
    // Steps equal to round-off of the values' magnitude count as uniform.
    if (axis.values.size() > 2 && largest - smallest > 1e-9 * largest) {
      std::cout << ", steps " << smallest << " to " << largest;
    }
    std::cout << '\n';
  }
  PrintRefinement(path, info);
  std::cout << "outputs (range over ok points):\n";
  for (const TableInfo::Output& output : info.outputs) {
    std::cout << "  " << std::left << std::setw(14) << output.name << std::setw(8) << output.unit
              << std::right << output.min << " to " << output.max << '\n';
  }
  std::cout << "status:";
  for (int s = 0; s < kPointStatusCount; ++s) {
    std::cout << ' ' << kStatusNames[s] << ' ' << info.status_counts[s];
  }
  if (info.other_status > 0) std::cout << " invalid " << info.other_status;
  if (info.warnings_count >= 0) std::cout << "; with warnings " << info.warnings_count;
  std::cout << '\n';
  if (!flat) {
    std::cout << "solve time: total " << info.solve_time_total_s << " s, mean "
              << (info.points ? info.solve_time_total_s / static_cast<double>(info.points) : 0.0)
              << " s, max " << info.solve_time_max_s << " s\n";
  }
  if (!info.failures.empty()) {
    std::cout << "failed points:\n";
    for (const TableInfo::Failure& failure : info.failures) {
      std::cout << "  (";
      for (std::size_t a = 0; a < info.axes.size(); ++a) {
        std::cout << (a ? ", " : "") << info.axes[a].name << " = "
                  << info.axes[a].values[failure.indices[a]];
      }
      std::cout << "): " << failure.message << '\n';
    }
  }
  std::cout << "scene:\n" << Attribute(info, schema::kScene);
}

}  // namespace

void AddInfoCommand(CLI::App& app, int* exit_code) {
  auto* cmd =
      app.add_subcommand("info", "Show what a table holds: axes, outputs, status, provenance");
  auto path = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  cmd->add_option("TABLE", *path, "Table file (HDF5 from wrc generate, or flat from wrc export)")
      ->required();
  cmd->add_flag("--json", *as_json, "Print one JSON object");
  cmd->callback([=]() {
    try {
      const TableInfo info = ReadTableInfo(*path);
      if (*as_json) {
        std::cout << InfoJson(*path, info).dump(1, ' ', false, kReplaceInvalidUtf8) << '\n';
      } else {
        PrintHuman(*path, info);
      }
      *exit_code = kExitOk;
    } catch (...) {
      *exit_code = ReportFailure("wrc info");
      // As wrc solve --json: a program reading stdout gets an error object, not nothing.
      if (*as_json) {
        const std::string message = FailureOf(std::current_exception()).message;
        std::cout << nlohmann::json{{"status", "error"}, {"message", message}}.dump(
                         1, ' ', false, kReplaceInvalidUtf8)
                  << '\n';
      }
    }
  });
}

}  // namespace wrc::cli
