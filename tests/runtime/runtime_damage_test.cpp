// Damaged table files: a changed datatype message, a changed filter parameter and every single
// changed byte of a small table give an error code and a message, or the very same numbers as
// the intact file; never a crash or a different number.

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/seal.h"
#include "tests/runtime/table_writer.h"
#include "wrc/runtime.h"

namespace {

using wrc::h5::FileFormat;
using wrc::test::ScratchFile;
using wrc::test::TableContent;

TableContent SmallTable(FileFormat format) {
  TableContent content;
  content.axes = {{"y", {-2.0, -1.0, 0.0, 1.5, 2.0}, "mm"}, {"roll", {-0.002, 0.0, 0.002}, "rad"}};
  content.outputs = {"fy", "fx"};
  content.function = [](int k, const std::vector<double>& x) {
    return 100.0 * k + x[0] + 10.0 * x[1];
  };
  content.format = format;
  content.axis_storage = wrc::h5::CompressedChecked();
  return content;
}

std::vector<char> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), {});
}

void WriteBytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// HDF5's encoding of an IEEE float64 little-endian datatype message: version 1, class float,
// bit field, size 8, offset 0, precision 64, exponent at 52 of 11 bits, mantissa at 0 of 52
// bits, bias 1023.
const std::vector<char> kFloat64Message = {0x11, 0x20, 0x3f,       0x00, 0x08, 0x00, 0x00,
                                           0x00, 0x00, 0x00,       0x40, 0x00, 0x34, 0x0b,
                                           0x00, 0x34, char(0xff), 0x03, 0x00, 0x00};

// Values of every output at a few points inside the table, or the open/eval error code.
struct Evaluation {
  int code = 0;
  std::vector<double> values;
};

Evaluation Evaluate(const std::string& path) {
  Evaluation result;
  wrc_table* table = nullptr;
  result.code = wrc_table_open(path.c_str(), &table);
  if (result.code != 0) return result;
  for (const double y : {-1.7, 0.3, 1.9}) {
    for (const double roll : {-0.0015, 0.001}) {
      const double point[2] = {y, roll};
      double out[2] = {0.0, 0.0};
      const int flags = wrc_table_eval(table, point, out);
      if (flags < 0) {
        result.code = flags;
        break;
      }
      result.values.insert(result.values.end(), {out[0], out[1]});
    }
  }
  wrc_table_close(table);
  return result;
}

// Patches the size field of every float64 datatype message (8 -> 65544 bytes, one byte).
int PatchFloatSizes(std::vector<char>* bytes) {
  int patched = 0;
  for (auto it = bytes->begin(); (it = std::search(it, bytes->end(), kFloat64Message.begin(),
                                                   kFloat64Message.end())) != bytes->end();
       ++it) {
    *(it + 6) = 0x01;
    ++patched;
  }
  return patched;
}

// Damaged earliest-format files found by fuzzing that crashed inside HDF5 1.10: iterating the
// root's attribute messages read freed memory (SIGSEGV without sanitizers), a header size asked
// HDF5 for 2 PB, and a damaged compact axis made HDF5 read past its buffer (the garbage is then
// refused by the axis checks). All are errors (tests/runtime/damaged/).
TEST(RuntimeDamage, FilesThatCrashedHdf5AreErrors) {
  const std::string dir = std::string(WRC_SOURCE_DIR) + "/tests/runtime/damaged/";
  for (const char* name :
       {"hdf5_attribute_iteration.h5", "hdf5_huge_allocation.h5", "hdf5_compact_overread.h5"}) {
    ASSERT_TRUE(std::ifstream(dir + name).good()) << dir + name << " is missing";
    wrc_table* table = nullptr;
    const int code = wrc_table_open((dir + name).c_str(), &table);
    EXPECT_TRUE(code == WRC_ERR_FILE || code == WRC_ERR_FORMAT) << name << ": " << code;
    EXPECT_EQ(table, nullptr);
    EXPECT_NE(std::string(wrc_last_error()).find(name), std::string::npos) << wrc_last_error();
    EXPECT_EQ(std::string(wrc_last_error()).find("no such file"), std::string::npos)
        << wrc_last_error();
  }
}

