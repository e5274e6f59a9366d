// The flat table (runtime/format/flat_table.h): what the runtime loads from it is what it loads
// from the HDF5 table it was exported from, to the bit; a damaged, truncated, extended or
// malformed flat file is refused with a message naming the problem, never a crash.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "runtime/format/flat_table.h"
#include "tests/runtime/table_writer.h"
#include "tests/support/flat_table.h"
#include "wrc/runtime.h"
#include "wrc/runtime.hpp"

namespace {

using wrc::format::DecodeFlatTable;
using wrc::format::EncodeFlatTable;
using wrc::format::ReadTableContent;
using wrc::test::ScratchFile;

// Four axes (one refined, one of a single node), eleven outputs (more than the multilinear
// kernel's chunk of 8), and failed nodes: every path of a lookup. `small`: 2 kB, for scans of
// every byte.
wrc::test::TableContent ExportedTable(bool small = false) {
  wrc::test::TableContent content;
  content.axes = {{"y", {-10.0, -4.0, -1.0, -0.5, 0.0, 0.25, 1.0, 3.0, 10.0}, "mm"},
                  {"fz", {50000.0}, "N"},
                  {"yaw", wrc::test::Linspace(-0.01, 0.01, 5), "rad"},
                  {"spin", wrc::test::Linspace(-0.01, 0.01, 7), "-"}};
  if (small) content.axes = {{"y", {-1.0, 0.0, 0.5, 3.0}, "mm"}, {"yaw", {-0.01, 0.01}, "rad"}};
  for (int k = 0; k < 11; ++k) content.outputs.push_back("out" + std::to_string(k));
  // y first, yaw third (second of the small table), spin fourth (none in the small table).
  content.function = [](int k, const std::vector<double>& x) {
    const double yaw = x[x.size() > 2 ? 2 : 1], spin = x.size() > 3 ? x[3] : 0.0;
    const bool failed = x[0] == 3.0 && yaw > 0.0;
    return failed ? NAN : std::sin(0.3 * x[0] + k) * 1e3 + 4e4 * yaw * spin + k * x[0] * x[0];
  };
  content.status = [](const std::vector<double>& x) -> std::int8_t {
    return x[0] == 3.0 && x[x.size() > 2 ? 2 : 1] > 0.0 ? 2 : 0;
  };
  content.scene = "[state]\nvelocity = 2000.0\n";
  content.sealed = true;
  return content;
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

struct Pair {
  ScratchFile h5{"flat-source"};
  ScratchFile flat{"flat"};
  explicit Pair(bool small = false) {
    wrc::test::WriteTable(h5.path(), ExportedTable(small));
    wrc::format::WriteFlatTable(ReadTableContent(h5.path()), flat.path());
  }
};

// The error code and message of opening `path`.
std::pair<int, std::string> OpenError(const std::string& path) {
  wrc_table* table = nullptr;
  const int code = wrc_table_open(path.c_str(), &table);
  if (code == 0) wrc_table_close(table);
  return {code, code == 0 ? std::string() : std::string(wrc_last_error())};
}

TEST(RuntimeFlat, HoldsWhatTheHdf5TableHolds) {
  const Pair files;
  const wrc::Table h5(files.h5.path());
  const wrc::Table flat(files.flat.path());
  ASSERT_EQ(flat.num_axes(), h5.num_axes());
  ASSERT_EQ(flat.num_outputs(), h5.num_outputs());
  for (int a = 0; a < h5.num_axes(); ++a) {
    EXPECT_EQ(flat.axis_name(a), h5.axis_name(a));
    EXPECT_EQ(flat.axis_unit(a), h5.axis_unit(a));
    EXPECT_EQ(flat.axis_values(a), h5.axis_values(a));
  }
  for (int k = 0; k < h5.num_outputs(); ++k) {
    EXPECT_EQ(flat.output_name(k), h5.output_name(k));
    EXPECT_EQ(flat.output_unit(k), h5.output_unit(k));
  }
  for (const char* name : {"format", "wrc_version", "scene", "rail_profile_sha256"}) {
    EXPECT_EQ(flat.attribute(name), h5.attribute(name)) << name;
  }
  EXPECT_EQ(flat.attribute("scene"), "[state]\nvelocity = 2000.0\n");
  EXPECT_EQ(flat.warning(), "");
}

// The same lookups to the bit, both modes, with derivatives, over 10^6 random points that
// reach outside the axes and into the failed nodes' cells.
TEST(RuntimeFlat, LooksUpTheSameBitsAsTheHdf5Table) {
  const Pair files;
  wrc::Table h5(files.h5.path());
  wrc::Table flat(files.flat.path());
  std::mt19937_64 random(20261206);
  std::uniform_real_distribution<double> unit(-0.1, 1.1);
  const int n_axes = h5.num_axes(), n_out = h5.num_outputs();
  std::vector<double> point(n_axes), out_h5(n_out), out_flat(n_out);
  std::vector<double> d_h5(n_out * n_axes), d_flat(n_out * n_axes);
  int differing = 0, flags_differing = 0;
  for (const wrc::Interpolation mode : {wrc::Interpolation::kLinear, wrc::Interpolation::kCubic}) {
    h5.set_interpolation(mode);
    flat.set_interpolation(mode);
    for (int i = 0; i < 500000; ++i) {
      for (int a = 0; a < n_axes; ++a) {
        const std::vector<double>& v = h5.axis_values(a);
        point[a] = v.front() + unit(random) * (v.back() - v.front());
      }
      const int f_h5 = wrc_table_eval_deriv(h5.get(), point.data(), out_h5.data(), d_h5.data());
      const int f_flat =
          wrc_table_eval_deriv(flat.get(), point.data(), out_flat.data(), d_flat.data());
      flags_differing += f_h5 != f_flat;
      if (f_h5 < 0) continue;
      differing += std::memcmp(out_h5.data(), out_flat.data(), 8 * n_out) != 0 ||
                   std::memcmp(d_h5.data(), d_flat.data(), 8 * n_out * n_axes) != 0;
    }
  }
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(flags_differing, 0);
}

TEST(RuntimeFlat, EveryChangedByteIsRefused) {
  const Pair files(/*small=*/true);
  const std::string bytes = ReadBytes(files.flat.path());
  ScratchFile damaged("flat-damaged");
  int opened = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    std::string copy = bytes;
    copy[i] = static_cast<char>(copy[i] ^ 0x5A);
    WriteBytes(damaged.path(), copy);
    const auto [code, message] = OpenError(damaged.path());
    opened += code == 0;
    // A damaged magic is no longer a flat table: refused as a file of no known kind.
    if (code != 0) {
      EXPECT_EQ(code, i < 8 ? WRC_ERR_FILE : WRC_ERR_FORMAT) << i << ": " << message;
    }
  }
  EXPECT_EQ(opened, 0);
}

TEST(RuntimeFlat, TruncatedOrExtendedFilesAreRefused) {
  const Pair files;
  const std::string bytes = ReadBytes(files.flat.path());
  ScratchFile damaged("flat-cut");
  for (const std::size_t keep : {std::size_t{0}, std::size_t{7}, std::size_t{63}, std::size_t{64},
                                 bytes.size() / 2, bytes.size() - 1}) {
    WriteBytes(damaged.path(), bytes.substr(0, keep));
    const auto [code, message] = OpenError(damaged.path());
    EXPECT_EQ(code, keep < 8 ? WRC_ERR_FILE : WRC_ERR_FORMAT) << keep << ": " << message;
  }
  WriteBytes(damaged.path(), bytes + std::string(8, '\0'));
  const auto [code, message] = OpenError(damaged.path());
  EXPECT_EQ(code, WRC_ERR_FORMAT);
  EXPECT_NE(message.find("damaged: the header gives a size of"), std::string::npos) << message;
}

// Damage behind a digest that matches (a writer's bug, or a forger): the parser names it.
TEST(RuntimeFlat, MalformedBodiesAreRefusedByName) {
  const Pair files;
  const std::string bytes = ReadBytes(files.flat.path());
  const auto decode_error = [](const std::string& forged) {
    try {
      DecodeFlatTable(forged, "forged.wrct");
    } catch (const wrc::TableError& e) {
      EXPECT_EQ(e.code(), WRC_ERR_FORMAT);
      return std::string(e.what());
    }
    return std::string("decoded");
  };
  std::string forged = bytes;
  forged[64 + 4] = 9;  // axis count 9: beyond WRC_MAX_AXES
  EXPECT_NE(decode_error(wrc::test::ResealedFlatTable(forged)).find("9 axes"), std::string::npos);
  forged = bytes;
  forged[64 + 11] = static_cast<char>(0xFF);  // output count 0xFF00000B: more than the bytes
  EXPECT_NE(decode_error(wrc::test::ResealedFlatTable(forged)).find("truncated"),
            std::string::npos);
  EXPECT_NE(decode_error(wrc::test::ResealedFlatTable(bytes + "x")).find("bytes follow the status"),
            std::string::npos);
  forged = bytes;
  forged[8] = 3;  // version 3
  EXPECT_NE(decode_error(wrc::test::ResealedFlatTable(forged))
                .find("version 3, this runtime reads versions 1 to 2"),
            std::string::npos);
  // Version 1, the same without numbers, still reads; its fourth count is reserved.
  forged = bytes;
  ASSERT_EQ(forged[64 + 12], 0);  // this table has no numbers
  forged[8] = 1;
  EXPECT_EQ(decode_error(wrc::test::ResealedFlatTable(forged)), "decoded");
  forged[64 + 12] = 1;
  EXPECT_NE(decode_error(wrc::test::ResealedFlatTable(forged)).find("must be 0"),
            std::string::npos);
  forged = bytes;
  forged[64 + 12] = 1;  // a number the body does not hold: the rest no longer parses
  EXPECT_NE(decode_error(wrc::test::ResealedFlatTable(forged)), "decoded");

  // Content the checks refuse, whichever format holds it.
  wrc::format::TableContent content = ReadTableContent(files.h5.path());
  content.axes[2].values[1] = content.axes[2].values[0];
  EXPECT_NE(decode_error(EncodeFlatTable(content)).find(":/axes/yaw: values must be strictly"),
            std::string::npos);
  content = ReadTableContent(files.h5.path());
  content.status[0] = 0;
  content.values[0] = INFINITY;
  EXPECT_NE(decode_error(EncodeFlatTable(content)).find("non-finite value at node"),
            std::string::npos);
  content = ReadTableContent(files.h5.path());
  content.axes[1].values.clear();  // (a fuzzer's find: the node count divided by zero)
  EXPECT_NE(decode_error(EncodeFlatTable(content)).find(":/axes/fz: is empty"), std::string::npos);
  content = ReadTableContent(files.h5.path());
  content.outputs[1].name = content.outputs[0].name;
  EXPECT_NE(decode_error(EncodeFlatTable(content)).find("output \"out0\" twice"),
            std::string::npos);
}

TEST(RuntimeFlat, AnUnwritableTargetLeavesNothingBehind) {
  const Pair files;
  const std::filesystem::path folder = std::filesystem::path(files.flat.path()).parent_path();
  const std::string target = (folder / "no-such-folder" / "t.wrct").string();
  try {
    wrc::format::WriteFlatTable(ReadTableContent(files.h5.path()), target);
    FAIL() << "wrote into a missing folder";
  } catch (const wrc::TableError& e) {
    EXPECT_EQ(e.code(), WRC_ERR_FILE);
    EXPECT_NE(std::string(e.what()).find(target), std::string::npos) << e.what();
  }
}

}  // namespace
