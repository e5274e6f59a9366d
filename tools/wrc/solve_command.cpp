// `wrc solve CASE.toml [--json] [--out DIR]` (SPEC §3).

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "tools/wrc/commands.h"
#include "wrc/case.h"
#include "wrc/errors.h"
#include "wrc/halfspace.h"

namespace wrc::cli {
namespace {

using nlohmann::json;

int ExitCodeFor(SolverStatus s) {
  return s == SolverStatus::kNotConverged ? kExitNotConverged : kExitOk;
}

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
  }
  return {{"status", ToString(r.status)},
          {"message", message},
          {"patches", r.status == SolverStatus::kNoContact ? json::array() : json::array({patch})},
          {"iterations", iterations},
          {"timing_s", {{"total", seconds}}}};
}

// Writes the fields as CSV, one row per element of the potential contact area (format in
// docs/output-format.md), plus the JSON summary.
void WriteHalfspaceFields(const std::filesystem::path& dir, const HalfspaceResult& r,
                          const json& summary) {
  std::filesystem::create_directories(dir);
  std::ofstream out(dir / "fields.csv");
  if (!out) throw InputError("--out " + dir.string() + ": cannot write fields.csv");
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
  std::ofstream(dir / "summary.json") << summary.dump(1) << '\n';
}

}  // namespace

void AddSolveCommand(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand("solve", "Solve one contact case (SPEC §2 case file)");
  auto case_path = std::make_shared<std::string>();
  auto out_dir = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  cmd->add_option("CASE", *case_path, "Case file (TOML)")->required();
  cmd->add_flag("--json", *as_json, "Print the result as one JSON object (SPEC §3)");
  cmd->add_option("--out", *out_dir, "Also write the solution fields into this directory");
  cmd->callback([=]() {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      const Case c = LoadCase(*case_path);
      if (c.type != CaseType::kHalfspace) {
        throw InputError(*case_path + ": problem.type = \"wheel-rail\" is not implemented yet");
      }
      const HalfspaceResult r = SolveHalfspace(c);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const json j = HalfspaceJson(r, seconds);
      if (!out_dir->empty()) WriteHalfspaceFields(*out_dir, r, j);
      if (*as_json) {
        std::cout << j.dump(1) << '\n';
      } else {
        std::cout << "status " << j["status"].get<std::string>() << "\n";
        if (!j["patches"].empty()) {
          const json& p = j["patches"][0];
          std::cout << "fn " << p["fn"] << " N, fx " << p["fx"] << " N, fs " << p["fs"]
                    << " N, mn " << p["mn"] << " N.mm\npmax " << p["pmax"] << " N/mm2, approach "
                    << p["approach"] << " mm, contact " << p["n_contact"] << " elements, slip "
                    << p["n_slip"] << "\n";
        }
        std::cout << "time " << seconds << " s\n";
      }
      *exit_code = ExitCodeFor(r.status);
      if (r.status == SolverStatus::kNotConverged) {
        std::cerr << "wrc solve: " << j["message"].get<std::string>() << '\n';
      }
    } catch (const std::exception& e) {
      // Bad input of any kind: a message naming the problem, status "error", exit 2.
      std::cerr << "wrc solve: error: " << e.what() << '\n';
      if (*as_json) {
        std::cout << json{{"status", "error"}, {"message", e.what()}}.dump(1) << '\n';
      }
      *exit_code = kExitBadInput;
    }
  });
}

}  // namespace wrc::cli
