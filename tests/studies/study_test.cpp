// `wrc study` as a user runs it: from a directory outside the checkout, on the user's own case
// and scene files (with their profiles next to them), writing CSV, PNG and a Markdown summary
// into --out.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/tools/tool_test_util.h"

namespace {

namespace fs = std::filesystem;

using wrc::tool_test::kSource;
using wrc::tool_test::ReadFile;

// The CSV's rows after the header, split at commas (no quoted commas in the columns read).
std::vector<std::vector<std::string>> CsvRows(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream text(ReadFile(path));
  std::string line;
  std::getline(text, line);  // header
  while (std::getline(text, line)) {
    std::vector<std::string> cells;
    std::stringstream cellstream(line);
    for (std::string cell; std::getline(cellstream, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

bool IsPng(const fs::path& path) {
  return fs::is_regular_file(path) && ReadFile(path).substr(1, 3) == "PNG";
}

bool HaveGnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

// A user's working directory outside the checkout, holding copies of the shipped cases and
// the profiles they name.
class Study : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("wrc_study_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "profiles");
    for (const char* name : {"MBench_UIC60_v3.prr", "MBench_S1002_v3.prw"}) {
      fs::copy_file(kSource / "tables" / "profiles" / name, dir_ / "profiles" / name);
    }
    fs::copy_file(kSource / "tables" / "hertz_demo.toml", dir_ / "hertz.toml");
    // The shipped Manchester case with 1 mm elements, to keep every solve short.
    std::string text = ReadFile(kSource / "tables" / "mbench_case.toml");
    text.replace(text.find("dx = 0.5"), 8, "dx = 1.0");
    text.replace(text.find("ds = 0.5"), 8, "ds = 1.0");
    std::ofstream(dir_ / "mbench.toml") << text;
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `wrc ARGS` in the user's directory; stdout and stderr go to files there.
  int Run(const std::string& args) const { return wrc::tool_test::RunWrcIn(dir_, args, 120); }
  std::string Err() const { return ReadFile(dir_ / "stderr.txt"); }
  std::string Out() const { return ReadFile(dir_ / "stdout.txt"); }

  fs::path dir_;
};

TEST_F(Study, SolverRunsOnTheUsersCases) {
  ASSERT_EQ(Run("study solver hertz.toml mbench.toml --sizes 0.5,0.25 --out out"), 0) << Err();
  const auto rows = CsvRows(dir_ / "out" / "solver.csv");
  ASSERT_EQ(rows.size(), 4u);  // two cases at two sizes
  for (const auto& row : rows) {
    ASSERT_GE(row.size(), 11u);
    EXPECT_EQ(row[3], "ok");
    const double fz = std::stod(row[6]);
    // Both cases prescribe the normal (vertical) force: 10 kN, whatever the element size.
    EXPECT_NEAR(fz, 1e4, 0.05) << row[0];
    // The finest size is the reference: its own errors are zero.
    if (row[1] == "0.25") {
      EXPECT_EQ(std::stod(row[9]), 0.0) << row[0];
    }
  }
  // Hertz: the approach of the half-space case is 0.022628 mm; within 3 % at 0.25 mm elements.
  EXPECT_NEAR(std::stod(rows[1][7]), 0.022628, 0.03 * 0.022628);
  EXPECT_NE(ReadFile(dir_ / "out" / "solver.md").find("| hertz.toml | 0.5 |"), std::string::npos);
  if (HaveGnuplot()) {
    EXPECT_TRUE(IsPng(dir_ / "out" / "solver.png"));
  }
}

TEST_F(Study, StabilitySweepsTheUsersCase) {
  ASSERT_EQ(Run("study stability mbench.toml --sweep y --from 0 --to 2 --step 1 "
                "--methods planar,curved --threads 2 --out out"),
            0)
      << Err();
  const auto rows = CsvRows(dir_ / "out" / "mbench_y.csv");
  ASSERT_EQ(rows.size(), 6u);  // two methods at three positions
  for (const auto& row : rows) {
    EXPECT_EQ(row[3], "ok");
    EXPECT_NEAR(std::stod(row[6]), 1e4, 1e-2);  // the case's prescribed fz
  }
  EXPECT_EQ(rows[1][2], "1");  // the swept values, in order
  EXPECT_NE(ReadFile(dir_ / "out" / "README.md").find("| mbench_y | curved | 3 | 3 |"),
            std::string::npos);
  if (HaveGnuplot()) {
    EXPECT_TRUE(IsPng(dir_ / "out" / "mbench_y.png"));
  }
}

TEST_F(Study, TablesRunsOnTheUsersScene) {
  std::string scene = ReadFile(dir_ / "mbench.toml");
  scene.replace(scene.find("y = 4.0  # mm\n"), 14, "");
  scene += "[table]\naxes = [\"y\"]\ny = [0.0, 2.0, 4.0]\noutputs = [\"fx\", \"fy\", \"fz\"]\n";
  std::ofstream(dir_ / "scene.toml") << scene;
  ASSERT_EQ(Run("study tables scene.toml --targets 0.2 --samples 4 --threads 2 --uniform "
                "--midpoint-rule 0.002 --out out"),
            0)
      << Err();
  const auto rows = CsvRows(dir_ / "out" / "tables.csv");
  // The refined table, its uniform twin, then every pass of the midpoint rule's run.
  ASSERT_GE(rows.size(), 4u) << Err();
  EXPECT_EQ(rows[0][0], "refined");
  EXPECT_EQ(rows[1][0], "uniform");
  EXPECT_EQ(rows[0][3], rows[1][3]);  // the same number of points, by construction
  for (std::size_t r = 2; r < rows.size(); ++r) {
    EXPECT_EQ(rows[r][0], "midpoint_rule");
    EXPECT_EQ(rows[r][2], std::to_string(r - 2));  // the pass
    EXPECT_GT(std::stod(rows[r][5]), 0.0);         // its CPU time so far
    if (r > 2) {
      EXPECT_GT(std::stod(rows[r][3]), std::stod(rows[r - 1][3]));  // points grow
    }
  }
  EXPECT_TRUE(fs::is_regular_file(dir_ / "out" / "tables.md"));
  if (HaveGnuplot()) {
    EXPECT_TRUE(IsPng(dir_ / "out" / "tables.png"));
  }
}

// The Manchester case of the fixture as a scene with `table` (its [table] section): the state's
// axis quantities removed, so that the axes give them.
std::string TableScene(const fs::path& dir, const std::string& table) {
  std::string scene = ReadFile(dir / "mbench.toml");
  for (const char* key : {"y = 4.0  # mm\n", "yaw = 0.002  # rad\n", "fz = 10000.0  # N\n"}) {
    scene.replace(scene.find(key), std::string(key).size(), "");
  }
  return scene + table;
}

// From the user's directory, with no --model: the shipped wheelset compiled in. The creep terms
// of the linearised contact (∂Fy/∂ψ, ∂Mz/∂vyaw) come from the yaw and spin axes, whose nodes at
// ±2e-4 make the table's secants those of the solver's ±1e-4 steps within 1 %; 10 % tells a
// wrong wheelset, wheel or sign apart. (The slopes along y are not compared: on this pair the
// forces bend sharply within ±1 mm of the centre, which a table this coarse does not follow.)
TEST_F(Study, DynamicsRunsWithTheShippedWheelsetFromAnyDirectory) {
  const std::string scene =
      TableScene(dir_,
                 "[table]\naxes = [\"y_wheel\", \"fz\", \"roll\", \"yaw\", \"spin\"]\n"
                 "y_wheel = [-1.0, 0.0, 1.0]\nfz = [12500.0]\nroll = [-0.001, 0.0, 0.001]\n"
                 "yaw = [-0.0002, 0.0, 0.0002]\nspin = [-0.0002, 0.0, 0.0002]\n"
                 "outputs = [\"fx\", \"fy\", \"fz\", \"mx\", \"my\", \"mz\", \"z\"]\n");
  std::ofstream(dir_ / "scene.toml") << scene;
  ASSERT_EQ(Run("generate scene.toml -o t.h5 --threads 2"), 0) << Err();
  ASSERT_EQ(Run("study dynamics t.h5 --linear-only --out out"), 0) << Err();
  const auto rows = CsvRows(dir_ / "out" / "linear.csv");
  ASSERT_EQ(rows.size(), 4u);  // table and solver at y = 0 and at the disturbance
  ASSERT_EQ(rows[0][0], "table");
  ASSERT_EQ(rows[1][0], "solver");
  ASSERT_EQ(rows[0][1], "0");
  for (const int column : {4, 10}) {  // dfy_dyaw, dmz_dvyaw
    const double table = std::stod(rows[0][column]), solver = std::stod(rows[1][column]);
    EXPECT_NEAR(table / solver, 1.0, 0.1) << column;
  }
  const std::string md = ReadFile(dir_ / "out" / "README.md");
  EXPECT_NE(md.find("wheel load 12500 N"), std::string::npos) << md;  // the shipped wheelset
  EXPECT_EQ(md.find("--model"), std::string::npos) << md;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "speeds.csv"));  // no runs asked for
  // The path along y at centred running: the pair is symmetric, so each source's Fy and Mz are
  // odd in y (the table to rounding, the solver to its force tolerance, 1e-6 of the load).
  const auto path = CsvRows(dir_ / "out" / "centred.csv");
  ASSERT_EQ(path.size(), 401u);
  for (std::size_t i = 0; i < path.size(); ++i) {
    const auto& a = path[i];
    const auto& b = path[path.size() - 1 - i];
    EXPECT_DOUBLE_EQ(std::stod(a[0]), -std::stod(b[0]));
    for (const int column : {1, 3}) {  // fy of the table and of the solver, N
      EXPECT_NEAR(std::stod(a[column]), -std::stod(b[column]), 0.05) << a[0] << ' ' << column;
    }
  }
  EXPECT_NE(md.find("### Along y at centred running"), std::string::npos) << md;
}

// --vehicle: the contact linearised at the vehicle's wheel load, and the bogie's linear critical
// speed and hunting frequencies on each source. The tiny table's slopes are the solver's
// secants in y (nodes at its ±0.25 mm steps) and secants over 2e-4 in yaw and spin (within 1 % of
// the solver's there); 10 % tells a wrong load, source or unit apart.
TEST_F(Study, DynamicsGivesTheVehiclesLinearCriticalSpeed) {
  const std::string scene =
      TableScene(dir_,
                 "[table]\naxes = [\"y_wheel\", \"fz\", \"roll\", \"yaw\", \"spin\"]\n"
                 "y_wheel = [-0.5, -0.25, 0.0, 0.25, 0.5]\nfz = [50000.0, 60000.0]\nroll = "
                 "[-0.001, 0.0, 0.001]\n"
                 "yaw = [-0.0002, 0.0, 0.0002]\nspin = [-0.0002, 0.0, 0.0002]\n"
                 "outputs = [\"fx\", \"fy\", \"fz\", \"mx\", \"my\", \"mz\", \"z\"]\n");
  std::ofstream(dir_ / "scene.toml") << scene;
  ASSERT_EQ(Run("generate scene.toml -o t.h5 --threads 2"), 0) << Err();
  const fs::path vehicle = kSource / "tables" / "manchester_vehicle.toml";
  ASSERT_EQ(Run("study dynamics t.h5 --linear-only --vehicle " + vehicle.string() + " --out out"),
            0)
      << Err();
  const auto rows = CsvRows(dir_ / "out" / "vehicle.csv");
  ASSERT_EQ(rows.size(), 4u);  // table and solver at two speeds each
  ASSERT_EQ(rows[0][0], "table");
  ASSERT_EQ(rows[2][0], "solver");
  const double table = std::stod(rows[0][1]), solver = std::stod(rows[2][1]);
  EXPECT_GT(solver, 10.0);   // m/s: a bogie that hunts below 10 m/s is a wrong model or unit
  EXPECT_LT(solver, 300.0);  // and one found above the search range is none
  EXPECT_NEAR(table / solver, 1.0, 0.1);
  EXPECT_EQ(rows[0][2], rows[2][2]);  // the frequencies at the same speeds
  const std::string md = ReadFile(dir_ / "out" / "README.md");
  EXPECT_NE(md.find("wheel load 54546 N"), std::string::npos) << md;  // the vehicle's
  EXPECT_NE(md.find("linear critical speed"), std::string::npos) << md;
  EXPECT_FALSE(fs::exists(dir_ / "out" / "speeds.csv"));  // no runs asked for

  // --solver-elements: the solver source alone at other elements (here 2 mm, twice the fixture's,
  // so that the check is quick): its derivatives move, the table's stay, the summary says so.
  ASSERT_EQ(Run("study dynamics t.h5 --linear-only --vehicle " + vehicle.string() +
                " --solver-elements 2 --out coarse"),
            0)
      << Err();
  const auto fine = CsvRows(dir_ / "out" / "linear.csv");
  const auto coarse = CsvRows(dir_ / "coarse" / "linear.csv");
  ASSERT_EQ(fine.size(), coarse.size());
  ASSERT_EQ(fine[1][0], "solver");
  EXPECT_EQ(coarse[0], fine[0]);  // the table's row
  EXPECT_GT(std::fabs(std::stod(coarse[1][3]) / std::stod(fine[1][3]) - 1.0), 1e-3);  // dfy_dy
  EXPECT_NE(ReadFile(dir_ / "coarse" / "README.md").find("--solver-elements 2"), std::string::npos);

  // The bogie integrated in time on the table, from a disturbance inside its central ±0.25 mm:
  // its critical speed by bisection on the growth rate is the eigenvalues' above, on the same
  // table's linearised contact (an independent computation: Eigen's eigensolver against RK4
  // trajectories). 2 %: the bisection's 0.05 m/s and the growth rate's fit over a few cycles,
  // but mostly the table's kink at its node y = 0: the slopes differ on either side, the
  // eigenvalues see their mean, a trajectory both (measured: 1.1 %).
  std::string file = ReadFile(vehicle);
  file.replace(file.find("initial_y = 1.0"), 15, "initial_y = 0.1");
  std::ofstream(dir_ / "vehicle.toml") << file;
  ASSERT_EQ(
      Run("study dynamics t.h5 --no-solver --vehicle vehicle.toml --speeds 60,100 --out runs"), 0)
      << Err();
  const std::string said = Err();
  const std::string key = "critical speed by time integration ";
  ASSERT_NE(said.find(key), std::string::npos) << said;
  const double integrated = std::stod(said.substr(said.find(key) + key.size()));
  EXPECT_NEAR(integrated / table, 1.0, 0.02) << said;
  const auto runs = CsvRows(dir_ / "runs" / "speeds.csv");
  EXPECT_GT(runs.size(), 4u);  // the sweep and the bisection's runs
  EXPECT_NE(ReadFile(dir_ / "runs" / "README.md").find("of the leading wheelset"),
            std::string::npos);

  // The same runs on the table's cubic interpolation: between the nodes at ±0.25 mm the bogie
  // meets other forces (C¹ in place of piecewise linear), so its growth rates change, and the
  // summary names the option as a user would repeat it.
  ASSERT_EQ(Run("study dynamics t.h5 --no-solver --vehicle vehicle.toml --speeds 60,100 "
                "--interpolation cubic --out cubic"),
            0)
      << Err();
  const auto cubic = CsvRows(dir_ / "cubic" / "speeds.csv");
  ASSERT_GE(cubic.size(), 2u);
  double largest_change = 0.0;  // of the growth rate at the swept speeds, 1/s
  for (std::size_t i = 0; i < 2; ++i) {
    ASSERT_EQ(cubic[i][1], runs[i][1]);  // the same speed
    largest_change =
        std::max(largest_change, std::fabs(std::stod(cubic[i][3]) - std::stod(runs[i][3])));
  }
  EXPECT_GT(largest_change, 1e-3);
  EXPECT_NE(ReadFile(dir_ / "cubic" / "README.md").find("--interpolation cubic"),
            std::string::npos);
  EXPECT_EQ(ReadFile(dir_ / "runs" / "README.md").find("--interpolation"), std::string::npos);
  // --no-runs: the curves without the time integrations.
  ASSERT_EQ(Run("study dynamics t.h5 --no-solver --no-runs --vehicle vehicle.toml --out curves"), 0)
      << Err();
  EXPECT_TRUE(fs::exists(dir_ / "curves" / "curving.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "curves" / "speeds.csv"));
  EXPECT_EQ(Run("study dynamics t.h5 --no-solver --interpolation spline"), 2);
  EXPECT_NE(Err().find("--interpolation"), std::string::npos) << Err();
}

TEST_F(Study, HelpShowsTheDefaults) {
  ASSERT_EQ(Run("study tables --help"), 0) << Err();
  EXPECT_NE(Out().find("1000"), std::string::npos) << Out();          // --samples
  EXPECT_NE(Out().find("study-tables"), std::string::npos) << Out();  // --out
  ASSERT_EQ(Run("study solver --help"), 0) << Err();
  EXPECT_NE(Out().find("0.25"), std::string::npos) << Out();  // --sizes
  ASSERT_EQ(Run("study stability --help"), 0) << Err();
  EXPECT_NE(Out().find("planar-icp"), std::string::npos) << Out();  // --methods
  EXPECT_NE(Out().find("study-stability"), std::string::npos) << Out();
}

TEST_F(Study, BadInputIsAnErrorNamingIt) {
  EXPECT_EQ(Run("study solver missing.toml"), 2);
  EXPECT_NE(Err().find("missing.toml"), std::string::npos) << Err();
  EXPECT_EQ(Run("study solver hertz.toml --sizes 0.5"), 2);
  EXPECT_NE(Err().find("--sizes"), std::string::npos) << Err();
  EXPECT_EQ(Run("study stability hertz.toml"), 2);
  EXPECT_NE(Err().find("wheel-rail"), std::string::npos) << Err();
  EXPECT_EQ(Run("study stability"), 2);
  EXPECT_NE(Err().find("--profiles"), std::string::npos) << Err();
}

}  // namespace
