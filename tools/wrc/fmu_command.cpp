// `wrc fmu TABLE.h5 [--left LEFT.h5] -o wheelset.fmu`: the wheelset FMU (fmu/, FMI 3.0 or 2.0
// co-simulation) packed with the tables it reads. The tables go in as flat tables (wrc export),
// which the FMU's binary reads without HDF5; the start values that depend on the table (its
// speed, its wheel load, the rail origins of its scene) go into modelDescription.xml and, from
// the same map, into resources/start_values.txt for the binary.

#include <chrono>
#include <cmath>
#include <ctime>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "fmu/model_description.h"
#include "fmu/start_values.h"
#include "fmu/variables.h"
#include "runtime/format/flat_table.h"
#include "studies/dynamics/forces.h"
#include "tools/wrc/commands.h"
#include "tools/wrc/fmu_binary.h"
#include "tools/wrc/verify.h"
#include "tools/wrc/zip_writer.h"
#include "wrc/core/output_file.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

using fmu::StartNumber;
using fmu::StartValues;

// The middle node of the named axis, or NaN when the table has no such axis.
double MiddleNode(const format::TableContent& table, const std::string& axis) {
  for (const format::AxisContent& a : table.axes) {
    if (a.name == axis) return a.values[a.values.size() / 2];
  }
  return NAN;
}

bool HasAxis(const format::TableContent& table, const std::string& axis) {
  return std::isfinite(MiddleNode(table, axis));
}

// 0 where the axis reaches it, else its middle node.
double AxisStart(const format::TableContent& table, const std::string& axis) {
  for (const format::AxisContent& a : table.axes) {
    if (a.name == axis && a.values.front() <= 0.0 && a.values.back() >= 0.0) return 0.0;
  }
  return MiddleNode(table, axis);
}

// The load on each rail a simulation starts from: the scene's, else the middle of an fz axis,
// else NaN (a table made with z prescribed: the wheelset reads no load).
double StartLoad(const format::TableContent& table, const Case& base) {
  return base.state.fz ? *base.state.fz : MiddleNode(table, "fz");
}

// Parameters and inputs at the table's own state and speed, SI units.
StartValues StartValuesOf(const format::TableContent& right, bool has_left,
                          const std::string& interpolation, const Case& base,
                          const dynamics::ContactGeometry& geometry) {
  using namespace fmu;  // NOLINT: the value references
  StartValues s;
  s[kRightTable] = "right.wrct";
  s[kLeftTable] = has_left ? "left.wrct" : "";
  s[kInterpolation] =
      std::to_string(interpolation == "cubic" ? kInterpolationCubic : kInterpolationLinear);
  s[kLeftRailOriginY] = StartNumber(geometry.origin[WRC_LEFT][0] / 1000.0);
  s[kLeftRailOriginZ] = StartNumber(geometry.origin[WRC_LEFT][1] / 1000.0);
  s[kRightRailOriginY] = StartNumber(geometry.origin[WRC_RIGHT][0] / 1000.0);
  s[kRightRailOriginZ] = StartNumber(geometry.origin[WRC_RIGHT][1] / 1000.0);
  // The pose the table fixes where it has no axis; where it has one, 0 if the axis reaches it
  // (centred running), else its middle node.
  const WheelsetState& state = base.state;
  const auto pose = [&](const char* axis, double fixed, double scale) {
    const bool y = std::string(axis) == "y";
    if (!HasAxis(right, axis) && !(y && HasAxis(right, "y_wheel"))) {
      return StartNumber(fixed / scale);
    }
    return StartNumber(AxisStart(right, y && !HasAxis(right, "y") ? "y_wheel" : axis) / scale);
  };
  s[kY] = pose("y", state.y, 1000.0);
  s[kZ] = pose("z", state.z.value_or(0.0), 1000.0);
  s[kRoll] = pose("roll", state.roll, 1.0);
  s[kYaw] = pose("yaw", state.yaw, 1.0);
  s[kVy] = pose("vy", state.vy, 1000.0);
  s[kVroll] = pose("vroll", state.vroll, 1.0);
  s[kVyaw] = pose("vyaw", state.vyaw, 1.0);
  s[kOmega] = StartNumber(base.state.omega);
  s[kVelocity] = StartNumber(base.state.velocity / 1000.0);
  s[kLeftWheelLoad] = s[kRightWheelLoad] = StartNumber(StartLoad(right, base));
  s[kLeftMu] = s[kRightMu] = StartNumber(MiddleNode(right, "mu"));
  return s;
}

