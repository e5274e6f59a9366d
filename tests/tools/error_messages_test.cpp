// Bad input to `wrc solve` (docs/reference/cli.md): each mistake a user can make in a wheel-rail
// case or its profiles gives exit code 2 and one message on stderr that names the file, the line or
// key and the offending value; a wheel that does not touch the rail is no error (status no_contact,
// exit 0). Runs the real binary, like cli_test.cpp.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kWrcBinary = fs::path(WRC_BINARY_DIR) / "wrc";
const fs::path kProfiles = fs::path(WRC_TEST_DATA_DIR) / "profiles";

// The Manchester benchmark pair with coarse elements, pressed 0.3 mm together (about 30 kN):
// every case below fails, or finds no contact, before any fine solve, so the tests stay fast.
std::vector<std::string> ValidWheelRailCaseLines() {
  return {
      "[problem]", "type = \"wheel-rail\"",
      "[rail]",    "profile = '" + (kProfiles / "MBench_UIC60_v3.prr").string() + "'",
      "[wheel]",   "profile = '" + (kProfiles / "MBench_S1002_v3.prw").string() + "'",
      "[grid]",    "dx = 0.5",
      "ds = 0.5",  "[state]",
      "y = 0.0",   "z = 0.3",
      "yaw = 0.0", "velocity = 2000.0",
  };
}

