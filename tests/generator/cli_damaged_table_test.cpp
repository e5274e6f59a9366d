// `wrc info` and `wrc verify` on damaged or invalid tables: exit 2 with a message naming the
// file and the problem, never a crash and never a description of numbers that are not there.
// And the table file of `wrc generate`: never written through a FIFO or a planted symlink, and
// a failed write leaves no half table.

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "generator/sha256.h"
#include "runtime/hdf5/seal.h"
#include "tests/generator/generator_test_util.h"
#include "tests/runtime/table_writer.h"
#include "wrc/generator/generator.h"
#include "wrc/runtime.hpp"

namespace wrc::test {
namespace {

TableContent ValidTable() {
  TableContent content;
  content.axes = {{"y", {-2.0, -1.0, 0.0, 1.5, 2.0}, "mm"}, {"roll", {-0.002, 0.0, 0.002}, "rad"}};
  content.outputs = {"fy", "fx"};
  content.function = [](int k, const std::vector<double>& x) { return 100.0 * k + x[0]; };
  content.format = h5::FileFormat::kChecksummed;
  return content;
}

// Runs info and verify on the table; both must exit 2 and name `problem` on stderr.
void ExpectRefused(const fs::path& table, const std::string& problem) {
  for (const std::string command : {" info ", " info --json ", " verify --samples 2 "}) {
    const CommandResult result =
        RunCommand(Quoted(WrcBinary()) + command + Quoted(table.string()), table.parent_path());
    EXPECT_EQ(result.exit_code, 2) << command << ": " << result.err;
    EXPECT_NE(result.err.find(problem), std::string::npos) << command << ": " << result.err;
    if (command == " info ") {
      EXPECT_TRUE(result.out.empty()) << result.out;
    }
    if (command == " info --json ") {  // an error object naming the problem, as solve --json
      const nlohmann::json error = nlohmann::json::parse(result.out, nullptr, false);
      EXPECT_EQ(error.value("status", ""), "error") << result.out;
      EXPECT_NE(error.value("message", "").find(problem), std::string::npos) << result.out;
    }
  }
}

template <typename Edit>
fs::path WriteEdited(const ScratchDir& dir, const std::string& name, TableContent content,
                     Edit edit) {
  const fs::path path = dir / name;
  WriteTable(path.string(), content);
  h5::File file = h5::File::Open(path.string(), h5::File::Mode::kReadWrite);
  edit(file);
  return path;
}

TEST(CliDamagedTable, AxisOfZeroLength) {
  ScratchDir dir("damaged_empty_axis");
  TableContent content = ValidTable();
  content.axes[1].values.clear();
  const fs::path table = dir / "empty.h5";
  WriteTable(table.string(), content);
  ExpectRefused(table, "is empty");
}

TEST(CliDamagedTable, AxisNotAscending) {
  ScratchDir dir("damaged_descending");
  TableContent content = ValidTable();
  content.axes[0].values = {-2.0, -1.0, 0.5, 0.0, 2.0};
  const fs::path table = dir / "descending.h5";
  WriteTable(table.string(), content);
  ExpectRefused(table, "strictly ascending");
}

TEST(CliDamagedTable, NonFiniteValueAtAnOkNode) {
  ScratchDir dir("damaged_nan");
  TableContent content = ValidTable();
  content.function = [](int k, const std::vector<double>& x) {
    return k == 1 && x[0] == 0.0 ? std::numeric_limits<double>::quiet_NaN() : x[0];
  };
  const fs::path table = dir / "nan.h5";
  WriteTable(table.string(), content);
  ExpectRefused(table, "non-finite value");
}

TEST(CliDamagedTable, IntegerOutput) {
  ScratchDir dir("damaged_int");
  const fs::path table = WriteEdited(dir, "int.h5", ValidTable(), [](h5::File& file) {
    h5::Group outputs = file.OpenGroup("outputs");
    outputs.Remove("fx");
    outputs.WriteDataset("fx", {5, 3}, std::vector<std::int32_t>(15, 0));
  });
  ExpectRefused(table, "must be floating point (float64), is int32");
}

// /errors names failed nodes by their flat index: one beyond the grid, one on a node that
// solved, or a point list longer than the message list is damage, not a failure to show.
TEST(CliDamagedTable, ErrorsThatNameNoFailedNode) {
  ScratchDir dir("damaged_errors");
  TableContent content = ValidTable();
  // The node at y = 0, roll = 0 (flat index 2 · 3 + 1 = 7) failed.
  content.status = [](const std::vector<double>& x) -> std::int8_t {
    return x[0] == 0.0 && x[1] == 0.0 ? 3 : 0;
  };
  const auto with_errors = [&](const std::string& name, std::vector<std::int64_t> points,
                               std::vector<std::string> messages) {
    return WriteEdited(dir, name, content, [&](h5::File& file) {
      h5::Group errors = file.CreateGroup("errors");
      errors.WriteDataset<std::int64_t>("point", {points.size()}, points);
      errors.WriteStringDataset("message", messages);
    });
  };
  const fs::path intact = with_errors("intact.h5", {7}, {"no contact"});
  const CommandResult shown =
      RunCommand(Quoted(WrcBinary()) + " info " + Quoted(intact.string()), dir.path());
  EXPECT_EQ(shown.exit_code, 0) << shown.err;
  EXPECT_NE(shown.out.find("no contact"), std::string::npos) << shown.out;
  // info and info --json (verify stops earlier here, at the test table's scene).
  const auto refused = [&](const fs::path& table, const std::string& problem) {
    for (const std::string command : {" info ", " info --json "}) {
      const CommandResult r =
          RunCommand(Quoted(WrcBinary()) + command + Quoted(table.string()), dir.path());
      EXPECT_EQ(r.exit_code, 2) << command << r.err;
      EXPECT_NE((r.err + r.out).find(problem), std::string::npos) << command << r.err << r.out;
    }
  };
  refused(with_errors("beyond.h5", {15}, {"no contact"}),
          "errors/point[0] = 15 lies outside the grid of 15 points");
  refused(with_errors("negative.h5", {-1}, {"no contact"}), "errors/point[0] = -1 lies outside");
  refused(with_errors("solved.h5", {7, 8}, {"no contact", "no contact"}),
          "errors/point[1] = 8 is a node that solved");
  refused(with_errors("short.h5", {7}, {"no contact", "again"}),
          "errors/point holds 1 entries but message 2");
}

TEST(CliDamagedTable, UnknownFormatVersion) {
  ScratchDir dir("damaged_version");
  const fs::path table = WriteEdited(dir, "v7.h5", ValidTable(), [](h5::File& file) {
    file.WriteIntAttribute("format_version", 7);
  });
  ExpectRefused(table, "format_version' is 7");
}

// An optional object that is there but cannot be read as what it should be (a damaged object
// header opens as neither group nor dataset) is an error, not shown as absent (zero solve time).
TEST(CliDamagedTable, OptionalObjectOfTheWrongKind) {
  ScratchDir dir("damaged_solve_time");
  const fs::path table = WriteEdited(dir, "time.h5", ValidTable(), [](h5::File& file) {
    file.Remove("solve_time_s");
    file.CreateGroup("solve_time_s");
  });
  const CommandResult result =
      RunCommand(Quoted(WrcBinary()) + " info " + Quoted(table.string()), dir.path());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find("solve_time_s: cannot be opened"), std::string::npos) << result.err;
}

// Refinement attributes that are not the JSON wrc generate writes (an array of strings, text
// that is not UTF-8): `wrc info` names the attribute, and --json stays valid JSON.
TEST(CliDamagedTable, RefinementAttributesThatAreNotItsJson) {
  ScratchDir dir("damaged_refine_attributes");
  const auto edits = std::vector<std::function<void(h5::File&)>>{
      [](h5::File& f) {
        f.WriteStringArrayAttribute("refine_target", {"a", "b"});
      },
      [](h5::File& f) { f.WriteStringAttribute("refine_target", "[1, 2]"); },
      [](h5::File& f) {
        f.WriteStringAttribute("refine_target", "{\"load_fraction\": 0.01}");
        f.WriteStringAttribute("refine_passes", "\xff\xfe");
      }};
  for (std::size_t i = 0; i < edits.size(); ++i) {
    SCOPED_TRACE(i);
    const fs::path table =
        WriteEdited(dir, "t" + std::to_string(i) + ".h5", ValidTable(), edits[i]);
    for (const std::string command : {" info ", " info --json "}) {
      const CommandResult result =
          RunCommand(Quoted(WrcBinary()) + command + Quoted(table.string()), dir.path());
      EXPECT_EQ(result.exit_code, 2) << command << result.err;
      EXPECT_NE(result.err.find("refine_"), std::string::npos) << result.err;
      EXPECT_EQ(result.err.find("json.exception"), std::string::npos) << result.err;
      if (command == " info --json ") {
        EXPECT_FALSE(nlohmann::json::parse(result.out, nullptr, false).is_discarded())
            << result.out;
      }
    }
  }
}

// ---- tables written before seals, and `wrc upgrade` ------------------------------------------

// `wrc COMMAND TABLE -o OUTPUT` (upgrade, export), run beside the table.
CommandResult RewriteTable(const char* command, const fs::path& table, const fs::path& output) {
  return RunCommand(Quoted(WrcBinary()) + " " + command + " " + Quoted(table.string()) + " -o " +
                        Quoted(output.string()),
                    table.parent_path());
}

CommandResult Upgrade(const fs::path& table, const fs::path& output) {
  return RewriteTable("upgrade", table, output);
}

std::vector<char> ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

void WriteBytes(const fs::path& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Every occurrence of `pattern` with the byte at `offset` in it set to `value`; how many.
int Patch(std::vector<char>* bytes, const std::vector<char>& pattern, std::size_t offset,
          char value) {
  int patched = 0;
  for (auto it = bytes->begin();
       (it = std::search(it, bytes->end(), pattern.begin(), pattern.end())) != bytes->end(); ++it) {
    *(it + static_cast<std::ptrdiff_t>(offset)) = value;
    ++patched;
  }
  return patched;
}

// Both outputs at points inside ValidTable's grid, through the runtime.
std::vector<double> Values(const fs::path& table) {
  const Table opened(table.string());
  std::vector<double> values;
  for (const double y : {-1.7, 0.3, 1.9}) {
    for (const double roll : {-0.0015, 0.001}) {
      std::vector<double> out(2);
      opened.eval(std::vector<double>{y, roll}.data(), out.data());
      values.insert(values.end(), out.begin(), out.end());
    }
  }
  return values;
}

// A table in HDF5's earliest format, with the variable-length string attributes tables had
// then: every command refuses it naming `wrc upgrade`, which rewrites it sealed, with the same
// numbers as the same table written today; an unsealed checksummed table is sealed the same way.
TEST(CliUpgrade, OlderTablesComeOutSealedWithTheSameNumbers) {
  ScratchDir dir("upgrade_older");
  const fs::path current = dir / "current.h5";
  TableContent content = ValidTable();
  content.sealed = true;
  WriteTable(current.string(), content);
  const fs::path earliest = dir / "earliest.h5";
  content.sealed = false;
  content.format = h5::FileFormat::kEarliest;
  WriteTable(earliest.string(), content);
  {
    h5::File file =
        h5::File::Open(earliest.string(), h5::File::Mode::kReadWrite, h5::File::Earliest::kAllow);
    const auto variable = h5::StringStorage::kVariable;
    file.WriteStringAttribute("format", "wrc-table", variable);
    file.OpenGroup("axes").WriteStringArrayAttribute("order", {"y", "roll"}, variable);
    file.OpenGroup("outputs").WriteStringArrayAttribute("order", {"fy", "fx"}, variable);
  }
  ExpectRefused(earliest, "wrc upgrade " + earliest.string());
  const fs::path unsealed = dir / "unsealed.h5";
  WriteTable(unsealed.string(), ValidTable());
  for (const fs::path& old : {earliest, unsealed}) {
    SCOPED_TRACE(old.string());
    const fs::path upgraded = dir / ("upgraded_" + old.filename().string());
    const CommandResult result = Upgrade(old, upgraded);
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(h5::CheckSeal(upgraded.string()), h5::SealStatus::kIntact);
    EXPECT_EQ(Table(upgraded.string()).warning(), "");
    EXPECT_EQ(Values(upgraded), Values(current));
    EXPECT_EQ(Table(upgraded.string()).attribute("scene"),
              Table(current.string()).attribute("scene"));
  }
  EXPECT_NE(Table(unsealed.string()).warning(), "");
  // Never onto its input; nothing left under the output's name after a failure.
  const CommandResult onto_itself = Upgrade(unsealed, unsealed);
  EXPECT_EQ(onto_itself.exit_code, 2) << onto_itself.err;
  EXPECT_NE(Table(unsealed.string()).warning(), "");
}

// A table written before tables stored their fixed state typed (here: a new one with those
// attributes removed) gets them from its scene text when upgraded: the same values, NaN for the
// axes, as the generator writes them.
TEST(CliUpgrade, TablesWithoutTheTypedFixedStateGetIt) {
  ScratchDir dir("upgrade_fixed_state");
  const fs::path scene = test::WriteFile(
      dir / "scene.toml", test::TinyScene("axes = [\"y\"]\ny = [0.0, 2.0]\noutputs = [\"fy\"]",
                                          "fz = 8000.0\nroll = 0.001"));
  const fs::path table = dir / "new.h5", old = dir / "old.h5";
  GenerateOptions options;
  options.output = table;
  options.progress = ProgressMode::kOff;
  options.mpi = MpiMode::kOff;
  ASSERT_TRUE(GenerateTable(LoadScene(scene), options).complete);
  fs::copy_file(table, old);
  {
    const auto lock = h5::LibraryLock();
    h5::File file = h5::File::Open(old.string(), h5::File::Mode::kReadWrite);
    for (const std::string& name : file.AttributeNames()) {
      if (name.rfind("fixed_", 0) == 0 || name.rfind("wheelset_", 0) == 0 ||
          name == "wheel_profile_offset") {
        file.RemoveAttribute(name);
      }
    }
  }
  h5::SealFile(old.string());
  ASSERT_THROW(Table(old.string()).number_attribute("wheelset_velocity"), TableError);
  const fs::path upgraded = dir / "upgraded.h5";
  const CommandResult result = Upgrade(old, upgraded);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const Table a(table.string()), b(upgraded.string());
  EXPECT_EQ(b.attribute("wheelset_side"), "right");
  for (const std::string name :
       {"wheelset_velocity", "wheelset_nominal_radius", "wheel_profile_offset", "fixed_y",
        "fixed_roll", "fixed_fz", "fixed_z", "fixed_mu", "fixed_omega", "fixed_y_wheel"}) {
    const double expected = a.number_attribute(name), got = b.number_attribute(name);
    EXPECT_TRUE(got == expected || (std::isnan(got) && std::isnan(expected))) << name;
  }
  EXPECT_EQ(b.number_attribute("fixed_roll"), 0.001);
  EXPECT_TRUE(std::isnan(b.number_attribute("fixed_y")));  // the axis
}

// Damaged tables in HDF5's earliest format (no metadata checksums) found by mutating one: HDF5
// 1.10 crashes reading them (a B-tree header, an attribute lookup by name, a compact dataset read
// past its buffer, an attribute iteration), or its own checks stop it. Every command refuses them
// before HDF5 reads a byte; `wrc upgrade` reads them in a child process, and a crash there, or
// HDF5's error, is exit 2 naming the file, with no output file left.
TEST(CliUpgrade, EarliestFormatFilesThatCrashHdf5AreErrors) {
  const fs::path dir = fs::path(WRC_SOURCE_DIR) / "tests" / "runtime" / "damaged";
  for (const char* name : {"crashes_hdf5_btree_header.h5", "crashes_hdf5_attribute_exists.h5",
                           "crashes_hdf5_compact_read.h5", "hdf5_attribute_iteration.h5",
                           "hdf5_compact_overread.h5", "hdf5_huge_allocation.h5"}) {
    SCOPED_TRACE(name);
    ScratchDir scratch("damaged_crashes_hdf5");
    const fs::path table = scratch / name;
    fs::copy_file(dir / name, table);
    ExpectRefused(table, "wrc upgrade");
    const CommandResult plot = RunCommand(
        Quoted(WrcBinary()) + " plot table " + Quoted(table.string()) + " --output fy --x y",
        scratch.path());
    EXPECT_EQ(plot.exit_code, 2) << plot.err;
    EXPECT_NE(plot.err.find("wrc upgrade"), std::string::npos) << plot.err;
    const CommandResult upgrade = Upgrade(table, scratch / "new.h5");
    EXPECT_EQ(upgrade.exit_code, 2) << upgrade.err;
    EXPECT_NE(upgrade.err.find(name), std::string::npos) << upgrade.err;
    EXPECT_FALSE(fs::exists(scratch / "new.h5"));
    EXPECT_FALSE(fs::exists(scratch / "new.h5.tmp"));
  }
}

// Earliest-format tables with one damaged byte that HDF5 copies faithfully: the float64
// datatype's size read as 65544, and the shuffle filter's element size as 2 (pipeline message:
// id 2, name length 8, flags 1, one parameter, "shuffle\0", then the element size 8). The
// upgrade's own read of the copy refuses them.
TEST(CliUpgrade, DamageTheCopyKeepsIsRefused) {
  const std::vector<char> float64 = {0x11, 0x20, 0x3f, 0x00, 0x08, 0x00, 0x00, 0x00};
  const std::vector<char> shuffle = {0x02, 0x00, 0x08, 0x00, 0x01, 0x00, 0x01, 0x00, 's',  'h',
                                     'u',  'f',  'f',  'l',  'e',  0x00, 0x08, 0x00, 0x00, 0x00};
  struct Damage {
    const std::vector<char>& pattern;
    std::size_t offset;
    char value;
    const char* problem;
  };
  for (const Damage& damage :
       {Damage{float64, 6, 0x01, "not a standard"}, Damage{shuffle, 16, 0x02, "filter"}}) {
    SCOPED_TRACE(damage.problem);
    ScratchDir dir("upgrade_damaged");
    TableContent content = ValidTable();
    content.format = h5::FileFormat::kEarliest;
    content.axis_storage = h5::CompressedChecked();
    const fs::path table = dir / "old.h5";
    WriteTable(table.string(), content);
    std::vector<char> bytes = ReadBytes(table);
    ASSERT_GT(Patch(&bytes, damage.pattern, damage.offset, damage.value), 0);
    WriteBytes(table, bytes);
    const CommandResult upgrade = Upgrade(table, dir / "new.h5");
    EXPECT_EQ(upgrade.exit_code, 2) << upgrade.err;
    EXPECT_NE(upgrade.err.find(damage.problem), std::string::npos) << upgrade.err;
    EXPECT_FALSE(fs::exists(dir / "new.h5"));
  }
}

// ---- the table file that `wrc generate` writes ---------------------------------------------

std::string SmallScene() {
  return TinyScene("axes = [\"y\"]\ny = [0.0, 1.0]\noutputs = [\"fx\", \"fz\"]");
}

CommandResult Generate(const ScratchDir& dir, const std::string& output,
                       const std::string& prefix = "") {
  WriteFile(dir / "scene.toml", SmallScene());
  return RunCommand(prefix + Quoted(WrcBinary()) + " generate " +
                        Quoted((dir / "scene.toml").string()) + " -o " + Quoted(output),
                    dir.path());
}

TEST(CliGenerateOutput, AFifoIsNotReplaced) {
  ScratchDir dir("output_fifo");
  const fs::path fifo = dir / "table.h5";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const CommandResult result = Generate(dir, fifo.string());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find("is a FIFO"), std::string::npos) << result.err;
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(CliGenerateOutput, ASymlinkPlantedAtTheTemporaryNameIsNotFollowed) {
  ScratchDir dir("output_symlink");
  WriteFile(dir / "victim", "keep");
  fs::create_symlink(dir / "victim", dir / "table.h5.tmp");
  const CommandResult result = Generate(dir, (dir / "table.h5").string());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find("symbolic link"), std::string::npos) << result.err;
  EXPECT_EQ(ReadFile(dir / "victim"), "keep");
  EXPECT_FALSE(fs::exists(dir / "table.h5"));
}

// A file-size limit makes the table's writes fail (EFBIG) as a full disk would.
TEST(CliGenerateOutput, AFullDiskIsExit2AndNoHalfTable) {
  ScratchDir dir("output_full");
  const CommandResult result =
      Generate(dir, (dir / "table.h5").string(), "ulimit -f 16; trap '' XFSZ; ");
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find("table.h5.tmp"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(dir / "table.h5"));
  EXPECT_FALSE(fs::exists(dir / "table.h5.tmp"));
}

// Every solved point's warnings are counted in the table (root attribute warnings_count): with
// a rail profile whose zig-zag is repaired, each of the two points has one.
TEST(CliGenerateOutput, WarningsAreCountedInTheTable) {
  ScratchDir dir("output_warnings");
  std::istringstream in(ReadFile(ProfilePath("MBench_UIC60_v3.prr")));
  std::ofstream rail(dir / "zigzag.prr");
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    rail << line << '\n';
    if (++line_number == 300) {  // the point after it moved back across it
      std::istringstream fields(line);
      double y = 0.0, z = 0.0;
      fields >> y >> z;
      rail << y - 0.3 << '\t' << z << '\n';
    }
  }
  rail.close();
  std::string scene = TinyScene("axes = [\"y\"]\ny = [0.0, 1.0]\noutputs = [\"fx\", \"fz\"]");
  const std::string original = ProfilePath("MBench_UIC60_v3.prr");
  scene.replace(scene.find(original), original.size(), (dir / "zigzag.prr").string());
  WriteFile(dir / "scene.toml", scene);
  const fs::path table = dir / "table.h5";
  const CommandResult result =
      RunCommand(Quoted(WrcBinary()) + " generate " + Quoted((dir / "scene.toml").string()) +
                     " -o " + Quoted(table.string()),
                 dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(h5::File::Open(table.string()).ReadIntAttribute("warnings_count"), 2);
  const CommandResult info =
      RunCommand(Quoted(WrcBinary()) + " info --json " + Quoted(table.string()), dir.path());
  EXPECT_NE(info.out.find("\"warnings_count\": 2"), std::string::npos) << info.out;
}

TEST(CliTableCommands, FullStandardOutputIsAnError) {
  ScratchDir dir("info_full");
  const fs::path table = dir / "table.h5";
  WriteTable(table.string(), ValidTable());
  // RunCommand redirects stdout itself; here stdout is /dev/full.
  const int status = std::system(
      (Quoted(WrcBinary()) + " info " + Quoted(table.string()) + " >/dev/full 2>/dev/null")
          .c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
}

// A table's stored profile is what its points were solved with: bytes that differ from the
// recorded SHA-256 would verify the table against another profile.
TEST(CliStoredProfile, BytesThatDifferFromTheDigestAreRefused) {
  ScratchDir dir("stored_profile_digest");
  ASSERT_EQ(Generate(dir, (dir / "table.h5").string()).exit_code, 0);
  {
    h5::File file = h5::File::Open((dir / "table.h5").string(), h5::File::Mode::kReadWrite);
    h5::Group profiles = file.OpenGroup("profiles");
    std::vector<std::uint8_t> bytes = profiles.OpenDataset("rail").Read<std::uint8_t>();
    bytes[bytes.size() / 2] ^= 1;  // one bit of one coordinate
    profiles.Remove("rail");
    profiles.WriteDataset<std::uint8_t>("rail", {bytes.size()}, bytes);
  }
  h5::SealFile((dir / "table.h5").string());  // consistent but for the digest, as if written so
  ExpectRefused(dir / "table.h5", "/profiles/rail: its SHA-256");
}

// verify solves from the table's copies of the profiles, in a scratch directory: the files the
// scene names (here by absolute path, edited since) are neither read nor written.
TEST(CliStoredProfile, VerifyLeavesTheScenesProfileFilesAlone) {
  ScratchDir dir("stored_profile_untouched");
  fs::copy_file(ProfilePath("MBench_UIC60_v3.prr"), dir / "rail.prr");
  std::string scene = SmallScene();
  const std::string original = ProfilePath("MBench_UIC60_v3.prr");
  scene.replace(scene.find(original), original.size(), (dir / "rail.prr").string());
  WriteFile(dir / "scene.toml", scene);
  const std::string in_dir = "cd " + Quoted(dir.path().string()) + " && " + Quoted(WrcBinary());
  ASSERT_EQ(RunCommand(in_dir + " generate scene.toml -o table.h5", dir.path()).exit_code, 0);
  WriteFile(dir / "rail.prr", "edited since\n");
  const CommandResult result = RunCommand(in_dir + " verify --samples 2 table.h5", dir.path());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(ReadFile(dir / "rail.prr"), "edited since\n");
}

// A stored profile that cannot be read is named as the table's, not as the scratch copy verify
// solves from (deleted by the time the message is read).
TEST(CliStoredProfile, AnUnreadableProfileIsNamedAsTheTables) {
  ScratchDir dir("stored_profile_unreadable");
  ASSERT_EQ(Generate(dir, (dir / "table.h5").string()).exit_code, 0);
  {
    h5::File file = h5::File::Open((dir / "table.h5").string(), h5::File::Mode::kReadWrite);
    const std::string junk = "not a profile\n1 2 3 x\n";
    h5::Group profiles = file.OpenGroup("profiles");
    profiles.Remove("wheel");
    profiles.WriteDataset<std::uint8_t>("wheel", {junk.size()},
                                        std::vector<std::uint8_t>(junk.begin(), junk.end()));
    file.WriteStringAttribute("wheel_profile_sha256", Sha256Hex(junk));
  }
  h5::SealFile((dir / "table.h5").string());
  const CommandResult result =
      RunCommand(Quoted(WrcBinary()) + " verify --samples 2 " + Quoted((dir / "table.h5").string()),
                 dir.path());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_NE(result.err.find("table.h5:/profiles/wheel"), std::string::npos) << result.err;
  EXPECT_EQ(result.err.find("wrc_verify_"), std::string::npos) << result.err;
}

// ---- `wrc export` -------------------------------------------------------------------------------

CommandResult Export(const fs::path& table, const fs::path& output) {
  return RewriteTable("export", table, output);
}

// The flat table holds the same numbers; a damaged table, a missing one or an output that is
// the input are refused with exit 2, and nothing is written.
TEST(CliExport, WritesTheSameNumbersAndRefusesWhatTheRuntimeRefuses) {
  ScratchDir dir("export");
  const fs::path table = dir / "table.h5";
  TableContent content = ValidTable();
  content.sealed = true;
  WriteTable(table.string(), content);
  const fs::path flat = dir / "table.wrct";
  const CommandResult exported = Export(table, flat);
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  EXPECT_NE(exported.out.find("2 axes, 2 outputs, 15 nodes"), std::string::npos) << exported.out;
  EXPECT_EQ(Values(flat), Values(table));
  EXPECT_EQ(Table(flat.string()).attribute("scene"), Table(table.string()).attribute("scene"));
  const CommandResult info =
      RunCommand(Quoted(WrcBinary()) + " info --json " + Quoted(flat.string()), dir.path());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json described = nlohmann::json::parse(info.out);
  EXPECT_EQ(described["format"], "wrc-flat-table");
  EXPECT_EQ(described["points"], 15);
  EXPECT_EQ(described["status"]["ok"], 15);
  EXPECT_EQ(described["axes"][1]["values"], nlohmann::json({-0.002, 0.0, 0.002}));
  // verify solves with the stored profiles, which a flat table leaves in the HDF5 table.
  const CommandResult verify =
      RunCommand(Quoted(WrcBinary()) + " verify --samples 2 " + Quoted(flat.string()), dir.path());
  EXPECT_EQ(verify.exit_code, 2);
  EXPECT_NE(verify.err.find("a flat table (wrc export) holds neither"), std::string::npos)
      << verify.err;

  std::vector<char> bytes = ReadBytes(table);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 1);
  const fs::path damaged = dir / "damaged.h5";
  WriteBytes(damaged, bytes);
  const std::vector<std::pair<fs::path, std::string>> refused = {
      {damaged, "damaged"}, {dir / "missing.h5", "no such file"}, {flat, "is also an input"}};
  for (const auto& [input, problem] : refused) {
    const fs::path output = input == flat ? flat : dir / "out.wrct";
    const CommandResult result = Export(input, output);
    EXPECT_EQ(result.exit_code, 2) << input;
    EXPECT_NE(result.err.find(problem), std::string::npos) << result.err;
    if (input != flat) {
      EXPECT_FALSE(fs::exists(output)) << input;
    }
  }
  EXPECT_EQ(Values(flat), Values(table));  // the refused export left it as it was
  int leftovers = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    leftovers += entry.path().filename().string().rfind(".table", 0) == 0 ||
                 entry.path().filename().string().rfind(".out", 0) == 0;
  }
  EXPECT_EQ(leftovers, 0);
}

}  // namespace
}  // namespace wrc::test
