// `wrc solve CASE.toml [--json] [--out DIR]` (docs/reference/cli.md).

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tools/wrc/commands.h"
#include "tools/wrc/solve_output.h"
#include "wrc/core/case.h"
#include "wrc/core/errors.h"
#include "wrc/core/halfspace.h"
#include "wrc/core/output_file.h"
#include "wrc/core/wheelrail.h"

namespace wrc::cli {

using nlohmann::json;

namespace {

int ExitCodeFor(SolverStatus s) {
  return s == SolverStatus::kNotConverged ? kExitNumerical : kExitOk;
}

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A short human-readable summary of the JSON result.
// A number for a reader: 6 significant digits, as CONTACT prints about 4 (the JSON keeps all).
std::string Human(const json& value) {
  if (!value.is_number()) return value.dump();
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value.get<double>());
  return text;
}

void PrintHuman(const json& j) {
  std::cout << "status " << j["status"].get<std::string>() << "\n";
  if (j.contains("rail_forces_track")) {
    const json& f = j["rail_forces_track"];
    std::cout << "forces on the rail (track): fx " << Human(f["fx"]) << " N, fy " << Human(f["fy"])
              << " N, fz " << Human(f["fz"]) << " N\nwheelset z " << Human(j["wheelset"]["z"])
              << " mm\nfrictional power Tgamma " << Human(j["t_gamma"]) << " N\n";
  }
  int n = 0;
  for (const json& p : j["patches"]) {
    std::cout << "patch " << ++n << ": fn " << Human(p["fn"]) << " N, fx " << Human(p["fx"])
              << " N, fs " << Human(p["fs"]) << " N, mn " << Human(p["mn"]) << " N.mm, pmax "
              << Human(p["pmax"]) << " N/mm2, contact " << p["n_contact"] << ", slip "
              << p["n_slip"];
    if (p.contains("t_gamma")) {
      std::cout << ", Tgamma " << Human(p["t_gamma"]) << " N (from the slip "
                << Human(p["t_gamma_slip"]) << " N), frictional power "
                << Human(p["frictional_power"]) << " W";
    }
    for (const char* body : {"rail", "wheel"}) {
      const std::string key = std::string("fi_surf_") + body;
      if (p.contains(key) && p[key].is_number()) {
        std::cout << ", FI_surf " << body << ' ' << Human(p[key]);
      }
    }
    std::cout << "\n";
  }
  std::cout << "time " << Human(j["timing_s"]["total"]) << " s\n";
}

json NumberOrNull(double value) { return std::isfinite(value) ? json(value) : json(); }

json Vec(const Eigen::Vector3d& v, const char* a, const char* b, const char* c) {
  return {{a, v(0)}, {b, v(1)}, {c, v(2)}};
}

}  // namespace

json HalfspaceJson(const HalfspaceResult& r, double seconds) {
  json patch = {{"fn", r.fn},
                {"fx", r.fx},
                {"fs", r.fy},
                {"mn", r.mz},
                {"pmax", r.pmax},
                {"n_contact", r.n_contact},
                {"n_slip", r.n_slip},
                {"n_adh", r.n_adhesion},
                {"area", r.area},
                {"approach", r.approach},
                {"n_pot", r.grid.size()}};
  json iterations = {{"normal", r.normal_summary.iterations}};
  if (r.tangential_solved) iterations["tangential"] = r.tangential_summary.iterations;
  std::string message;
  if (r.status == SolverStatus::kNotConverged) {
    message = "solver reached its iteration limit (normal residual " +
              std::to_string(r.normal_summary.residual) + ", tangential residual " +
              std::to_string(r.tangential_summary.residual) + ")";
    if (!std::isfinite(r.fn) || !std::isfinite(r.fx) || !std::isfinite(r.fy)) {
      message = "the solution is not finite";
    }
  }
  return {{"status", ToString(r.status)},
          {"message", message},
          {"patches", r.status == SolverStatus::kNoContact ? json::array() : json::array({patch})},
          {"iterations", iterations},
          {"timing_s", {{"total", seconds}}},
          {"warnings", r.warnings}};
}