struct WrcRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string FileText(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Single-quoted for the shell, with embedded single quotes closed and reopened.
std::string ShellWord(const std::string& word) {
  std::string quoted = "'";
  for (const char c : word) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

class ErrorMessages : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test_name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() /
           ("wrc_error_messages_" + std::to_string(::getpid()) + "_" + test_name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  WrcRun Solve(const fs::path& case_file, bool as_json = false) const {
    return Wrc("solve " + ShellWord(case_file) + (as_json ? " --json" : ""));
  }

  // `wrc ARGUMENTS` (already quoted for the shell).
  WrcRun Wrc(const std::string& arguments) const {
    std::string command = ShellWord(kWrcBinary.string()) + " " + arguments;
    command += " >" + ShellWord(dir_ / "stdout") + " 2>" + ShellWord(dir_ / "stderr");
    const int status = std::system(command.c_str());
    WrcRun run;
    if (status != -1 && WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
    run.out = FileText(dir_ / "stdout");
    run.err = FileText(dir_ / "stderr");
    return run;
  }

  fs::path WriteFile(const std::string& name, const std::string& text) const {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }

  // The valid case with the line `original` replaced by `replacement`; `line_number` gets the
  // replaced line's number (1-based), as messages count it.
  fs::path WriteCaseWith(const std::string& original, const std::string& replacement,
                         int* line_number = nullptr) const {
    std::vector<std::string> lines = ValidWheelRailCaseLines();
    bool found = false;
    std::string text;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (lines[i] == original) {
        lines[i] = replacement;
        found = true;
        if (line_number != nullptr) *line_number = static_cast<int>(i) + 1;
      }
      text += lines[i] + "\n";
    }
    EXPECT_TRUE(found) << "no line '" << original << "' in the valid case";
    return WriteFile("case.toml", text);
  }

  // The valid case reading its rail profile from `rail_file` (relative to the case file).
  fs::path WriteCaseWithRail(const std::string& rail_file, int* line_number = nullptr) const {
    return WriteCaseWith(ValidWheelRailCaseLines()[3], "profile = \"" + rail_file + "\"",
                         line_number);
  }

  fs::path dir_;
};

// Checks exit code 2 and that stderr holds every one of `parts`.
void ExpectBadInput(const WrcRun& run, const std::vector<std::string>& parts) {
  EXPECT_EQ(run.exit_code, 2) << run.err;
  for (const std::string& part : parts) {
    EXPECT_NE(run.err.find(part), std::string::npos) << "'" << part << "' missing in: " << run.err;
  }
}

TEST_F(ErrorMessages, ValidCaseSolves) {
  // The base every other test breaks: without this, a failure below could hide a broken base.
  std::string text;
  for (const std::string& line : ValidWheelRailCaseLines()) text += line + "\n";
  const WrcRun run = Solve(WriteFile("case.toml", text), /*as_json=*/true);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["status"], "ok");
}

TEST_F(ErrorMessages, MissingCaseFile) {
  const fs::path missing = dir_ / "no_such_case.toml";
  ExpectBadInput(Solve(missing), {missing.string(), "cannot open"});
}

TEST_F(ErrorMessages, ATableGivenAsCaseIsNamedSo) {
  // HDF5's signature at 0 and after a 512-byte user block; then any binary file.
  const std::string signature("\x89HDF\r\n\x1a\n", 8);
  ExpectBadInput(Solve(WriteFile("table.h5", signature + std::string(100, '\0'))),
                 {"table.h5", "an HDF5 file (a wrc table?), not a TOML case", "wrc info"});
  ExpectBadInput(Solve(WriteFile("ub.h5", std::string(512, '\0') + signature)),
                 {"ub.h5", "an HDF5 file"});
  ExpectBadInput(Solve(WriteFile("blob.bin", std::string("a = 1\0", 6))),
                 {"blob.bin", "a binary file (it holds NUL bytes)"});
}

TEST_F(ErrorMessages, MissingProfileFile) {
  int line = 0;
  const fs::path case_file = WriteCaseWithRail("no_such_rail.prr", &line);
  ExpectBadInput(Solve(case_file), {"case.toml:" + std::to_string(line),
                                    "rail.profile = \"no_such_rail.prr\"", "not found"});
}

// A broken profile is reported at the case key that names it: the message starts with the case
// file, line, key and value as written, then gives the profile's own file, line and problem.
class ProfileErrorMessages : public ErrorMessages {
 protected:
  // Solves the valid case reading its rail from `rail_file` (written next to the case) and
  // expects exit code 2 and a message that starts with the case's location and key and holds
  // every one of `parts`.
  void ExpectRailError(const std::string& rail_file, const std::vector<std::string>& parts) {
    int line = 0;
    const fs::path case_file = WriteCaseWithRail(rail_file, &line);
    const WrcRun run = Solve(case_file);
    const std::string prefix = "wrc solve: error: " + case_file.string() + ":" +
                               std::to_string(line) + ": rail.profile = \"" + rail_file + "\": ";
    EXPECT_EQ(run.err.rfind(prefix, 0), 0u) << run.err << "\nexpected to start with " << prefix;
    ExpectBadInput(run, parts);
  }
};

TEST_F(ProfileErrorMessages, GarbageProfile) {
  WriteFile("garbage.prr", "this is not a profile\n\x01\x02\x7f binary junk\n");
  ExpectRailError("garbage.prr", {(dir_ / "garbage.prr:2:").string(), "not a Simpack profile"});
}

TEST_F(ProfileErrorMessages, TextInProfileData) {
  WriteFile("rail.csv", "y,z\n-10,0\n-5,0.1\n0,0\nfive,0.1\n10,0\n");
  ExpectRailError("rail.csv",
                  {(dir_ / "rail.csv:5:").string(), "'five' is not a number (in 'five,0.1')"});
}

TEST_F(ProfileErrorMessages, NanInProfile) {
  WriteFile("rail.csv", "-10,0\n-5,0.1\n0,nan\n5,0.1\n10,0\n");
  ExpectRailError("rail.csv",
                  {(dir_ / "rail.csv:3:").string(), "value 'nan' is not a finite number"});
}

TEST_F(ProfileErrorMessages, ProfileWithTwoPoints) {
  WriteFile("rail.csv", "-10,0\n10,0\n");
  ExpectRailError("rail.csv",
                  {(dir_ / "rail.csv:2:").string(), "only 2 profile point(s)", "at least 4"});
}

TEST_F(ProfileErrorMessages, ProfileUnits) {
  // A Simpack rail whose units.len.f is not positive, and a table in metres.
  WriteFile("units.prr",
            "spline.begin\n units.len.f = 0\n point.begin\n 0 0\n 5 0\n 10 0\n 15 0\n"
            " point.end\nspline.end\n");
  ExpectRailError("units.prr",
                  {(dir_ / "units.prr:2:").string(), "units.len.f = '0' must be positive"});
  WriteFile("metres.csv", "-0.01,0\n-0.005,0.0001\n0,0\n0.005,0.0001\n0.01,0\n");
  ExpectRailError("metres.csv",
                  {(dir_ / "metres.csv").string(), "profile length 0.02", "outside [5, 500] mm"});
}

TEST_F(ErrorMessages, UnknownKey) {
  int line = 0;
  const fs::path case_file = WriteCaseWith("dx = 0.5", "dxx = 0.5", &line);
  ExpectBadInput(Solve(case_file), {"case.toml:" + std::to_string(line), "grid.dxx = 0.5",
                                    "unknown key", "did you mean grid.dx?"});
}

TEST_F(ErrorMessages, WrongType) {
  int line = 0;
  const fs::path case_file = WriteCaseWith("dx = 0.5", "dx = \"fine\"", &line);
  ExpectBadInput(Solve(case_file),
                 {"case.toml:" + std::to_string(line), "grid.dx = \"fine\"", "must be a number"});
}

TEST_F(ErrorMessages, NegativeElementSize) {
  int line = 0;
  const fs::path case_file = WriteCaseWith("dx = 0.5", "dx = -0.5", &line);
  ExpectBadInput(Solve(case_file),
                 {"case.toml:" + std::to_string(line), "grid.dx = -0.5", "must be positive"});
}

// Values that used to be solved into a wrong answer with status ok: a speed so small that the
// creepage arithmetic underflows (1e-200 mm/s gave fx 0.5 N where 2 kN is right), friction
// angles beyond any contact angle, and a scene axis that leaves the case file's range.
TEST_F(ErrorMessages, ValuesOutsideTheirRangesNameTheirKey) {
  int line = 0;
  const fs::path slow = WriteCaseWith("velocity = 2000.0", "velocity = 1e-200", &line);
  ExpectBadInput(Solve(slow), {"case.toml:" + std::to_string(line), "state.velocity = 1e-200",
                               "at least 0.001 mm/s"});
  ExpectBadInput(Solve(WriteCaseWith("ds = 0.5",
                                     "ds = 0.5\n[friction]\nmu = [0.25, 0.3]\nalpha_deg = "
                                     "[-1e308, 1e308]")),
                 {"friction.alpha_deg[0] = -1e+308", "must lie within ±90"});
  const std::string scene_text = FileText(WriteCaseWith("y = 0.0", "y = 0.0")) +
                                 "[table]\naxes = [\"spin\"]\nspin = [-2.0, 0.0]\n";
  const fs::path scene = WriteFile("scene.toml", scene_text);
  const WrcRun run = Wrc("generate " + ShellWord(scene) + " -o " + ShellWord(dir_ / "t.h5"));
  ExpectBadInput(
      run, {"scene.toml", "table.spin", "at the corner spin = -2", "state.spin must be within ±1"});
  EXPECT_FALSE(fs::exists(dir_ / "t.h5"));
}

TEST_F(ErrorMessages, NanInState) {
  int line = 0;
  const fs::path case_file = WriteCaseWith("y = 0.0", "y = nan", &line);
  const WrcRun run = Solve(case_file, /*as_json=*/true);
  ExpectBadInput(run, {"case.toml:" + std::to_string(line), "state.y = nan", "finite"});
  // With --json, stdout still holds one object with status "error" (docs/reference/cli.md).
  EXPECT_EQ(nlohmann::json::parse(run.out)["status"], "error");
}

TEST_F(ErrorMessages, LateralPositionOutOfRange) {
  // The wheel, 500 mm to the side, lies nowhere above the rail: bad input, not "no contact".
  const fs::path case_file = WriteCaseWith("y = 0.0", "y = 500.0");
  ExpectBadInput(Solve(case_file), {"case.toml", "y = 500"});
}

// A track or wheelset that puts the wheel beside its rail names every key that places the wheel
// sideways, with the value that did it, not only state.y.
TEST_F(ErrorMessages, WheelBesideTheRailNamesThePlacingKeys) {
  struct Placement {
    const char* lines;  // inserted before [grid]
    const char* named;  // what the message must say
  };
  for (const Placement& p :
       {Placement{"[track]\ngauge_width = 3000.0", "track.gauge_width = 3000 mm"},
        Placement{"[wheelset]\nflange_back_distance = 300.0",
                  "wheelset.flange_back_distance = 300 mm"}}) {
    const fs::path case_file = WriteCaseWith("[grid]", std::string(p.lines) + "\n[grid]");
    ExpectBadInput(Solve(case_file), {"nowhere above the rail", p.named, "state.y = 0 mm"});
  }
}

// Roll beyond the range of wheelset-on-track contact names the key and value.
TEST_F(ErrorMessages, RollOutOfRange) {
  const fs::path case_file = WriteCaseWith("yaw = 0.0", "roll = 0.5");
  ExpectBadInput(Solve(case_file), {"case.toml", "state.roll", "0.5", "0.1 rad"});
}

TEST_F(ErrorMessages, LiftedWheelIsNoContact) {
  // z points down: z = -5 lifts the wheel 5 mm off the rail.
  const WrcRun run = Solve(WriteCaseWith("z = 0.3", "z = -5.0"), /*as_json=*/true);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json result = nlohmann::json::parse(run.out);
  EXPECT_EQ(result["status"], "no_contact");
  EXPECT_TRUE(result["patches"].empty());
}

// An fz no elastic contact can carry names state.fz and its value.
TEST_F(ErrorMessages, UnreachableVerticalForce) {
  int line = 0;
  const fs::path case_file = WriteCaseWith("z = 0.3", "fz = 1.0e12", &line);
  ExpectBadInput(Solve(case_file), {"case.toml", "state.fz = 1", "not reached"});
}

// toml++ 3.3.0 (Debian 12) reaches __builtin_unreachable() when it meets some non-ASCII
// characters where it allows white space (upstream marzer/tomlplusplus#190, #295). The core
// compiles that parser in (core/io/toml_implementation.cpp), so these pin down what our build of
// it does there: a syntax error for a stray combining mark, and the TOML meaning of a line-ending
// backslash followed by '§'. A different compiler choice showing up as a crash fails here.
TEST_F(ErrorMessages, NonAsciiWhereWhiteSpaceIsAllowedIsASyntaxError) {
  int line = 0;
  const fs::path case_file = WriteCaseWith("dx = 0.5", "dx = [1\xcc\xaa]", &line);
  ExpectBadInput(Solve(case_file), {"case.toml:" + std::to_string(line), "TOML syntax error"});
}

TEST_F(ErrorMessages, NonAsciiAfterLineEndingBackslashIsKept) {
  const fs::path case_file =
      WriteCaseWith("type = \"wheel-rail\"", "type = \"\"\"\\\n\xc2\xa7wheel-rail\"\"\"");
  ExpectBadInput(Solve(case_file), {"case.toml", "problem.type = \"\xc2\xa7wheel-rail\""});
}

}  // namespace
