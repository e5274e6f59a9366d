// GenerateTable() in process: determinism across thread counts and interruptions, agreement
// with direct solves, failing and no-contact points, journal errors, and the runtime reading
// what the generator wrote.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "generator/sha256.h"
#include "runtime/hdf5/hdf5.h"
#include "tests/generator/generator_test_util.h"
#include "wrc/core/errors.h"
#include "wrc/core/scene.h"
#include "wrc/core/wheelrail.h"
#include "wrc/generator/generator.h"
#include "wrc/runtime.hpp"

namespace wrc {
namespace {

using test::ScratchDir;
namespace fs = std::filesystem;

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

Scene WriteAndLoad(const ScratchDir& dir, const std::string& text, const std::string& name) {
  return LoadScene(test::WriteFile(dir / name, text));
}

GenerateOptions Options(const fs::path& output, int threads) {
  GenerateOptions options;
  options.output = output;
  options.threads = threads;
  options.progress = ProgressMode::kOff;
  options.mpi = MpiMode::kOff;
  // Whole lines as segments even in these small tables, so that warm starts are exercised.
  options.min_segments = 1;
  return options;
}

struct StoredTable {
  std::vector<std::vector<double>> outputs;  // in scene.outputs order
  std::vector<std::int8_t> status;
};

StoredTable ReadStored(const fs::path& path, const Scene& scene) {
  const auto lock = h5::LibraryLock();
  const h5::File file = h5::File::Open(path.string());
  StoredTable table;
  for (const std::string& name : scene.outputs) {
    table.outputs.push_back(file.OpenGroup("outputs").OpenDataset(name).Read<double>());
  }
  table.status = file.OpenDataset("status").Read<std::int8_t>();
  return table;
}

std::vector<std::size_t> IndicesOf(const Scene& scene, std::size_t point) {
  const std::vector<std::size_t> shape = scene.Shape();
  std::vector<std::size_t> indices(shape.size());
  for (std::size_t a = shape.size(); a-- > 0;) {
    indices[a] = point % shape[a];
    point /= shape[a];
  }
  return indices;
}

std::size_t OutputIndex(const Scene& scene, const std::string& name) {
  for (std::size_t k = 0; k < scene.outputs.size(); ++k) {
    if (scene.outputs[k] == name) return k;
  }
  ADD_FAILURE() << "no output " << name;
  return 0;
}

// The tiny scene's table made once with one thread; the tests compare against it.
class GenerateTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir("generate");
    scene_ = new Scene(WriteAndLoad(*dir_, test::TinyScene(test::DefaultTinyTable()), "tiny.toml"));
    reference_ = *dir_ / "reference.h5";
    const GenerateSummary summary = GenerateTable(*scene_, Options(reference_, 1));
    ASSERT_TRUE(summary.complete);
    ASSERT_EQ(summary.computed, 12u);
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete dir_;
  }
  static ScratchDir* dir_;
  static Scene* scene_;
  static fs::path reference_;
};
ScratchDir* GenerateTest::dir_ = nullptr;
Scene* GenerateTest::scene_ = nullptr;
fs::path GenerateTest::reference_;

