#pragma once
// Shared parts of the generator tests: scratch directories, a tiny scene, bit-exact table
// comparison and running the `wrc` binary.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/hdf5/hdf5.h"
#include "tests/support/files.h"
#include "tests/support/run.h"

namespace wrc::test {

namespace fs = std::filesystem;

/// A fresh directory under the system temp dir, removed with everything in it afterwards.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name) {
    path_ = fs::temp_directory_path() / ("wrc_gen_" + name + "_" + std::to_string(::getpid()) +
                                         "_" + std::to_string(counter_++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
  static inline int counter_ = 0;
};

inline std::string ProfilePath(const std::string& name) {
  return (fs::path(WRC_SOURCE_DIR) / "tables" / "profiles" / name).string();
}

/// A small Manchester-benchmark scene: coarse 1 mm elements keep each solve at a few
/// hundredths of a second. `table` is the [table] section's body.
inline std::string TinyScene(const std::string& table, const std::string& state = "fz = 10000.0",
                             bool tangential = true) {
  std::ostringstream text;
  text << "[problem]\ntype = \"wheel-rail\"\n"
       << "[rail]\nprofile = \"" << ProfilePath("MBench_UIC60_v3.prr") << "\"\n"
       << "[wheel]\nprofile = \"" << ProfilePath("MBench_S1002_v3.prw") << "\"\n"
       << "[grid]\ndx = 1.0\nds = 1.0\n"
       // Rail and wheel steels' yield limits in shear, for the surface-fatigue outputs.
       << "[material]\nshear_yield = [300.0, 350.0]\n"
       << "[effects]\ntangential = " << (tangential ? "true" : "false") << "\n"
       << "[state]\n"
       << state
       << "\n"
       // Every case states its forward velocity; 2 m/s unless the test gives its own.
       << (state.find("velocity") == std::string::npos ? "velocity = 2000.0\n" : "") << "[table]\n"
       << table << "\n";
  return text.str();
}

/// 2 yaw angles × 6 lateral positions, every output.
inline std::string DefaultTinyTable() {
  return "axes = [\"yaw\", \"y\"]\n"
         "yaw = [0.0, 0.004]\n"
         "y = {from = 0.0, to = 5.0, step = 1.0}\n"
         "outputs = [\"fx\", \"fy\", \"fz\", \"mx\", \"my\", \"mz\", \"fx_ws\", \"fy_ws\", "
         "\"fz_ws\", \"n_patches\", \"contact_y\", \"contact_angle\", \"pmax\", \"z\", "
         "\"t_gamma\", \"frictional_power\", \"t_gamma_slip\", \"fi_surf_rail\", "
         "\"fi_surf_wheel\"]";
}

using test_support::ReadFile;
using test_support::WriteFile;

/// Everything a table stores, as bytes per object path, for bit-exact comparison: every
/// dataset's values (numbers as the bits of float64, strings as they are) and every string
/// attribute. Left out: /solve_time_s and the root attributes `created` and
/// `refine_cpu_seconds`, which record when and how fast the table was made, not what it holds.
inline std::map<std::string, std::string> TableContents(const fs::path& path) {
  std::map<std::string, std::string> contents;
  const auto lock = h5::LibraryLock();
  const h5::File file = h5::File::Open(path.string());
  auto attributes = [&contents](const h5::Object& object) {
    for (const std::string& name : object.AttributeNames()) {
      if (object.Path() == "/" && (name == "created" || name == "refine_cpu_seconds")) continue;
      const h5::Attribute attribute = object.OpenAttribute(name);
      std::string value;
      if (attribute.Type().Class() == h5::TypeClass::kString) {
        for (const std::string& s : attribute.ReadStrings()) value += s + '\0';
      } else {
        value = std::to_string(attribute.ReadDouble());
      }
      contents[object.Path() + "@" + name] = value;
    }
  };
  std::function<void(const h5::Group&)> walk = [&](const h5::Group& group) {
    attributes(group);
    for (const std::string& name : group.MemberNames()) {
      if (group.Kind(name) == h5::LinkKind::kGroup) {
        walk(group.OpenGroup(name));
        continue;
      }
      const h5::Dataset dataset = group.OpenDataset(name);
      if (dataset.Path() == "/solve_time_s") continue;
      attributes(dataset);
      std::string bytes;
      if (dataset.Type().Class() == h5::TypeClass::kString) {
        for (const std::string& s : dataset.ReadStrings()) bytes += s + '\0';
      } else {
        const std::vector<double> values = dataset.Read<double>();
        bytes.resize(values.size() * sizeof(double));
        if (!values.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
      }
      contents[dataset.Path()] = bytes;
    }
  };
  walk(file);
  return contents;
}

/// Expects two tables to hold the same bits (see TableContents), naming what differs.
inline void ExpectIdenticalTables(const fs::path& a, const fs::path& b) {
  const auto contents_a = TableContents(a);
  const auto contents_b = TableContents(b);
  for (const auto& [name, value] : contents_a) {
    const auto other = contents_b.find(name);
    if (other == contents_b.end()) {
      ADD_FAILURE() << name << " is in " << a << " but not in " << b;
    } else if (other->second != value) {
      ADD_FAILURE() << name << " differs between " << a << " and " << b;
    }
  }
  for (const auto& [name, value] : contents_b) {
    if (contents_a.count(name) == 0) ADD_FAILURE() << name << " is in " << b << " only";
  }
}

using test_support::CommandResult;
using test_support::Quoted;
using test_support::RunCommand;

inline std::string WrcBinary() { return test_support::WrcBinary().string(); }

}  // namespace wrc::test
