// The wheelset FMU as an importer uses it: `wrc fmu` packs a table generated here, the test's
// own FMI 3.0 importer (fmi3_importer.h) unpacks and loads it, and a 2 s wheelset simulation
// runs on its forces, step by step against the C runtime's wheelset on the HDF5 table it was
// made from. The FMU reads the flat copy of that table, which the runtime reads to the bit
// (runtime_flat_test.cpp), and converts units (m, N·m) on the way: forces agree exactly and
// the converted outputs within a rounding of the unit conversion.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "fmu/variables.h"
#include "tests/fmu/fmi2_importer.h"
#include "tests/fmu/fmi3_importer.h"
#include "tests/tools/tool_test_util.h"
#include "wrc/runtime.h"

namespace {

namespace fs = std::filesystem;
using wrc::test::Fmi2Fmu;
using wrc::test::Fmi3Fmu;
using wrc::test::Log;
using wrc::tool_test::kSource;
using wrc::tool_test::ReadFile;
using wrc::tool_test::RunWrcIn;
namespace fmi3 = wrc::fmu::fmi3;

// The Manchester pair at 1 mm elements over y, yaw and spin, with the outputs the wheelset reads.
std::string Scene() {
  std::string scene = ReadFile(kSource / "tables" / "mbench.toml");
  scene = scene.substr(0, scene.find("[grid]"));
  return scene +
         "[grid]\ndx = 1.0\nds = 1.0\n[method]\nreference = \"curved\"\n"
         "[state]\nvelocity = 2000.0\nfz = 10000.0\n"
         "[table]\naxes = [\"y\", \"yaw\", \"spin\"]\n"
         "y = [-2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0]\n"
         "yaw = [-0.002, -0.0005, 0.0, 0.0005, 0.002]\nspin = [-0.002, 0.0, 0.002]\n"
         "outputs = [\"fx\", \"fy\", \"fz\", \"mx\", \"my\", \"mz\", \"contact_y\", "
         "\"contact_angle\", \"t_gamma\"]\n";
}

class Fmu : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("wrc_fmu_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_ / "profiles");
    for (const char* name : {"MBench_UIC60_v3.prr", "MBench_S1002_v3.prw"}) {
      fs::copy_file(kSource / "tables" / "profiles" / name, *dir_ / "profiles" / name);
    }
    std::ofstream(*dir_ / "scene.toml") << Scene();
    generate_ = RunWrcIn(*dir_, "generate scene.toml -o t.h5 --threads 2", 600);
    if (generate_ != 0) return;
    pack_ = RunWrcIn(*dir_, "fmu t.h5 -o wheelset.fmu", 120);
    if (pack_ == 0) wrc::test::Unzip(*dir_ / "wheelset.fmu", *dir_ / "unpacked");
    if (pack_ == 0) pack_ = RunWrcIn(*dir_, "fmu t.h5 --fmi-version 2 -o wheelset2.fmu", 120);
    // A space in the path: FMI 2.0 passes the resources as a URI, with %20.
    if (pack_ == 0) wrc::test::Unzip(*dir_ / "wheelset2.fmu", *dir_ / "unpacked2");
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  void SetUp() override {
    ASSERT_EQ(generate_, 0) << ReadFile(*dir_ / "stderr.txt");
    ASSERT_EQ(pack_, 0) << ReadFile(*dir_ / "stderr.txt");
    fmu_ = std::make_unique<Fmi3Fmu>(*dir_ / "unpacked");
  }

  // An instance through initialization, with the interpolation given.
  void* Start(int interpolation = wrc::fmu::kInterpolationLinear) {
    void* instance = fmu_->Instantiate3(&log_, fmu_->token());
    EXPECT_NE(instance, nullptr) << log_.All();
    const fmi3::ValueReference vr = fmu_->Vr("interpolation");
    const std::int64_t value = interpolation;
    EXPECT_EQ(fmu_->set_int64(instance, &vr, 1, &value, 1), fmi3::kOK) << log_.All();
    EXPECT_EQ(fmu_->enter_initialization(instance, false, 0.0, 0.0, false, 0.0), fmi3::kOK);
    EXPECT_EQ(fmu_->exit_initialization(instance), fmi3::kOK) << log_.All();
    return instance;
  }

  static fs::path* dir_;
  static int generate_, pack_;
  std::unique_ptr<Fmi3Fmu> fmu_;
  Log log_;
};
fs::path* Fmu::dir_ = nullptr;
int Fmu::generate_ = -1;
int Fmu::pack_ = -1;

// The runtime's wheelset on the HDF5 table, mirrored for the left wheel as the FMU is.
struct RuntimeWheelset {
  template <typename Importer>
  RuntimeWheelset(const fs::path& table, int interpolation, const Importer& fmu, void* instance) {
    EXPECT_EQ(wrc_table_open(table.c_str(), &t), 0) << wrc_last_error();
    wrc_table_set_interpolation(t, interpolation);
    EXPECT_EQ(wrc_wheelset_create(nullptr, t, &w), 0) << wrc_last_error();
    for (const auto& [side, name] : {std::pair{WRC_LEFT, "left"}, std::pair{WRC_RIGHT, "right"}}) {
      const std::string prefix = std::string(name) + ".rail_origin_";
      wrc_wheelset_set_rail_origin(w, side, 1000.0 * fmu.GetFloat64(instance, prefix + "y"),
                                   1000.0 * fmu.GetFloat64(instance, prefix + "z"));
    }
  }
  ~RuntimeWheelset() {
    wrc_wheelset_destroy(w);
    wrc_table_close(t);
  }
  wrc_table* t = nullptr;
  wrc_wheelset* w = nullptr;
};

// A wheelset on stiff primary springs, stable at 20 m/s, SI units.
struct Body {
  double y = 0.001, yaw = 0.0, vy = 0.0, vyaw = 0.0;
};
constexpr double kMass = 1813.0, kYawInertia = 1120.0;      // kg, kg m²
constexpr double kKy = 1e6, kKx = 1e7, kSemiSpacing = 1.0;  // N/m per axlebox, m
constexpr double kSpeed = 20.0, kRadius = 0.46;             // m/s, m
constexpr double kStep = 1e-3;                              // s

// The FMU's output name, the runtime's value in FMU units' scale (runtime units per FMU unit).
struct Compared {
  const char* name;
  double scale;
  double (*runtime)(const wrc_wheelset_result&);
};
const Compared kCompared[] = {
    {"wheelset.fy", 1.0, [](const wrc_wheelset_result& r) { return r.force[1]; }},
    {"wheelset.mz", 1000.0, [](const wrc_wheelset_result& r) { return r.moment[2]; }},
    {"wheelset.mx", 1000.0, [](const wrc_wheelset_result& r) { return r.moment[0]; }},
    {"left.fx", 1.0, [](const wrc_wheelset_result& r) { return r.wheel[WRC_LEFT].force[0]; }},
    {"right.fy", 1.0, [](const wrc_wheelset_result& r) { return r.wheel[WRC_RIGHT].force[1]; }},
    {"right.fz", 1.0, [](const wrc_wheelset_result& r) { return r.wheel[WRC_RIGHT].force[2]; }},
    {"left.mz", 1000.0, [](const wrc_wheelset_result& r) { return r.wheel[WRC_LEFT].moment[2]; }},
    {"right.contact_y", 1000.0,
     [](const wrc_wheelset_result& r) { return r.wheel[WRC_RIGHT].contact_y; }},
    {"left.t_gamma", 1.0, [](const wrc_wheelset_result& r) { return r.wheel[WRC_LEFT].t_gamma; }},
};

// Runs `steps` co-simulation steps; returns the largest difference of FMU and runtime relative
// to the runtime's value (+1 N or N·mm), and the body's final state in *body.
template <typename Importer>
double Simulate(const Importer& fmu, void* instance, const RuntimeWheelset& runtime, int steps,
                Body* body) {
  double worst = 0.0;
  Body& b = *body;
  for (int i = 0; i < steps; ++i) {
    const double inputs[] = {b.y, b.yaw, b.vy, b.vyaw, kSpeed, -kSpeed / kRadius};
    const char* names[] = {"y", "yaw", "vy", "vyaw", "velocity", "omega"};
    for (int k = 0; k < 6; ++k) EXPECT_EQ(fmu.SetFloat64(instance, names[k], inputs[k]), 0);
    EXPECT_EQ(fmu.Step(instance, i * kStep, kStep), 0);

    wrc_wheelset_state s;
    wrc_wheelset_state_init(&s);
    s.y = b.y * 1000.0, s.yaw = b.yaw, s.vy = b.vy * 1000.0, s.vyaw = b.vyaw;
    s.velocity = kSpeed * 1000.0, s.omega = -kSpeed / kRadius;
    wrc_wheelset_result r;
    EXPECT_GE(wrc_wheelset_eval(runtime.w, &s, &r), 0) << wrc_last_error();
    for (const Compared& c : kCompared) {
      const double from_fmu = fmu.GetFloat64(instance, c.name) * c.scale;
      const double difference =
          std::fabs(from_fmu - c.runtime(r)) / (1.0 + std::fabs(c.runtime(r)));
      worst = std::max(worst, difference);
    }
    const double fy = fmu.GetFloat64(instance, "wheelset.fy");
    const double mz = fmu.GetFloat64(instance, "wheelset.mz");
    b.vy += kStep * (fy - 2.0 * kKy * b.y) / kMass;  // semi-implicit Euler
    b.vyaw += kStep * (mz - 2.0 * kKx * kSemiSpacing * kSemiSpacing * b.yaw) / kYawInertia;
    b.y += kStep * b.vy;
    b.yaw += kStep * b.vyaw;
  }
  return worst;
}

TEST_F(Fmu, SimulatesTwoSecondsWithTheRuntimesForces) {
  void* instance = Start();
  RuntimeWheelset runtime(*dir_ / "t.h5", WRC_INTERP_LINEAR, *fmu_, instance);
  Body body;
  const double worst = Simulate(*fmu_, instance, runtime, 2000, &body);
  // Forces pass unconverted (exactly equal); moments and positions are divided by 1000 in the
  // FMU and multiplied back here: within two roundings.
  EXPECT_LT(worst, 1e-15);
  std::cout << "largest relative difference FMU - runtime over 2 s: " << worst << '\n';
  // The wheelset moved: the forces acted (centring from 1 mm), it did not run away.
  EXPECT_LT(std::fabs(body.y), 0.002);
  EXPECT_GT(std::fabs(fmu_->GetFloat64(instance, "wheelset.fy")), 0.0);
  EXPECT_EQ(fmu_->terminate(instance), fmi3::kOK);
  fmu_->free_instance(instance);
}

TEST_F(Fmu, CubicInterpolationIsTheRuntimesToo) {
  void* instance = Start(wrc::fmu::kInterpolationCubic);
  RuntimeWheelset runtime(*dir_ / "t.h5", WRC_INTERP_CUBIC, *fmu_, instance);
  Body body;
  EXPECT_LT(Simulate(*fmu_, instance, runtime, 200, &body), 1e-15);
  fmu_->free_instance(instance);
}

// Start values come from the table: its speed, its wheel load, the solver's rail origins.
// --left: a table of its own for the left wheel, packed beside the right one. Given the right
// wheel's table again, the left wheel reads it mirrored, as the one-table FMU does: the same
// forces to the bit.
TEST_F(Fmu, PacksATableForTheLeftWheel) {
  ASSERT_EQ(RunWrcIn(*dir_, "fmu t.h5 --left t.h5 -o two.fmu", 120), 0)
      << ReadFile(*dir_ / "stderr.txt");
  wrc::test::Unzip(*dir_ / "two.fmu", *dir_ / "two");
  EXPECT_TRUE(fs::is_regular_file(*dir_ / "two" / "resources" / "left.wrct"));
  Fmi3Fmu two(*dir_ / "two");
  void* a = Start();
  void* b = two.Instantiate3(&log_, two.token());
  ASSERT_NE(b, nullptr) << log_.All();
  EXPECT_EQ(two.enter_initialization(b, false, 0.0, 0.0, false, 0.0), fmi3::kOK);
  EXPECT_EQ(two.exit_initialization(b), fmi3::kOK) << log_.All();
  for (const double y : {-0.0015, 0.0004, 0.0019}) {
    EXPECT_EQ(fmu_->SetFloat64(a, "y", y), fmi3::kOK);
    EXPECT_EQ(two.SetFloat64(b, "y", y), fmi3::kOK);
    for (const char* name : {"left.fy", "left.mz", "right.fy", "wheelset.fy"}) {
      EXPECT_EQ(fmu_->GetFloat64(a, name), two.GetFloat64(b, name)) << name << ' ' << y;
    }
  }
  fmu_->free_instance(a);
  two.free_instance(b);
}

TEST_F(Fmu, StartsAtTheTablesOwnState) {
  void* instance = Start();
  EXPECT_DOUBLE_EQ(fmu_->GetFloat64(instance, "velocity"), 2.0);
  EXPECT_DOUBLE_EQ(fmu_->GetFloat64(instance, "right.wheel_load"), 10000.0);
  const double origin = fmu_->GetFloat64(instance, "right.rail_origin_y");
  EXPECT_GT(origin, 0.7);  // m: half the gauge and a rail head's width from the track centre
  EXPECT_LT(origin, 0.8);
  EXPECT_DOUBLE_EQ(fmu_->GetFloat64(instance, "left.rail_origin_y"), -origin);
  // Centred, at the table's speed: the two wheels carry the load each, symmetric.
  EXPECT_NEAR(fmu_->GetFloat64(instance, "right.fz"), 10000.0, 1e-6 * 10000.0);
  EXPECT_NEAR(fmu_->GetFloat64(instance, "wheelset.fy"), 0.0, 1e-6 * 10000.0);
  fmu_->free_instance(instance);
}

TEST_F(Fmu, RefusesWhatTheStandardForbidsWithAMessage) {
  EXPECT_EQ(fmu_->Instantiate3(&log_, "{another FMU}"), nullptr);
  ASSERT_FALSE(log_.messages.empty());
  EXPECT_NE(log_.All().find("instantiation token"), std::string::npos) << log_.All();

  void* instance = Start();
  log_.messages.clear();
  // A fixed parameter after initialization, an output, the independent variable.
  const std::int64_t cubic = wrc::fmu::kInterpolationCubic;
  const fmi3::ValueReference interpolation = fmu_->Vr("interpolation");
  EXPECT_EQ(fmu_->set_int64(instance, &interpolation, 1, &cubic, 1), fmi3::kError);
  EXPECT_EQ(fmu_->SetFloat64(instance, "wheelset.fy", 1.0), fmi3::kError);
  EXPECT_EQ(fmu_->SetFloat64(instance, "time", 1.0), fmi3::kError);
  EXPECT_EQ(log_.messages.size(), 3u) << log_.All();
  EXPECT_NE(log_.All().find("fixed parameter"), std::string::npos) << log_.All();
  // A NaN state: the lookup fails, the outputs are NaN and status says why.
  EXPECT_EQ(fmu_->SetFloat64(instance, "y", NAN), fmi3::kOK);
  fmi3::Status status = fmi3::kOK;
  EXPECT_TRUE(std::isnan(fmu_->GetFloat64(instance, "wheelset.fy", &status)));
  EXPECT_EQ(status, fmi3::kError);
  const fmi3::ValueReference status_vr = fmu_->Vr("status");
  std::int32_t code = 0;
  fmu_->get_int32(instance, &status_vr, 1, &code, 1);
  EXPECT_EQ(code, WRC_ERR_NAN_INPUT);
  EXPECT_NE(log_.All().find("NaN"), std::string::npos) << log_.All();
  fmu_->free_instance(instance);
}

TEST_F(Fmu, NamesATableItCannotRead) {
  void* instance = fmu_->Instantiate3(&log_, fmu_->token());
  ASSERT_NE(instance, nullptr);
  const fmi3::ValueReference vr = fmu_->Vr("right_table");
  const fmi3::String missing = "missing.wrct";
  EXPECT_EQ(fmu_->set_string(instance, &vr, 1, &missing, 1), fmi3::kOK);
  EXPECT_EQ(fmu_->enter_initialization(instance, false, 0.0, 0.0, false, 0.0), fmi3::kOK);
  EXPECT_EQ(fmu_->exit_initialization(instance), fmi3::kError);
  EXPECT_NE(log_.All().find("missing.wrct"), std::string::npos) << log_.All();
  fmu_->free_instance(instance);
}

// What an importer finds in the binary: every function of the FMI 3.0 API, and nothing of the
// runtime that could clash with a simulator's own copy; and no HDF5 among its libraries.
TEST_F(Fmu, ExportsTheStandardsFunctionsOnly) {
  for (const char* name : {"fmi3GetVersion",
                           "fmi3SetDebugLogging",
                           "fmi3InstantiateModelExchange",
                           "fmi3InstantiateCoSimulation",
                           "fmi3InstantiateScheduledExecution",
                           "fmi3FreeInstance",
                           "fmi3EnterInitializationMode",
                           "fmi3ExitInitializationMode",
                           "fmi3EnterEventMode",
                           "fmi3Terminate",
                           "fmi3Reset",
                           "fmi3GetFloat32",
                           "fmi3GetFloat64",
                           "fmi3GetInt8",
                           "fmi3GetUInt8",
                           "fmi3GetInt16",
                           "fmi3GetUInt16",
                           "fmi3GetInt32",
                           "fmi3GetUInt32",
                           "fmi3GetInt64",
                           "fmi3GetUInt64",
                           "fmi3GetBoolean",
                           "fmi3GetString",
                           "fmi3GetBinary",
                           "fmi3GetClock",
                           "fmi3SetFloat32",
                           "fmi3SetFloat64",
                           "fmi3SetInt8",
                           "fmi3SetUInt8",
                           "fmi3SetInt16",
                           "fmi3SetUInt16",
                           "fmi3SetInt32",
                           "fmi3SetUInt32",
                           "fmi3SetInt64",
                           "fmi3SetUInt64",
                           "fmi3SetBoolean",
                           "fmi3SetString",
                           "fmi3SetBinary",
                           "fmi3SetClock",
                           "fmi3GetNumberOfVariableDependencies",
                           "fmi3GetVariableDependencies",
                           "fmi3GetFMUState",
                           "fmi3SetFMUState",
                           "fmi3FreeFMUState",
                           "fmi3SerializedFMUStateSize",
                           "fmi3SerializeFMUState",
                           "fmi3DeserializeFMUState",
                           "fmi3GetDirectionalDerivative",
                           "fmi3GetAdjointDerivative",
                           "fmi3EnterConfigurationMode",
                           "fmi3ExitConfigurationMode",
                           "fmi3GetIntervalDecimal",
                           "fmi3GetIntervalFraction",
                           "fmi3GetShiftDecimal",
                           "fmi3GetShiftFraction",
                           "fmi3SetIntervalDecimal",
                           "fmi3SetIntervalFraction",
                           "fmi3SetShiftDecimal",
                           "fmi3SetShiftFraction",
                           "fmi3EvaluateDiscreteStates",
                           "fmi3UpdateDiscreteStates",
                           "fmi3EnterContinuousTimeMode",
                           "fmi3CompletedIntegratorStep",
                           "fmi3SetTime",
                           "fmi3SetContinuousStates",
                           "fmi3GetContinuousStateDerivatives",
                           "fmi3GetEventIndicators",
                           "fmi3GetContinuousStates",
                           "fmi3GetNominalsOfContinuousStates",
                           "fmi3GetNumberOfEventIndicators",
                           "fmi3GetNumberOfContinuousStates",
                           "fmi3EnterStepMode",
                           "fmi3GetOutputDerivatives",
                           "fmi3DoStep",
                           "fmi3ActivateModelPartition"}) {
    EXPECT_NE(fmu_->Symbol(name), nullptr) << name;
  }
  EXPECT_EQ(fmu_->Symbol("wrc_table_open"), nullptr);
  const fs::path so = *dir_ / "unpacked" / "binaries" / "x86_64-linux" / "wrc_wheelset.so";
  const std::string command =
      "readelf -d '" + so.string() + "' > '" + (*dir_ / "needed.txt").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string needed = ReadFile(*dir_ / "needed.txt");
  for (const char* library : {"hdf5", "stdc++", "nettle"}) {
    EXPECT_EQ(needed.find(library), std::string::npos) << library << '\n' << needed;
  }
}

// modelDescription.xml against the standard's schema (tests/data/fmi, FMI 3.0.2).
TEST_F(Fmu, ModelDescriptionValidatesAgainstTheFmiSchema) {
  const fs::path schema =
      kSource / "tests" / "data" / "fmi" / "fmi3-schema-v3.0.2" / "fmi3ModelDescription.xsd";
  const std::string command = "xmllint --noout --schema '" + schema.string() + "' '" +
                              (*dir_ / "unpacked" / "modelDescription.xml").string() + "' > '" +
                              (*dir_ / "xmllint.txt").string() + "' 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << ReadFile(*dir_ / "xmllint.txt");
  EXPECT_NE(ReadFile(*dir_ / "xmllint.txt").find("validates"), std::string::npos);
}

// The same FMU as FMI 2.0: the same binary behind the older API, its XML against the 2.0.5
// schema, the same 2 s simulation against the runtime.
TEST_F(Fmu, AlsoServesFmi2) {
  Fmi2Fmu fmu(*dir_ / "unpacked2");
  EXPECT_EQ(fmu.Instantiate2(&log_, "{another FMU}"), nullptr);
  EXPECT_NE(log_.All().find("GUID"), std::string::npos) << log_.All();
  void* instance = fmu.Instantiate2(&log_, fmu.guid());
  ASSERT_NE(instance, nullptr) << log_.All();
  EXPECT_EQ(fmu.setup(instance, 0, 0.0, 0.0, 0, 0.0), 0);
  EXPECT_EQ(fmu.enter_initialization(instance), 0);
  EXPECT_EQ(fmu.exit_initialization(instance), 0) << log_.All();
  RuntimeWheelset runtime(*dir_ / "t.h5", WRC_INTERP_LINEAR, fmu, instance);
  Body body;
  EXPECT_LT(Simulate(fmu, instance, runtime, 2000, &body), 1e-15);
  EXPECT_LT(std::fabs(body.y), 0.002);
  // A lookup that fails logs its reason through the variadic logger, '%' and all.
  EXPECT_EQ(fmu.SetFloat64(instance, "velocity", -1.0), 0);
  EXPECT_EQ(fmu.Step(instance, 2.0, kStep), 3);  // fmi2Error
  EXPECT_NE(log_.All().find("velocity"), std::string::npos) << log_.All();
  EXPECT_EQ(fmu.terminate(instance), 0);
  fmu.free_instance(instance);
  for (const char* name : {"fmi2GetTypesPlatform",
                           "fmi2GetVersion",
                           "fmi2SetDebugLogging",
                           "fmi2Instantiate",
                           "fmi2FreeInstance",
                           "fmi2SetupExperiment",
                           "fmi2EnterInitializationMode",
                           "fmi2ExitInitializationMode",
                           "fmi2Terminate",
                           "fmi2Reset",
                           "fmi2GetReal",
                           "fmi2GetInteger",
                           "fmi2GetBoolean",
                           "fmi2GetString",
                           "fmi2SetReal",
                           "fmi2SetInteger",
                           "fmi2SetBoolean",
                           "fmi2SetString",
                           "fmi2GetFMUstate",
                           "fmi2SetFMUstate",
                           "fmi2FreeFMUstate",
                           "fmi2SerializedFMUstateSize",
                           "fmi2SerializeFMUstate",
                           "fmi2DeSerializeFMUstate",
                           "fmi2GetDirectionalDerivative",
                           "fmi2SetRealInputDerivatives",
                           "fmi2GetRealOutputDerivatives",
                           "fmi2DoStep",
                           "fmi2CancelStep",
                           "fmi2GetStatus",
                           "fmi2GetRealStatus",
                           "fmi2GetIntegerStatus",
                           "fmi2GetBooleanStatus",
                           "fmi2GetStringStatus"}) {
    EXPECT_NE(fmu.Symbol(name), nullptr) << name;
  }
  const fs::path schema =
      kSource / "tests" / "data" / "fmi" / "fmi2-schema-v2.0.5" / "fmi2ModelDescription.xsd";
  const std::string command = "xmllint --noout --schema '" + schema.string() + "' '" +
                              (*dir_ / "unpacked2" / "modelDescription.xml").string() + "' > '" +
                              (*dir_ / "xmllint2.txt").string() + "' 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << ReadFile(*dir_ / "xmllint2.txt");
}

}  // namespace