TEST_F(GenerateTest, LayoutAndProvenanceFollowTheSpec) {
  const auto lock = h5::LibraryLock();
  const h5::File file = h5::File::Open(reference_.string());
  EXPECT_EQ(file.ReadStringAttribute("format"), "wrc-table");
  EXPECT_EQ(file.ReadIntAttribute("format_version"), 1);
  EXPECT_EQ(file.ReadStringAttribute("wrc_version"), GeneratorVersion());
  EXPECT_EQ(file.ReadStringAttribute("scene"), scene_->base.source_text);
  const std::string created = file.ReadStringAttribute("created");
  EXPECT_EQ(created.size(), 20u) << created;  // 2025-01-02T03:04:05Z
  EXPECT_EQ(created.back(), 'Z');
  EXPECT_EQ(file.ReadStringAttribute("rail_profile_sha256"),
            Sha256FileHex(test::ProfilePath("MBench_UIC60_v3.prr")));
  EXPECT_EQ(file.ReadStringAttribute("wheel_profile_sha256"),
            Sha256FileHex(test::ProfilePath("MBench_S1002_v3.prw")));

  const h5::Group axes = file.OpenGroup("axes");
  EXPECT_EQ(axes.ReadStringArrayAttribute("order"), (std::vector<std::string>{"yaw", "y"}));
  EXPECT_EQ(axes.OpenDataset("y").Read<double>(),
            (std::vector<double>{0.0, 1.0, 2.0, 3.0, 4.0, 5.0}));
  EXPECT_EQ(axes.OpenDataset("y").ReadStringAttribute("unit"), "mm");
  EXPECT_EQ(axes.OpenDataset("yaw").ReadStringAttribute("unit"), "rad");
  const std::vector<h5::Size> shape = {2, 6};
  const h5::Group outputs = file.OpenGroup("outputs");
  EXPECT_EQ(outputs.MemberNames(), scene_->outputs);
  for (const std::string& name : scene_->outputs) {
    const h5::Dataset dataset = outputs.OpenDataset(name);
    EXPECT_EQ(dataset.Shape(), shape) << name;
    EXPECT_EQ(dataset.Type().Describe(), "float64") << name;
    EXPECT_EQ(dataset.ReadStringAttribute("unit"), QuantityUnit(name)) << name;
    EXPECT_TRUE(dataset.HasDeflate() && dataset.HasFletcher32()) << name;
    EXPECT_FALSE(dataset.ChunkShape().empty()) << name;
  }
  EXPECT_EQ(outputs.OpenDataset("fx").ReadStringAttribute("unit"), "N");
  EXPECT_EQ(outputs.OpenDataset("mz").ReadStringAttribute("unit"), "N*mm");
  EXPECT_EQ(outputs.OpenDataset("z").ReadStringAttribute("unit"), "mm");
  EXPECT_EQ(file.OpenDataset("status").Type().Describe(), "int8");
  EXPECT_EQ(file.OpenDataset("status").Shape(), shape);
  EXPECT_EQ(file.OpenDataset("solve_time_s").Type().Describe(), "float32");
  for (const float t : file.OpenDataset("solve_time_s").Read<float>()) EXPECT_GT(t, 0.0f);
  const h5::Dataset rail = file.OpenGroup("profiles").OpenDataset("rail");
  EXPECT_EQ(rail.Type().Describe(), "uint8");
  EXPECT_EQ(rail.ReadStringAttribute("name"), "MBench_UIC60_v3.prr");
  const std::vector<std::uint8_t> rail_bytes = rail.Read<std::uint8_t>();
  EXPECT_EQ(std::string(rail_bytes.begin(), rail_bytes.end()),
            test::ReadFile(test::ProfilePath("MBench_UIC60_v3.prr")));
  EXPECT_EQ(file.OpenGroup("profiles").OpenDataset("wheel").ReadStringAttribute("name"),
            "MBench_S1002_v3.prw");
  EXPECT_FALSE(file.Exists("errors"));  // nothing failed
  // The run cleaned up after itself.
  EXPECT_FALSE(fs::exists(reference_.string() + ".journal"));
  EXPECT_FALSE(fs::exists(reference_.string() + ".tmp"));
}

TEST_F(GenerateTest, TwoThreadsGiveTheSameBitsAsOne) {
  const fs::path two = *dir_ / "two_threads.h5";
  const GenerateSummary summary = GenerateTable(*scene_, Options(two, 2));
  EXPECT_TRUE(summary.complete);
  EXPECT_EQ(summary.threads, 2);
  test::ExpectIdenticalTables(reference_, two);
}

