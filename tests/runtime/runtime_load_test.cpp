// Loading: a valid table exposes its metadata; every kind of broken file gives a clear error
// (code and a message naming file, object and problem), a NULL handle and no crash.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "runtime/hdf5/hdf5.h"
#include "tests/runtime/table_writer.h"
#include "wrc/runtime.h"

namespace {

using wrc::test::ScratchFile;
using wrc::test::TableContent;

TableContent SmallTable() {
  TableContent content;
  content.axes = {{"y", {-2.0, -1.0, 0.0, 1.5, 2.0}, "mm"},
                  {"roll", {-0.002, 0.0, 0.002}, "rad"},
                  {"yaw", {-0.01, -0.005, 0.0, 0.01}, "rad"}};
  content.outputs = {"fy", "fx", "fz"};
  content.function = [](int k, const std::vector<double>& x) {
    return 100.0 * k + x[0] + 10.0 * x[1] + 1000.0 * x[2];
  };
  return content;
}

struct OpenResult {
  int code;
  std::string message;
};

OpenResult TryOpen(const std::string& path) {
  wrc_table* table = reinterpret_cast<wrc_table*>(0x1);  // Must be reset to NULL on failure.
  const int code = wrc_table_open(path.c_str(), &table);
  if (code == 0) {
    wrc_table_close(table);
    return {0, ""};
  }
  EXPECT_EQ(table, nullptr);
  return {code, wrc_last_error()};
}

void ExpectOpenError(const std::string& path, int code, const std::vector<std::string>& fragments) {
  const OpenResult result = TryOpen(path);
  EXPECT_EQ(result.code, code) << result.message;
  for (const std::string& fragment : fragments) {
    EXPECT_NE(result.message.find(fragment), std::string::npos)
        << "message \"" << result.message << "\" lacks \"" << fragment << "\"";
  }
}

// Writes the small valid table, then lets edit damage it.
template <typename Edit>
void WriteDamaged(const std::string& path, Edit edit) {
  wrc::test::WriteTable(path, SmallTable());
  wrc::h5::File file = wrc::h5::File::Open(path, wrc::h5::File::Mode::kReadWrite);
  edit(file);
}

TEST(RuntimeLoad, ValidTableExposesItsMetadata) {
  ScratchFile scratch("valid");
  wrc::test::WriteTable(scratch.path(), SmallTable());
  wrc_table* table = nullptr;
  ASSERT_EQ(wrc_table_open(scratch.path().c_str(), &table), 0) << wrc_last_error();
  EXPECT_EQ(wrc_table_num_axes(table), 3);
  EXPECT_EQ(wrc_table_num_outputs(table), 3);
  EXPECT_STREQ(wrc_table_axis_name(table, 0), "y");
  EXPECT_STREQ(wrc_table_axis_name(table, 2), "yaw");
  EXPECT_EQ(wrc_table_axis_size(table, 0), 5);
  EXPECT_EQ(wrc_table_axis_size(table, 2), 4);
  EXPECT_EQ(wrc_table_axis_values(table, 0)[3], 1.5);
  EXPECT_STREQ(wrc_table_axis_unit(table, 1), "rad");
  // Output order follows /outputs 'order', not the alphabet.
  EXPECT_STREQ(wrc_table_output_name(table, 0), "fy");
  EXPECT_STREQ(wrc_table_output_name(table, 1), "fx");
  EXPECT_STREQ(wrc_table_output_unit(table, 0), "N");
  EXPECT_EQ(wrc_table_output_index(table, "fz"), 2);
  EXPECT_EQ(wrc_table_axis_index(table, "roll"), 1);
  EXPECT_EQ(wrc_table_axis_index(table, "spin"), WRC_ERR_NOT_FOUND);
  EXPECT_NE(std::string(wrc_last_error()).find("no axis named 'spin'"), std::string::npos);
  EXPECT_STREQ(wrc_table_attribute(table, "format"), "wrc-table");
  EXPECT_STREQ(wrc_table_attribute(table, "wrc_version"), "0.1.0-test");
  EXPECT_EQ(wrc_table_attribute(table, "nonexistent"), nullptr);
  EXPECT_EQ(wrc_table_interpolation(table), WRC_INTERP_LINEAR);
  // Index errors are reported, not crashes.
  EXPECT_EQ(wrc_table_axis_name(table, 3), nullptr);
  EXPECT_NE(std::string(wrc_last_error()).find("axis index 3 out of range"), std::string::npos);
  EXPECT_EQ(wrc_table_axis_values(table, -1), nullptr);
  EXPECT_EQ(wrc_table_axis_size(table, 7), WRC_ERR_INVALID_ARGUMENT);
  EXPECT_EQ(wrc_table_output_name(table, 3), nullptr);
  EXPECT_EQ(wrc_table_set_interpolation(table, 7), WRC_ERR_INVALID_ARGUMENT);
  wrc_table_close(table);
}

TEST(RuntimeLoad, OutputsWithoutOrderAttributeKeepCreationOrder) {
  ScratchFile scratch("creation-order");
  TableContent content = SmallTable();
  content.write_output_order = false;
  wrc::test::WriteTable(scratch.path(), content);
  wrc_table* table = nullptr;
  ASSERT_EQ(wrc_table_open(scratch.path().c_str(), &table), 0) << wrc_last_error();
  EXPECT_STREQ(wrc_table_output_name(table, 0), "fy");
  EXPECT_STREQ(wrc_table_output_name(table, 1), "fx");
  EXPECT_STREQ(wrc_table_output_name(table, 2), "fz");
  wrc_table_close(table);
}

TEST(RuntimeLoad, FixedLengthStringAttributesAreAccepted) {
  // As NumPy byte strings written by h5py would store them.
  ScratchFile scratch("fixed-strings");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    file.WriteStringAttribute("format", "wrc-table", wrc::h5::StringStorage::kFixed);
    file.OpenGroup("axes").WriteStringArrayAttribute("order", {"y", "roll", "yaw"},
                                                     wrc::h5::StringStorage::kFixed);
    file.WriteStringArrayAttribute("not_scalar", {"a", "b"});  // Skipped by wrc_table_attribute.
  });
  wrc_table* table = nullptr;
  ASSERT_EQ(wrc_table_open(scratch.path().c_str(), &table), 0) << wrc_last_error();
  EXPECT_STREQ(wrc_table_axis_name(table, 1), "roll");
  EXPECT_EQ(wrc_table_attribute(table, "not_scalar"), nullptr);
  wrc_table_close(table);
}