// A table in HDF5's earliest format (no metadata checksums) never reaches HDF5 in the runtime:
// refused, naming the command that converts it. An unsealed table in the checksummed format
// loads, with a warning naming the same command; a sealed one has none.
TEST(RuntimeDamage, EarliestFormatIsRefusedAndUnsealedLoadsWithAWarning) {
  ScratchFile earliest("earliest");
  wrc::test::WriteTable(earliest.path(), SmallTable(FileFormat::kEarliest));
  wrc_table* table = nullptr;
  EXPECT_EQ(wrc_table_open(earliest.path().c_str(), &table), WRC_ERR_FORMAT);
  EXPECT_NE(std::string(wrc_last_error()).find("wrc upgrade " + earliest.path()), std::string::npos)
      << wrc_last_error();

  ScratchFile unsealed("unsealed");
  wrc::test::WriteTable(unsealed.path(), SmallTable(FileFormat::kChecksummed));
  ASSERT_EQ(wrc_table_open(unsealed.path().c_str(), &table), 0) << wrc_last_error();
  ASSERT_NE(wrc_table_warning(table), nullptr);
  EXPECT_NE(std::string(wrc_table_warning(table)).find("wrc upgrade"), std::string::npos);
  wrc_table_close(table);

  ScratchFile sealed("sealed");
  TableContent content = SmallTable(FileFormat::kChecksummed);
  content.sealed = true;
  wrc::test::WriteTable(sealed.path(), content);
  ASSERT_EQ(wrc_table_open(sealed.path().c_str(), &table), 0) << wrc_last_error();
  EXPECT_EQ(wrc_table_warning(table), nullptr);
  wrc_table_close(table);
}

TEST(RuntimeDamage, FloatOfAbsurdSizeIsAnErrorInTheChecksummedFormat) {
  ScratchFile scratch("float-size-v110");
  wrc::test::WriteTable(scratch.path(), SmallTable(FileFormat::kChecksummed));
  std::vector<char> bytes = ReadBytes(scratch.path());
  ASSERT_GT(PatchFloatSizes(&bytes), 0);
  WriteBytes(scratch.path(), bytes);
  EXPECT_LT(Evaluate(scratch.path()).code, 0);
}

// Every byte of a checksummed table, one at a time: an error, or exactly the intact numbers.
TEST(RuntimeDamage, NoSingleChangedByteGivesADifferentNumber) {
  ScratchFile intact("intact");
  wrc::test::WriteTable(intact.path(), SmallTable(FileFormat::kChecksummed));
  const Evaluation expected = Evaluate(intact.path());
  ASSERT_EQ(expected.code, 0) << wrc_last_error();
  const std::vector<char> bytes = ReadBytes(intact.path());
  ScratchFile scratch("flipped");
  int refused = 0;
  for (std::size_t offset = 0; offset < bytes.size(); ++offset) {
    std::vector<char> damaged = bytes;
    damaged[offset] = static_cast<char>(damaged[offset] ^ 0x5a);
    WriteBytes(scratch.path(), damaged);
    const Evaluation result = Evaluate(scratch.path());
    if (result.code != 0) {
      ++refused;
      continue;
    }
    ASSERT_EQ(result.values, expected.values) << "byte " << offset << " changed the numbers";
  }
  EXPECT_GT(refused, 0);
}

// A sealed table proves itself before HDF5 reads it: every single changed byte, in the seal, its
// padding or the HDF5 file after it, is WRC_ERR_FORMAT, and so is a truncated or extended file.
TEST(RuntimeDamage, EveryChangedByteOfASealedTableIsRefusedBeforeHdf5) {
  ScratchFile intact("sealed");
  TableContent content = SmallTable(FileFormat::kChecksummed);
  content.sealed = true;
  wrc::test::WriteTable(intact.path(), content);
  const Evaluation expected = Evaluate(intact.path());
  ASSERT_EQ(expected.code, 0) << wrc_last_error();
  const std::vector<char> bytes = ReadBytes(intact.path());
  ASSERT_GT(bytes.size(), wrc::h5::kUserBlockSize);
  ScratchFile scratch("sealed_flipped");
  std::size_t refused = 0;
  for (std::size_t offset = 0; offset < bytes.size(); ++offset) {
    std::vector<char> damaged = bytes;
    damaged[offset] = static_cast<char>(damaged[offset] ^ 0x5a);
    WriteBytes(scratch.path(), damaged);
    const Evaluation result = Evaluate(scratch.path());
    EXPECT_EQ(result.code, WRC_ERR_FORMAT) << "byte " << offset;
    refused += result.code == WRC_ERR_FORMAT ? 1 : 0;
  }
  EXPECT_EQ(refused, bytes.size());
  std::vector<char> shorter(bytes.begin(), bytes.end() - 1), longer = bytes;
  longer.push_back('\0');
  for (const auto& changed : {shorter, longer}) {
    WriteBytes(scratch.path(), changed);
    EXPECT_EQ(Evaluate(scratch.path()).code, WRC_ERR_FORMAT) << changed.size() << " bytes";
    EXPECT_NE(std::string(wrc_last_error()).find("damaged"), std::string::npos) << wrc_last_error();
  }
}

// A sealed table edited through HDF5 and sealed again reads as the edit left it; edited and not
// sealed again, it is refused.
TEST(RuntimeDamage, ASealedTableEditedMustBeSealedAgain) {
  ScratchFile scratch("resealed");
  TableContent content = SmallTable(FileFormat::kChecksummed);
  content.sealed = true;
  wrc::test::WriteTable(scratch.path(), content);
  {
    wrc::h5::File file = wrc::h5::File::Open(scratch.path(), wrc::h5::File::Mode::kReadWrite);
    EXPECT_TRUE(file.Sealed());
    file.WriteStringAttribute("note", "edited");
  }
  EXPECT_EQ(Evaluate(scratch.path()).code, WRC_ERR_FORMAT);
  wrc::h5::SealFile(scratch.path());
  const Evaluation result = Evaluate(scratch.path());
  ASSERT_EQ(result.code, 0) << wrc_last_error();
  EXPECT_EQ(result.values.size(), 12u);
}

}  // namespace