// Every stored value is what SolveWheelRail gives for that point when started from the same
// z: the predecessor's stored z along the line (exact equality, as the computation is the same).
TEST_F(GenerateTest, StoredValuesEqualDirectSolves) {
  const StoredTable stored = ReadStored(reference_, *scene_);
  const std::size_t z_out = OutputIndex(*scene_, "z");
  const std::size_t line = scene_->Shape().back();
  for (std::size_t point = 0; point < scene_->PointCount(); ++point) {
    const double z_guess = point % line == 0 || stored.status[point - 1] != 0
                               ? std::numeric_limits<double>::quiet_NaN()
                               : stored.outputs[z_out][point - 1];
    const Case c = CaseAtIndex(*scene_, IndicesOf(*scene_, point));
    WheelRailOptions options;
    options.z_guess = z_guess;
    const WheelRailResult direct = SolveWheelRail(c, options);
    ASSERT_EQ(direct.status, SolverStatus::kConverged);
    ASSERT_EQ(stored.status[point], 0);
    const std::vector<double> expected = {
        direct.force_T(0),  direct.force_T(1),
        direct.force_T(2),  direct.moment_T(0),
        direct.moment_T(1), direct.moment_T(2),
        direct.force_W(0),  direct.force_W(1),
        direct.force_W(2),  static_cast<double>(direct.patches.size()),
        direct.contact_y,   direct.contact_angle};
    for (std::size_t k = 0; k < expected.size(); ++k) {
      EXPECT_TRUE(SameBits(stored.outputs[k][point], expected[k]))
          << scene_->outputs[k] << " at point " << point << ": " << stored.outputs[k][point]
          << " vs " << expected[k];
    }
    double pmax = 0.0;
    for (const PatchResult& patch : direct.patches) pmax = std::max(pmax, patch.pmax);
    EXPECT_TRUE(SameBits(stored.outputs[OutputIndex(*scene_, "pmax")][point], pmax));
    EXPECT_TRUE(SameBits(stored.outputs[z_out][point], direct.z));
    EXPECT_TRUE(SameBits(stored.outputs[OutputIndex(*scene_, "t_gamma")][point], TGamma(direct)));
    double power = 0.0;
    for (const PatchResult& patch : direct.patches)
      power += FrictionalPower(patch, c.state.velocity);
    EXPECT_TRUE(SameBits(stored.outputs[OutputIndex(*scene_, "frictional_power")][point], power));
    EXPECT_LE(power, 0.0);  // dissipated
    double slip = 0.0, fi_rail = -1e300, fi_wheel = -1e300;
    for (const PatchResult& patch : direct.patches) {
      slip += patch.t_gamma_slip;
      fi_rail = std::max(fi_rail, SurfaceFatigueIndex(patch, 300.0));
      fi_wheel = std::max(fi_wheel, SurfaceFatigueIndex(patch, 350.0));
    }
    EXPECT_TRUE(SameBits(stored.outputs[OutputIndex(*scene_, "t_gamma_slip")][point], slip));
    EXPECT_TRUE(SameBits(stored.outputs[OutputIndex(*scene_, "fi_surf_rail")][point], fi_rail));
    EXPECT_TRUE(SameBits(stored.outputs[OutputIndex(*scene_, "fi_surf_wheel")][point], fi_wheel));
    EXPECT_TRUE(direct.has_force_location);
  }
}