// Writes the fields as CSV, one row per element of the potential contact area (format in
// docs/output-format.md), plus the JSON summary.
void WriteHalfspaceFields(const std::filesystem::path& dir, const HalfspaceResult& r,
                          const json& summary) {
  std::filesystem::create_directories(dir);
  std::ostringstream out;
  out << "i,j,x,y,h,pn,px,py,sx,sy,state\n";
  out.precision(10);
  const Grid& g = r.grid;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      const bool t = r.tangential_solved;
      out << i << ',' << j << ',' << g.x(i) << ',' << g.y(j) << ',' << r.h[k] - r.approach << ','
          << r.pressure[k] << ',' << (t ? r.px[k] : 0.0) << ',' << (t ? r.py[k] : 0.0) << ','
          << (t ? r.sx[k] : 0.0) << ',' << (t ? r.sy[k] : 0.0) << ','
          << (t ? static_cast<int>(r.state[k]) : (r.pressure[k] > 0.0 ? 1 : 0)) << '\n';
    }
  }
  WriteFileAtomically(dir / "fields.csv", out.str());
  WriteFileAtomically(dir / "summary.json", summary.dump(1) + '\n');
}

json WheelRailJson(const WheelRailResult& r, double seconds) {
  json forces = Vec(r.force_T, "fx", "fy", "fz");
  forces.update(Vec(r.moment_T, "mx", "my", "mz"));
  json patches = json::array();
  for (const PatchResult& p : r.patches) {
    patches.push_back(
        {{"fn", p.fn},
         {"fx", p.fx},
         {"fs", p.fs},
         {"mn", p.mn},
         {"pmax", p.pmax},
         {"n_contact", p.n_contact},
         {"n_slip", p.n_slip},
         {"n_adh", p.n_adhesion},
         {"n_pot", p.n_pot},
         {"contact_angle", p.contact_angle},
         {"x_tr", p.reference_T(0)},
         {"y_tr", p.reference_T(1)},
         {"z_tr", p.reference_T(2)},
         {"y_r", p.reference_rail(0)},
         {"z_r", p.reference_rail(1)},
         {"x_w", p.reference_wheel(0)},
         {"y_w", p.reference_wheel(1)},
         {"z_w", p.reference_wheel(2)},
         {"approach", p.approach},
         {"cksi", p.cksi},
         {"ceta", p.ceta},
         {"cphi", p.cphi},
         {"t_gamma", TGamma(p)},
         {"t_gamma_slip", p.t_gamma_slip},
         {"frictional_power", FrictionalPower(p, r.velocity)},
         {"contact_area", p.contact_area},
         {"fi_surf_rail", NumberOrNull(p.fi_surf_rail)},
         {"fi_surf_wheel", NumberOrNull(p.fi_surf_wheel)},
         {"iterations",
          {{"normal", p.normal_iterations}, {"tangential", p.tangential_iterations}}}});
  }
  return {{"status", ToString(r.status)},
          {"message", r.message},
          {"wheelset",
           {{"y", r.y},
            {"z", r.z},
            {"roll", r.roll},
            {"yaw", r.yaw},
            {"omega", r.omega},
            {"velocity", r.velocity}}},
          {"rail_forces_track", forces},
          {"rail_forces_wheelset", Vec(r.force_W, "fx", "fy", "fz")},
          {"t_gamma", TGamma(r)},
          {"t_gamma_slip", TGammaSlip(r)},
          {"frictional_power", FrictionalPower(r)},
          {"patches", patches},
          {"force_location", r.has_force_location ? json{{"x_tr", r.force_location_T(0)},
                                                         {"y_tr", r.force_location_T(1)},
                                                         {"z_tr", r.force_location_T(2)},
                                                         {"y_r", r.contact_y},
                                                         {"contact_angle", r.contact_angle}}
                                                  : json(nullptr)},
          {"warnings", r.warnings},
          {"iterations", {{"fz", r.fz_iterations}}},
          {"timing_s",
           {{"total", seconds},
            {"solver", r.timings.total},
            {"profiles", r.timings.profiles},
            {"search", r.timings.search},
            {"geometry", r.timings.geometry},
            {"influence", r.timings.influence},
            {"normal", r.timings.normal},
            {"tangential", r.timings.tangential}}}};
}