TEST(RuntimeLoad, NullArgumentsAreErrors) {
  wrc_table* table = nullptr;
  EXPECT_EQ(wrc_table_open(nullptr, &table), WRC_ERR_NULL_POINTER);
  EXPECT_EQ(wrc_table_open("x.h5", nullptr), WRC_ERR_NULL_POINTER);
  EXPECT_EQ(wrc_table_num_axes(nullptr), WRC_ERR_NULL_POINTER);
  EXPECT_EQ(wrc_table_num_outputs(nullptr), WRC_ERR_NULL_POINTER);
  EXPECT_EQ(wrc_table_axis_name(nullptr, 0), nullptr);
  EXPECT_EQ(wrc_table_axis_size(nullptr, 0), WRC_ERR_NULL_POINTER);
  EXPECT_EQ(wrc_table_axis_values(nullptr, 0), nullptr);
  EXPECT_EQ(wrc_table_output_name(nullptr, 0), nullptr);
  EXPECT_EQ(wrc_table_set_interpolation(nullptr, WRC_INTERP_CUBIC), WRC_ERR_NULL_POINTER);
  double point[1] = {0.0};
  double out[1];
  EXPECT_EQ(wrc_table_eval(nullptr, point, out), WRC_ERR_NULL_POINTER);
  EXPECT_NE(std::string(wrc_last_error()).find("handle is NULL"), std::string::npos);
  wrc_table_close(nullptr);  // Allowed, like free(NULL).
}

TEST(RuntimeLoad, MissingFile) {
  ScratchFile scratch("never-written");
  ExpectOpenError(scratch.path(), WRC_ERR_FILE, {scratch.path(), "no such file"});
}