std::string UtcNow() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

struct FmuOptions {
  std::string right, left, output, interpolation = "linear";
  int fmi_version = 3;
};

// The binary's folder: FMI 3.0 names platforms by tuple, FMI 2.0 by its own short names.
std::string PlatformFolder(int fmi_version) {
  const std::string tuple = FmuPlatform();
  if (fmi_version == 3) return tuple;
  if (tuple == "x86_64-linux") return "linux64";
  throw std::invalid_argument("FMI 2.0 names no platform folder for " + tuple +
                              ": use --fmi-version 3");
}

format::TableContent ReadTable(const std::string& path) {
  format::TableContent content = format::ReadTableContent(path);
  if (!content.warning.empty()) std::cerr << "wrc fmu: warning: " << content.warning << '\n';
  return content;
}

void PackFmu(const FmuOptions& o) {
  const std::string platform = PlatformFolder(o.fmi_version);  // refused before any work
  RequireRegularOutput(o.output);
  RequireNotAnInput(o.output, {o.right, o.left});
  const format::TableContent right = ReadTable(o.right);
  const bool has_left = !o.left.empty();
  const format::TableContent left = has_left ? ReadTable(o.left) : format::TableContent{};
  // The tables must serve a wheelset (known axes, a speed in the scene), as the FMU reads them.
  const Table right_table(o.right);
  if (has_left) {
    const Table left_table(o.left);
    const WheelsetTable serves_both(left_table, right_table);
  } else {
    const WheelsetTable serves(right_table);
  }
  // The rail origins are where the solver places the rails for the right table's scene; their
  // placement does not depend on the load, so a table without one is placed at 10 kN.
  const auto stored = LoadStoredScene(o.right);
  const Case& base = stored->scene.base;
  const double load = StartLoad(right, base);
  const auto geometry = dynamics::SceneGeometry(base, std::isfinite(load) ? load : 1e4);
  const StartValues start = StartValuesOf(right, has_left, o.interpolation, base, geometry);
  fmu::ModelDescriptionInfo info;
  info.description = "Wheel-rail contact of a wheelset from the wrc table " + o.right +
                     (has_left ? " (left wheel: " + o.left + ")" : "");
  info.generation_tool = std::string("wrc ") + WRC_VERSION;
  info.generated_at = UtcNow();
  info.fmi_version = o.fmi_version;

  ZipWriter zip(o.output);
  zip.Add("modelDescription.xml", fmu::ModelDescriptionXml(start, info));
  zip.Add("binaries/" + platform + "/" + fmu::kModelIdentifier + ".so", std::string(FmuBinary()),
          0755);
  zip.Add("resources/right.wrct", format::EncodeFlatTable(right));
  if (has_left) zip.Add("resources/left.wrct", format::EncodeFlatTable(left));
  zip.Add(std::string("resources/") + fmu::kStartValuesFile, fmu::FormatStartValues(start));
  zip.Close();
  std::cout << "wrc fmu: wrote " << o.output << ": FMI " << o.fmi_version << ".0 co-simulation, "
            << platform << ", "
            << (has_left ? "two tables" : "one table, mirrored for the left wheel") << ", velocity "
            << base.state.velocity / 1000.0 << " m/s\n";
}

}  // namespace

void AddFmuCommand(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand(
      "fmu", "Pack a wheelset FMU (FMI 3.0 or 2.0 co-simulation) that reads the table");
  auto o = std::make_shared<FmuOptions>();
  cmd->add_option("TABLE", o->right, "Table of the right wheel (HDF5, made by wrc generate)")
      ->required();
  cmd->add_option("--left", o->left,
                  "Table of the left wheel (default: the right wheel's table, mirrored)");
  cmd->add_option("--interpolation", o->interpolation,
                  "Start value of the FMU's interpolation parameter")
      ->check(CLI::IsMember({"linear", "cubic"}));
  cmd->add_option("--fmi-version", o->fmi_version, "FMI version of the FMU: 3 (3.0) or 2 (2.0)")
      ->check(CLI::IsMember({2, 3}));
  cmd->add_option("-o,--output", o->output, "The FMU to write (replaced if it exists)")->required();
  cmd->callback([=]() {
    try {
      PackFmu(*o);
      FinishStandardOutput();
      *exit_code = kExitOk;
    } catch (...) {
      *exit_code = ReportFailure("wrc fmu");
    }
  });
}

}  // namespace wrc::cli