TEST_F(GenerateTest, InterruptedAndResumedRunGivesTheSameBits) {
  const fs::path resumed = *dir_ / "resumed.h5";
  GenerateOptions options = Options(resumed, 2);
  // Stop mid-line twice (5 and 3 more points), so that resumed lines start from journal z's.
  options.max_points = 5;
  GenerateSummary summary = GenerateTable(*scene_, options);
  EXPECT_FALSE(summary.complete);
  EXPECT_TRUE(summary.interrupted);
  EXPECT_EQ(summary.computed, 5u);
  EXPECT_FALSE(fs::exists(resumed));
  EXPECT_TRUE(fs::exists(summary.journal));

  options.resume = true;
  options.max_points = 3;
  options.threads = 1;
  summary = GenerateTable(*scene_, options);
  EXPECT_FALSE(summary.complete);
  EXPECT_EQ(summary.reused, 5u);
  EXPECT_EQ(summary.computed, 3u);

  options.max_points = 0;
  summary = GenerateTable(*scene_, options);
  EXPECT_TRUE(summary.complete);
  EXPECT_EQ(summary.reused, 8u);
  EXPECT_EQ(summary.computed, 4u);
  EXPECT_FALSE(fs::exists(summary.journal));
  test::ExpectIdenticalTables(reference_, resumed);
}

TEST_F(GenerateTest, CancelFlagStopsTheRun) {
  const fs::path output = *dir_ / "cancelled.h5";
  std::atomic<bool> cancel{true};
  GenerateOptions options = Options(output, 2);
  options.cancel = &cancel;
  const GenerateSummary summary = GenerateTable(*scene_, options);
  EXPECT_TRUE(summary.interrupted);
  EXPECT_EQ(summary.computed, 0u);
  EXPECT_FALSE(fs::exists(output));
  fs::remove(summary.journal);
}

TEST_F(GenerateTest, AnExistingJournalNeedsResume) {
  const fs::path output = *dir_ / "journal_exists.h5";
  GenerateOptions options = Options(output, 1);
  options.max_points = 1;
  GenerateTable(*scene_, options);
  options.max_points = 0;
  try {
    GenerateTable(*scene_, options);
    ADD_FAILURE() << "an existing journal was overwritten";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("journal_exists.h5.journal"), std::string::npos) << message;
    EXPECT_NE(message.find("--resume"), std::string::npos) << message;
    EXPECT_NE(message.find("delete"), std::string::npos) << message;
  }
  // The journal of another scene (here: other outputs) cannot be resumed.
  const Scene other = WriteAndLoad(
      *dir_, test::TinyScene(test::DefaultTinyTable() + "\n# changed\n"), "other.toml");
  options.resume = true;
  try {
    GenerateTable(other, options);
    ADD_FAILURE() << "a journal of another scene was resumed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("different"), std::string::npos) << e.what();
  }
  fs::remove(output.string() + ".journal");
}

// The runtime library opens the table and gives back the node values exactly: at a node every
// interpolation weight is 0 or 1.
TEST_F(GenerateTest, RuntimeReproducesNodeValues) {
  const Table table(reference_.string());
  const StoredTable stored = ReadStored(reference_, *scene_);
  ASSERT_EQ(table.num_axes(), 2);
  ASSERT_EQ(table.output_names(), scene_->outputs);
  EXPECT_EQ(table.axis_unit(1), "mm");
  EXPECT_EQ(table.attribute("format"), "wrc-table");
  std::vector<double> out(scene_->outputs.size());
  for (std::size_t point = 0; point < scene_->PointCount(); ++point) {
    const std::vector<std::size_t> indices = IndicesOf(*scene_, point);
    const double coordinates[2] = {scene_->axes[0].values[indices[0]],
                                   scene_->axes[1].values[indices[1]]};
    for (const Interpolation mode : {Interpolation::kLinear, Interpolation::kCubic}) {
      Table& mutable_table = const_cast<Table&>(table);
      mutable_table.set_interpolation(mode);
      EXPECT_EQ(table.eval(coordinates, out.data()), 0);
      for (std::size_t k = 0; k < out.size(); ++k) {
        EXPECT_TRUE(SameBits(out[k], stored.outputs[k][point]))
            << scene_->outputs[k] << " at point " << point << ": " << out[k] << " vs "
            << stored.outputs[k][point];
      }
    }
  }
}