// Per patch: fields.csv over the patch grid, and for the curved reference its curve.
void WriteWheelRailFields(const std::filesystem::path& dir, const WheelRailResult& r,
                          const json& summary) {
  std::filesystem::create_directories(dir);
  for (std::size_t n = 0; n < r.patches.size(); ++n) {
    const PatchResult& p = r.patches[n];
    const std::string stem = "patch" + std::to_string(n + 1);
    std::ostringstream out;
    out << "i,j,x,s,h,pn,px,ps,sx,ss,wx,ws,state\n";
    out.precision(10);
    const Grid& g = p.grid;
    const bool t = !p.px.empty();
    for (int j = 0; j < g.ny; ++j) {
      for (int i = 0; i < g.nx; ++i) {
        const std::size_t k = g.index(i, j);
        out << i << ',' << j << ',' << g.x(i) << ',' << g.y(j) << ',' << p.h[k] << ',' << p.pn[k]
            << ',' << (t ? p.px[k] : 0.0) << ',' << (t ? p.ps[k] : 0.0) << ','
            << (t ? p.sx[k] : 0.0) << ',' << (t ? p.ss[k] : 0.0) << ',' << (t ? p.wx[k] : 0.0)
            << ',' << (t ? p.ws[k] : 0.0) << ',' << static_cast<int>(p.state[k]) << '\n';
      }
    }
    if (!p.curve_y.empty()) {
      std::ostringstream curve;
      curve << "j,s,y_tr,z_tr,angle\n";
      curve.precision(10);
      for (std::size_t j = 0; j < p.curve_y.size(); ++j) {
        curve << j << ',' << g.y(static_cast<int>(j)) << ',' << p.curve_y[j] << ',' << p.curve_z[j]
              << ',' << p.curve_angle[j] << '\n';
      }
      WriteFileAtomically(dir / (stem + "_curve.csv"), curve.str());
    }
    WriteFileAtomically(dir / (stem + "_fields.csv"), out.str());
  }
  WriteFileAtomically(dir / "summary.json", summary.dump(1) + '\n');
}

namespace {

// Ctrl-C or SIGTERM during a solve ends it at once, with a message (and for --json an error
// object) and exit 130: a solve cannot stop half-way, and nothing it writes is left half-written
// under its final name (outputs go to NAME.tmp and are renamed into place; the next run removes a
// leftover NAME.tmp). Only async-signal-safe calls in the handler.
volatile std::sig_atomic_t g_interrupt_as_json = 0;

extern "C" void OnSolveInterrupt(int) {
  static const char kText[] = "wrc solve: interrupted\n";
  static const char kJson[] = "{\"status\": \"error\", \"message\": \"interrupted\"}\n";
  if (g_interrupt_as_json != 0 && ::write(STDOUT_FILENO, kJson, sizeof kJson - 1) < 0) {
    // Nothing left to tell: the exit code says it.
  }
  if (::write(STDERR_FILENO, kText, sizeof kText - 1) < 0) {
  }
  ::_exit(kExitInterrupted);
}

void EndSolveOnInterrupt(bool as_json) {
  g_interrupt_as_json = as_json ? 1 : 0;
  struct sigaction action {};
  action.sa_handler = OnSolveInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace

void AddSolveCommand(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand(
      "solve", "Solve one contact case (a case file, " + DocFile("reference/case-files.md") + ")");
  auto case_path = std::make_shared<std::string>();
  auto out_dir = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  cmd->add_option("CASE", *case_path, "Case file (TOML)")->required();
  cmd->add_flag("--json", *as_json,
                "Print the result as one JSON object (" + DocFile("reference/json.md") + ")");
  cmd->add_option("--out", *out_dir, "Also write the solution fields into this directory");
  cmd->callback([=]() {
    const auto t0 = std::chrono::steady_clock::now();
    EndSolveOnInterrupt(*as_json);
    try {
      const Case c = LoadCase(*case_path);
      SolverStatus status;
      json j;
      if (c.type == CaseType::kHalfspace) {
        const HalfspaceResult r = SolveHalfspace(c);
        j = HalfspaceJson(r, Seconds(t0));
        if (!out_dir->empty()) WriteHalfspaceFields(*out_dir, r, j);
        status = r.status;
      } else {
        WheelRailOptions options;
        options.keep_fields = !out_dir->empty();
        const WheelRailResult r = SolveWheelRail(c, options);
        j = WheelRailJson(r, Seconds(t0));
        if (!out_dir->empty()) WriteWheelRailFields(*out_dir, r, j);
        status = r.status;
      }
      if (*as_json) {
        std::cout << j.dump(1) << '\n';
      } else {
        PrintHuman(j);
        if (j.contains("warnings")) {
          for (const json& w : j["warnings"]) {
            std::cerr << "wrc solve: warning: " << w.get<std::string>() << '\n';
          }
        }
      }
      *exit_code = ExitCodeFor(status);
      if (status == SolverStatus::kNotConverged) {
        std::cerr << "wrc solve: " << j["message"].get<std::string>() << '\n';
      }
    } catch (...) {
      // A message naming the problem, status "error", the exit code of its class.
      *exit_code = ReportFailure("wrc solve");
      if (*as_json) {
        const std::string message = FailureOf(std::current_exception()).message;
        std::cout << json{{"status", "error"}, {"message", message}}.dump(1) << '\n';
      }
    }
  });
}

}  // namespace wrc::cli