// Replaces /outputs/fy of a small table with what `make` creates there (through HDF5 itself, as
// a hostile writer would), and returns the runtime's open: code and message.
template <typename Make>
std::pair<int, std::string> OpenWithReplacedOutput(const std::string& stem, Make make) {
  ScratchFile scratch(stem);
  wrc::test::WriteTable(scratch.path(), SmallTable(FileFormat::kChecksummed));
  {
    const hid_t file = H5Fopen(scratch.path().c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t outputs = H5Gopen2(file, "outputs", H5P_DEFAULT);
    EXPECT_GE(H5Lmove(outputs, "fy", file, "fy_moved", H5P_DEFAULT, H5P_DEFAULT), 0);
    make(file, outputs);
    H5Gclose(outputs);
    H5Fclose(file);
  }
  wrc_table* table = nullptr;
  const int code = wrc_table_open(scratch.path().c_str(), &table);
  wrc_table_close(table);
  return {code, wrc_last_error()};
}

// A dataset of the table's grid shape (5 × 3 float64) made with the creation list `dcpl`.
void CreateGridDataset(hid_t group, hid_t dcpl) {
  const hsize_t dims[2] = {5, 3};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t dataset =
      H5Dcreate2(group, "fy", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  EXPECT_GE(dataset, 0);
  H5Dclose(dataset);
  H5Sclose(space);
}

// Values that live anywhere but in the file (a link elsewhere, raw data in another file or a
// device, a virtual mapping onto a missing source) or in a storage the writer never uses are
// refused by name, never read as zeros or as whatever the target holds.
TEST(RuntimeDamage, ValuesNotStoredInTheFileAreRefused) {
  struct Case {
    const char* name;
    std::function<void(hid_t, hid_t)> make;
    const char* problem;
  };
  const std::vector<Case> cases = {
      {"soft link",
       [](hid_t, hid_t outputs) {
         H5Lcreate_soft("/fy_moved", outputs, "fy", H5P_DEFAULT, H5P_DEFAULT);
       },
       "soft or external link"},
      {"external link",
       [](hid_t, hid_t outputs) {
         H5Lcreate_external("/dev/zero", "/fy", outputs, "fy", H5P_DEFAULT, H5P_DEFAULT);
       },
       "soft or external link"},
      {"external storage",
       [](hid_t, hid_t outputs) {
         const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
         H5Pset_external(dcpl, "/dev/zero", 0, 15 * 8);
         CreateGridDataset(outputs, dcpl);
         H5Pclose(dcpl);
       },
       "external storage"},
      {"virtual dataset",
       [](hid_t, hid_t outputs) {
         const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
         const hsize_t dims[2] = {5, 3};
         const hid_t space = H5Screate_simple(2, dims, nullptr);
         H5Pset_virtual(dcpl, space, "missing.h5", "/fy", space);
         CreateGridDataset(outputs, dcpl);
         H5Sclose(space);
         H5Pclose(dcpl);
       },
       "virtual dataset"},
      {"compact storage",
       [](hid_t, hid_t outputs) {
         const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
         H5Pset_layout(dcpl, H5D_COMPACT);
         CreateGridDataset(outputs, dcpl);
         H5Pclose(dcpl);
       },
       "other than contiguous or chunked"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const auto [code, message] = OpenWithReplacedOutput("stored", c.make);
    EXPECT_EQ(code, WRC_ERR_FORMAT) << message;
    EXPECT_NE(message.find(c.problem), std::string::npos) << message;
    EXPECT_NE(message.find("/outputs/fy"), std::string::npos) << message;
  }
}

// Finite but beyond what a cubic lookup can difference: refused, not NaN with flags 0.
TEST(RuntimeDamage, ValuesBeyondTheInterpolationsRangeAreRefused) {
  for (const double huge : {1e308, -2e30}) {
    ScratchFile scratch("huge");
    TableContent content = SmallTable(FileFormat::kChecksummed);
    content.function = [huge](int k, const std::vector<double>& x) {
      return x[0] == 0.0 && x[1] == 0.0 && k == 1 ? huge : x[0];
    };
    wrc::test::WriteTable(scratch.path(), content);
    wrc_table* table = nullptr;
    EXPECT_EQ(wrc_table_open(scratch.path().c_str(), &table), WRC_ERR_FORMAT);
    EXPECT_NE(std::string(wrc_last_error()).find("is beyond"), std::string::npos)
        << wrc_last_error();
  }
}
