// The `wrc` command line as users run it (docs/reference/cli.md): the real binary, started through
// the shell, on reference cases and on broken input. Checks results, the files of --out, exit codes
// and that every error message names its problem.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/files.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kWrc = fs::path(WRC_BINARY_DIR) / "wrc";
const fs::path kHalfspaceCases = fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / "halfspace";

// CONTACT prints four significant digits and wrc meets the reference cases far closer than this
// (score-against-reference: < 0.01 % of the load); 0.5 % of the load is the tolerance the
// half-space reference test uses too, loose enough for any platform's round-off.
constexpr double kReferenceTolerance = 5e-3;

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

using wrc::test_support::ReadFile;

using wrc::test_support::Quoted;

// A valid half-space case (docs/reference/case-files.md, half-space cases) that the bad-input tests
// break one line at a time.
constexpr const char* kValidCase = R"([problem]
type = "halfspace"
[geometry]
a1 = 0.001087
b1 = 0.001087
[grid]
dx = 0.5
dy = 0.5
x = [-4.0, 4.0]
y = [-4.0, 4.0]
[state]
fn = 10000.0
cksi = 0.001
)";

std::vector<std::string> ValidCaseLines() {
  std::vector<std::string> lines;
  std::stringstream text(kValidCase);
  for (std::string line; std::getline(text, line);) lines.push_back(line);
  return lines;
}

class WrcCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("wrc_cli_test_" + std::to_string(::getpid()) + "_" + test->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `wrc ARGS...` with stdout and stderr captured in files of the temp dir.
  RunResult Run(const std::vector<std::string>& args) const {
    std::string command = Quoted(kWrc.string());
    for (const std::string& arg : args) command += " " + Quoted(arg);
    command +=
        " >" + Quoted((dir_ / "stdout").string()) + " 2>" + Quoted((dir_ / "stderr").string());
    const int status = std::system(command.c_str());
    RunResult result;
    if (status != -1 && WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
    result.out = ReadFile(dir_ / "stdout");
    result.err = ReadFile(dir_ / "stderr");
    return result;
  }

  // Writes the valid case with line `index` (0-based) replaced, returns the file's path.
  fs::path WriteCase(int index, const std::string& replacement) const {
    const fs::path path = dir_ / "case.toml";
    const std::vector<std::string> lines = ValidCaseLines();
    std::ofstream out(path);
    for (int k = 0; k < static_cast<int>(lines.size()); ++k) {
      out << (k == index ? replacement : lines[k]) << '\n';
    }
    return path;
  }

  // Index (0-based) of the line `text` in the valid case; messages count lines from 1.
  static int IndexOf(const std::string& text) {
    const std::vector<std::string> lines = ValidCaseLines();
    for (int k = 0; k < static_cast<int>(lines.size()); ++k) {
      if (lines[k] == text) return k;
    }
    ADD_FAILURE() << "no line '" << text << "' in the valid case";
    return 0;
  }

  fs::path dir_;
};

json ReferencePatch(const std::string& name) {
  return json::parse(ReadFile(kHalfspaceCases / (name + ".contact.json")))["patches"][0];
}

TEST_F(WrcCli, ApproachPrescribedForceMatchesContact) {
  // The approach is prescribed, so fn is a result, not an input echoed back.
  const RunResult run =
      Run({"solve", (kHalfspaceCases / "ab1_approach0.02.toml").string(), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json result = json::parse(run.out);
  EXPECT_EQ(result["status"], "ok");
  ASSERT_EQ(result["patches"].size(), 1u);
  const double fn_reference = ReferencePatch("ab1_approach0.02")["fn"].get<double>();
  EXPECT_NEAR(result["patches"][0]["fn"].get<double>(), fn_reference,
              kReferenceTolerance * fn_reference);
}

TEST_F(WrcCli, RollingForcesMatchContact) {
  const RunResult run = Run({"solve", (kHalfspaceCases / "ab1_cksi0.001.toml").string(), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json result = json::parse(run.out);
  EXPECT_EQ(result["status"], "ok");
  ASSERT_EQ(result["patches"].size(), 1u);
  const json reference = ReferencePatch("ab1_cksi0.001");
  const double fn_reference = reference["fn"].get<double>();
  const json& patch = result["patches"][0];
  EXPECT_NEAR(patch["fn"].get<double>(), fn_reference, kReferenceTolerance * fn_reference);
  EXPECT_NEAR(patch["fx"].get<double>(), reference["fx"].get<double>(),
              kReferenceTolerance * fn_reference);
  // The extras of docs/output-format.md add up: every contact element sticks or slips.
  EXPECT_EQ(patch["n_adh"].get<int>() + patch["n_slip"].get<int>(), patch["n_contact"].get<int>());
  EXPECT_EQ(patch["n_pot"].get<int>(), reference["n_pot"].get<int>());
  EXPECT_GT(result["iterations"]["normal"].get<int>(), 0);
  EXPECT_GT(result["iterations"]["tangential"].get<int>(), 0);
}

TEST_F(WrcCli, OutWritesFieldsThatSumToTheForces) {
  const fs::path out_dir = dir_ / "solution";
  const RunResult run = Run({"solve", (kHalfspaceCases / "ab1_cksi0.001.toml").string(), "--json",
                             "--out", out_dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const json patch = json::parse(run.out)["patches"][0];
  const json summary = json::parse(ReadFile(out_dir / "summary.json"));
  EXPECT_EQ(summary["patches"][0]["fn"], patch["fn"]);

  std::ifstream csv(out_dir / "fields.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line, "i,j,x,y,h,pn,px,py,sx,sy,state");
  constexpr double kCellArea = 0.28 * 0.28;  // dx · dy of the case file, mm².
  double fn = 0.0, fx = 0.0;
  int rows = 0, adhesion = 0, slip = 0;
  while (std::getline(csv, line)) {
    std::vector<double> v;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 11u) << line;
    const double pn = v[5], px = v[6], state = v[10];
    fn += pn * kCellArea;
    fx += px * kCellArea;
    if (state == 1.0) ++adhesion;
    if (state == 2.0) ++slip;
    // Exterior elements carry no pressure; in the contact, |p_t| <= μ·p_n (μ = 0.3, plus the
    // 10 printed digits' round-off).
    if (state == 0.0) {
      EXPECT_EQ(pn, 0.0) << line;
    }
    EXPECT_LE(std::hypot(px, v[7]), 0.3 * pn * (1.0 + 1e-9) + 1e-12) << line;
    ++rows;
  }
  EXPECT_EQ(rows, patch["n_pot"].get<int>());
  EXPECT_EQ(adhesion, patch["n_adh"].get<int>());
  EXPECT_EQ(slip, patch["n_slip"].get<int>());
  // The CSV holds 10 significant digits: its sums meet the totals to ~1e-10; 1e-6 leaves room.
  const double fn_total = patch["fn"].get<double>();
  EXPECT_NEAR(fn, fn_total, 1e-6 * fn_total);
  EXPECT_NEAR(fx, patch["fx"].get<double>(), 1e-6 * fn_total);
}

TEST_F(WrcCli, MissingFileIsBadInput) {
  const std::string missing = (dir_ / "no_such_case.toml").string();
  const RunResult run = Run({"solve", missing});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find(missing), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("cannot open"), std::string::npos) << run.err;
}

TEST_F(WrcCli, UnknownKeyIsBadInput) {
  const int index = IndexOf("dx = 0.5");
  const RunResult run = Run({"solve", WriteCase(index, "dxx = 0.1").string()});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("case.toml:" + std::to_string(index + 1)), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("grid.dxx"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("unknown key"), std::string::npos) << run.err;
}

TEST_F(WrcCli, NegativeElementSizeIsBadInput) {
  const int index = IndexOf("dx = 0.5");
  const RunResult run = Run({"solve", WriteCase(index, "dx = -0.1").string()});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("case.toml:" + std::to_string(index + 1)), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("grid.dx = -0.1"), std::string::npos) << run.err;
}

TEST_F(WrcCli, NanValueIsBadInput) {
  const int index = IndexOf("fn = 10000.0");
  const RunResult run = Run({"solve", WriteCase(index, "fn = nan").string(), "--json"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("case.toml:" + std::to_string(index + 1)), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("state.fn = nan"), std::string::npos) << run.err;
  // With --json, stdout still holds one JSON object, with status "error" (docs/reference/cli.md).
  const json result = json::parse(run.out);
  EXPECT_EQ(result["status"], "error");
  EXPECT_NE(result["message"].get<std::string>().find("state.fn"), std::string::npos);
}

// Without grid.x and grid.y the grid follows the Hertz contact of the load: one it cannot build
// names the keys it came from, not the grid library's call.
TEST_F(WrcCli, AGridTheLoadCannotHaveNamesItsKeys) {
  const fs::path path = dir_ / "case.toml";
  std::ofstream(path) << "[problem]\ntype = \"halfspace\"\n[geometry]\na1 = 0.001087\n"
                         "b1 = 0.001087\n[grid]\ndx = 0.5\ndy = 0.5\n[state]\nfn = 1e12\n";
  const RunResult run = Run({"solve", path.string()});
  EXPECT_EQ(run.exit_code, 2);
  for (const char* named : {"case.toml", "state.fn = 1e+12 N", "grid.dx = 0.5", "geometry.a1"}) {
    EXPECT_NE(run.err.find(named), std::string::npos) << named << ": " << run.err;
  }
}

TEST_F(WrcCli, TomlSyntaxErrorIsBadInput) {
  const int index = IndexOf("dx = 0.5");
  const RunResult run = Run({"solve", WriteCase(index, "dx = = 0.5").string()});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("case.toml:" + std::to_string(index + 1)), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("syntax error"), std::string::npos) << run.err;
}

TEST_F(WrcCli, UnknownSubcommandIsBadInput) {
  const RunResult run = Run({"frobnicate"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("frobnicate"), std::string::npos) << run.err;
}

TEST_F(WrcCli, NoArgumentsIsBadInput) {
  const RunResult run = Run({});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("subcommand"), std::string::npos) << run.err;
}

TEST_F(WrcCli, HelpListsSubcommandsAndOptions) {
  const RunResult top = Run({"--help"});
  EXPECT_EQ(top.exit_code, 0) << top.err;
  EXPECT_NE(top.out.find("solve"), std::string::npos) << top.out;

  const RunResult solve = Run({"solve", "--help"});
  EXPECT_EQ(solve.exit_code, 0) << solve.err;
  for (const char* option : {"CASE", "--json", "--out"}) {
    EXPECT_NE(solve.out.find(option), std::string::npos) << option << " missing in\n" << solve.out;
  }
}

}  // namespace