TEST(RuntimeLoad, NotAnHdf5File) {
  ScratchFile scratch("text");
  std::ofstream(scratch.path()) << "this is not HDF5\n";
  ExpectOpenError(scratch.path(), WRC_ERR_FILE, {scratch.path(), "not a wrc table"});
}

TEST(RuntimeLoad, WrongFormatAttribute) {
  ScratchFile scratch("format");
  WriteDamaged(scratch.path(),
               [](wrc::h5::File& file) { file.WriteStringAttribute("format", "wrc-tabel"); });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT,
                  {scratch.path() + ":/", "'format'", "\"wrc-tabel\"", "expected \"wrc-table\""});
}

TEST(RuntimeLoad, MissingFormatAttribute) {
  ScratchFile scratch("no-format");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) { file.RemoveAttribute("format"); });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT, {scratch.path(), "'format' is missing"});
}

TEST(RuntimeLoad, WrongFormatVersion) {
  ScratchFile scratch("version");
  WriteDamaged(scratch.path(),
               [](wrc::h5::File& file) { file.WriteIntAttribute("format_version", 2); });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT,
                  {scratch.path(), "'format_version' is 2", "reads version 1"});
}

TEST(RuntimeLoad, FormatVersionOfTheWrongType) {
  ScratchFile scratch("version-type");
  WriteDamaged(scratch.path(),
               [](wrc::h5::File& file) { file.WriteStringAttribute("format_version", "1"); });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT,
                  {scratch.path(), "'format_version'", "expected an integer, found string"});
}

TEST(RuntimeLoad, OutputShapeDoesNotMatchAxes) {
  ScratchFile scratch("shape");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    wrc::h5::Group outputs = file.OpenGroup("outputs");
    outputs.Remove("fx");
    outputs.WriteDataset("fx", {5, 3}, std::vector<double>(15, 0.0));
  });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT,
                  {scratch.path() + ":/outputs/fx", "shape [5,3]", "[5,3,4]"});
}

TEST(RuntimeLoad, OutputShapeWithAxesSwapped) {
  ScratchFile scratch("swapped");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    wrc::h5::Group outputs = file.OpenGroup("outputs");
    outputs.Remove("fz");
    outputs.WriteDataset("fz", {5, 4, 3}, std::vector<double>(60, 0.0));
  });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT, {"/outputs/fz", "shape [5,4,3]", "[5,3,4]"});
}

TEST(RuntimeLoad, StatusShapeDoesNotMatchAxes) {
  ScratchFile scratch("status-shape");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    file.Remove("status");
    file.WriteDataset("status", {5, 3, 5}, std::vector<std::int8_t>(75, 0));
  });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT, {scratch.path() + ":/status", "shape [5,3,5]"});
}

TEST(RuntimeLoad, AxisNotAscending) {
  ScratchFile scratch("ascending");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    wrc::h5::Group axes = file.OpenGroup("axes");
    axes.Remove("yaw");
    axes.WriteDataset<double>("yaw", {4}, {-0.01, 0.0, 0.0, 0.01});
  });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT,
                  {scratch.path() + ":/axes/yaw", "strictly ascending", "value 2"});
}

TEST(RuntimeLoad, AxisDescending) {
  ScratchFile scratch("descending");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    wrc::h5::Group axes = file.OpenGroup("axes");
    axes.Remove("y");
    axes.WriteDataset<double>("y", {5}, {2.0, 1.5, 0.0, -1.0, -2.0});
  });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT, {"/axes/y", "strictly ascending", "value 1"});
}

// Axes whose span overflows, whose steps are subnormal or too small for their magnitude
// would make the cell search or the interpolation weights infinite: refused, not evaluated.
TEST(RuntimeLoad, AxisValuesBeyondTheLimitsAreRefused) {
  const std::vector<std::pair<std::vector<double>, std::string>> cases = {
      {{-1e308, 0.0, 1e308}, "beyond"},     {{-1.0, 0.0, 1e31}, "beyond"},
      {{0.0, 1e-310, 2e-310}, "too close"}, {{0.0, 1e-300, 2e-300}, "too close"},
      {{0.0, 5e-324}, "too close"},         {{1.0, 1.0 + 1e-12, 2.0}, "too close"},
  };
  for (const auto& [values, fragment] : cases) {
    ScratchFile scratch("limits");
    WriteDamaged(scratch.path(), [&values = values](wrc::h5::File& file) {
      wrc::h5::Group axes = file.OpenGroup("axes");
      axes.Remove("roll");
      axes.WriteDataset<double>("roll", {values.size()}, values);
    });
    ExpectOpenError(scratch.path(), WRC_ERR_FORMAT, {":/axes/roll", fragment});
  }
}