// A point far off the rail fails with status 3 and its message; the others are solved, and
// the point after it in its line starts cold (checked against a direct solve).
TEST(GenerateFailures, FailingPointIsRecordedAndTheRunGoesOn) {
  ScratchDir dir("failing");
  const Scene scene = WriteAndLoad(
      dir, test::TinyScene("axes = [\"y\"]\ny = [-200.0, 0.0, 1.0]\noutputs = [\"fy\", \"z\"]"),
      "failing.toml");
  const fs::path output = dir / "failing.h5";
  const GenerateSummary summary = GenerateTable(scene, Options(output, 2));
  ASSERT_TRUE(summary.complete);
  EXPECT_EQ(summary.status_counts[0], 2u);
  EXPECT_EQ(summary.status_counts[3], 1u);
  ASSERT_EQ(summary.failures.size(), 1u);
  EXPECT_EQ(summary.failures[0].first, 0u);
  EXPECT_NE(summary.failures[0].second.find("nowhere above the rail"), std::string::npos)
      << summary.failures[0].second;

  const StoredTable stored = ReadStored(output, scene);
  EXPECT_EQ(stored.status, (std::vector<std::int8_t>{3, 0, 0}));
  EXPECT_TRUE(std::isnan(stored.outputs[0][0]) && std::isnan(stored.outputs[1][0]));
  // After the failure the next point starts cold: exactly a cold direct solve.
  const PointResult cold = SolveScenePoint(scene, {1});
  EXPECT_TRUE(SameBits(stored.outputs[0][1], cold.values[0]));
  const PointResult warm = SolveScenePoint(scene, {2}, stored.outputs[1][1]);
  EXPECT_TRUE(SameBits(stored.outputs[0][2], warm.values[0]));

  const TableInfo info = ReadTableInfo(output);
  ASSERT_EQ(info.failures.size(), 1u);
  EXPECT_EQ(info.failures[0].index, 0u);
  EXPECT_EQ(info.failures[0].message, summary.failures[0].second);
  EXPECT_EQ(info.status_counts[3], 1u);

  // The runtime opens a table with a failed node and flags lookups next to it.
  const Table table(output.string());
  double out[2];
  const double next_to_failure = -100.0;
  const int flags = table.try_eval(&next_to_failure, out);
  EXPECT_TRUE(flags < 0 || (flags & WRC_FLAG_STATUS) != 0) << flags;
}

// With z prescribed, a lifted wheel has no contact: status 1, zero forces, no location.
TEST(GenerateFailures, NoContactStoresZeroForces) {
  ScratchDir dir("no_contact");
  const Scene scene = WriteAndLoad(
      dir,
      test::TinyScene("axes = [\"z\"]\nz = [-1.0, 0.3]\noutputs = [\"fy\", \"fz\", \"n_patches\", "
                      "\"pmax\", \"contact_y\"]",
                      "y = 0.0", /*tangential=*/false),
      "no_contact.toml");
  const fs::path output = dir / "no_contact.h5";
  const GenerateSummary summary = GenerateTable(scene, Options(output, 1));
  ASSERT_TRUE(summary.complete);
  const StoredTable stored = ReadStored(output, scene);
  EXPECT_EQ(stored.status, (std::vector<std::int8_t>{1, 0}));
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(stored.outputs[k][0], 0.0) << scene.outputs[k];
  EXPECT_TRUE(std::isnan(stored.outputs[4][0]));
  EXPECT_GT(stored.outputs[1][1], 0.0);  // z = 0.3 mm presses the wheel in
  EXPECT_TRUE(std::isfinite(stored.outputs[4][1]));
}

TEST(GenerateFailures, OutputDirectoryMustExist) {
  ScratchDir dir("no_dir");
  const Scene scene = WriteAndLoad(dir, test::TinyScene(test::DefaultTinyTable()), "s.toml");
  EXPECT_THROW(GenerateTable(scene, Options(dir / "missing" / "t.h5", 1)), InputError);
}

}  // namespace
}  // namespace wrc