TEST(RuntimeLoad, AxesWhoseNodeCountOverflowsAreRefused) {
  ScratchFile scratch("overflow");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    wrc::h5::Group axes = file.OpenGroup("axes");
    const std::vector<double> values = wrc::test::Linspace(0.0, 65535.0, 65536);
    std::vector<std::string> order;
    for (const std::string name : {"a", "b", "c", "d"}) {
      axes.WriteDataset<double>(name, {values.size()}, values);
      order.push_back(name);
    }
    axes.RemoveAttribute("order");
    axes.WriteStringArrayAttribute("order", order);
  });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT, {":/axes", "more than 4294967296 nodes"});
}

// Axes of equal length listed in another order would pass every shape check and transpose the
// data; the grid datasets' 'dimensions' catch it. Without the attribute the order is trusted.
TEST(RuntimeLoad, AxisOrderThatContradictsTheDimensionsIsRefused) {
  TableContent content = SmallTable();
  content.axes = {{"y", {-1.0, 0.0, 1.0}, "mm"}, {"roll", {-0.002, 0.0, 0.002}, "rad"}};
  ScratchFile scratch("transposed");
  wrc::test::WriteTable(scratch.path(), content);
  {
    wrc::h5::File file = wrc::h5::File::Open(scratch.path(), wrc::h5::File::Mode::kReadWrite);
    file.OpenGroup("axes").WriteStringArrayAttribute("order", {"roll", "y"});
  }
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT,
                  {":/outputs/fy", "dimensions are (y, roll)", "lists (roll, y)"});

  content.write_dimensions = false;
  ScratchFile older("older");
  wrc::test::WriteTable(older.path(), content);
  EXPECT_EQ(TryOpen(older.path()).code, 0);
}

TEST(RuntimeLoad, AxisListedInOrderButAbsent) {
  ScratchFile scratch("absent-axis");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    file.OpenGroup("axes").WriteStringArrayAttribute("order", {"y", "roll", "spin"});
  });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT, {"/axes/spin", "no such dataset"});
}

TEST(RuntimeLoad, AxisOrderAttributeMissing) {
  ScratchFile scratch("no-order");
  WriteDamaged(scratch.path(),
               [](wrc::h5::File& file) { file.OpenGroup("axes").RemoveAttribute("order"); });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT,
                  {scratch.path() + ":/axes", "'order' is missing"});
}

TEST(RuntimeLoad, OutputsGroupMissing) {
  ScratchFile scratch("no-outputs");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) { file.Remove("outputs"); });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT, {"/outputs", "group is missing"});
}

TEST(RuntimeLoad, NonFiniteValueAtAnOkNode) {
  ScratchFile scratch("nan-ok");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    std::vector<double> values(60, 1.0);
    // Node 7 of shape [5, 3, 4] is (0, 1, 3): y = -2, roll = 0, yaw = 0.01.
    values[7] = std::numeric_limits<double>::quiet_NaN();
    wrc::h5::Group outputs = file.OpenGroup("outputs");
    outputs.Remove("fz");
    outputs.WriteDataset("fz", {5, 3, 4}, values);
  });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT,
                  {"/outputs/fz", "non-finite value", "(y=-2, roll=0, yaw=0.01)", "status"});
}

TEST(RuntimeLoad, OutputOfTheWrongType) {
  ScratchFile scratch("int-output");
  WriteDamaged(scratch.path(), [](wrc::h5::File& file) {
    wrc::h5::Group outputs = file.OpenGroup("outputs");
    outputs.Remove("fy");
    outputs.WriteDataset("fy", {5, 3, 4}, std::vector<std::int32_t>(60, 0));
  });
  ExpectOpenError(scratch.path(), WRC_ERR_FORMAT, {"/outputs/fy", "floating point", "int32"});
}

}  // namespace
