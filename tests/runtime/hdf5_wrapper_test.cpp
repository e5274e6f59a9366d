// Round trips through the wrc::h5 wrapper: what is written reads back identically, storage
// options are applied, and failures throw wrc::h5::Error naming file and object.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "runtime/hdf5/hdf5.h"
#include "tests/runtime/table_writer.h"

namespace wrc::h5 {
namespace {

using test::ScratchFile;

// Expects that statement throws h5::Error whose message contains every given fragment.
template <typename Statement>
void ExpectError(Statement statement, const std::vector<std::string>& fragments) {
  try {
    statement();
    ADD_FAILURE() << "no h5::Error thrown";
  } catch (const Error& error) {
    const std::string message = error.what();
    for (const std::string& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "message \"" << message << "\" lacks \"" << fragment << "\"";
    }
  }
}

TEST(Hdf5Wrapper, NumericDatasetsRoundTripExactly) {
  ScratchFile scratch("numeric");
  const std::vector<double> doubles = {
      0.0, -1.5, 1e-300, 1e300, std::numeric_limits<double>::quiet_NaN(), 3.141592653589793};
  const std::vector<float> floats = {0.25f, -7.0f, 1e30f};
  const std::vector<std::int8_t> int8s = {-128, -1, 0, 3, 127};
  const std::vector<std::uint8_t> uint8s = {0, 1, 200, 255};
  const std::vector<std::int32_t> int32s = {-2147483647 - 1, 0, 2147483647};
  const std::vector<std::int64_t> int64s = {std::numeric_limits<std::int64_t>::min(), 42};
  {
    File file = File::Create(scratch.path());
    Group group = file.CreateGroup("data");
    group.WriteDataset("doubles", {2, 3}, doubles);
    group.WriteDataset("floats", {3}, floats, CompressedChecked());
    group.WriteDataset("int8s", {5}, int8s, CompressedChecked());
    group.WriteDataset("uint8s", {4}, uint8s);
    group.WriteDataset("int32s", {3}, int32s);
    group.WriteDataset("int64s", {2}, int64s);
  }
  const File file = File::Open(scratch.path());
  const Group group = file.OpenGroup("data");
  const Dataset dataset = group.OpenDataset("doubles");
  EXPECT_EQ(dataset.Shape(), (std::vector<Size>{2, 3}));
  EXPECT_EQ(dataset.Type().Describe(), "float64");
  const std::vector<double> read = dataset.Read<double>();
  ASSERT_EQ(read.size(), doubles.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    if (std::isnan(doubles[i])) {
      EXPECT_TRUE(std::isnan(read[i]));
    } else {
      EXPECT_EQ(read[i], doubles[i]);  // Bit-exact: no conversion on the way.
    }
  }
  EXPECT_EQ(group.OpenDataset("floats").Read<float>(), floats);
  EXPECT_EQ(group.OpenDataset("int8s").Type().Describe(), "int8");
  EXPECT_EQ(group.OpenDataset("int8s").Read<std::int8_t>(), int8s);
  EXPECT_EQ(group.OpenDataset("uint8s").Type().Describe(), "uint8");
  EXPECT_EQ(group.OpenDataset("uint8s").Read<std::uint8_t>(), uint8s);
  EXPECT_EQ(group.OpenDataset("int32s").Read<std::int32_t>(), int32s);
  EXPECT_EQ(group.OpenDataset("int64s").Read<std::int64_t>(), int64s);
  // Widening conversions are allowed: float32 data read as float64 exactly.
  const std::vector<double> widened = group.OpenDataset("floats").Read<double>();
  for (std::size_t i = 0; i < floats.size(); ++i) EXPECT_EQ(widened[i], double{floats[i]});
}

TEST(Hdf5Wrapper, StorageOptionsAreApplied) {
  ScratchFile scratch("options");
  std::vector<double> values(41 * 5 * 5 * 9);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.5 * static_cast<double>(i);
  {
    File file = File::Create(scratch.path());
    DatasetOptions options = CompressedChecked();
    options.chunk = {41, 5, 5, 3};
    file.WriteDataset("explicit", {41, 5, 5, 9}, values, options);
    file.WriteDataset("automatic", {41, 5, 5, 9}, values, CompressedChecked());
    file.WriteDataset("plain", {41, 5, 5, 9}, values);
  }
  const File file = File::Open(scratch.path());
  const Dataset explicit_chunks = file.OpenDataset("explicit");
  EXPECT_EQ(explicit_chunks.ChunkShape(), (std::vector<Size>{41, 5, 5, 3}));
  EXPECT_TRUE(explicit_chunks.HasDeflate());
  EXPECT_TRUE(explicit_chunks.HasFletcher32());
  EXPECT_EQ(explicit_chunks.Read<double>(), values);
  const Dataset automatic = file.OpenDataset("automatic");
  // 73 800 bytes fit one automatic chunk (limit 1 MiB): the whole shape.
  EXPECT_EQ(automatic.ChunkShape(), (std::vector<Size>{41, 5, 5, 9}));
  EXPECT_TRUE(automatic.HasFletcher32());
  EXPECT_EQ(automatic.Read<double>(), values);
  const Dataset plain = file.OpenDataset("plain");
  EXPECT_TRUE(plain.ChunkShape().empty());
  EXPECT_FALSE(plain.HasDeflate());
  EXPECT_FALSE(plain.HasFletcher32());
}

TEST(Hdf5Wrapper, AutomaticChunksStayBelowOneMebibyte) {
  ScratchFile scratch("big");
  File file = File::Create(scratch.path());
  const Dataset dataset = file.CreateDataset<double>("big", {1000, 400}, CompressedChecked());
  const std::vector<Size> chunk = dataset.ChunkShape();
  ASSERT_EQ(chunk.size(), 2u);
  EXPECT_LE(chunk[0] * chunk[1] * 8, Size{1} << 20);
  EXPECT_GE(chunk[0] * chunk[1] * 8, Size{1} << 19);  // Halving overshoots by at most 2×.
}

TEST(Hdf5Wrapper, AttributesRoundTrip) {
  ScratchFile scratch("attributes");
  const std::string long_text(200000, 'x');  // Beyond the 64 KiB limit of compact attributes.
  const std::string utf8 = "μ = 0.3, ν = 0.28 — N/mm²";
  const std::vector<std::string> order = {"y", "roll", "yaw", "spin"};
  {
    File file = File::Create(scratch.path());
    file.WriteStringAttribute("format", "wrc-table");
    file.WriteIntAttribute("format_version", 1);
    file.WriteDoubleAttribute("scale", 0.125);
    file.WriteStringAttribute("scene", long_text);
    file.WriteStringAttribute("utf8", utf8);
    file.WriteStringAttribute("empty", "");
    Group axes = file.CreateGroup("axes");
    axes.WriteStringArrayAttribute("order", order);
    axes.WriteStringAttribute("replaced", "first");
    axes.WriteStringAttribute("replaced", "second");
    axes.WriteIntAttribute("temporary", 5);
    axes.RemoveAttribute("temporary");
  }
  const File file = File::Open(scratch.path());
  EXPECT_EQ(file.ReadStringAttribute("format"), "wrc-table");
  EXPECT_EQ(file.ReadIntAttribute("format_version"), 1);
  EXPECT_EQ(file.ReadDoubleAttribute("format_version"), 1.0);
  EXPECT_EQ(file.ReadDoubleAttribute("scale"), 0.125);
  EXPECT_EQ(file.ReadStringAttribute("scene"), long_text);
  EXPECT_EQ(file.ReadStringAttribute("utf8"), utf8);
  EXPECT_EQ(file.ReadStringAttribute("empty"), "");
  EXPECT_EQ(file.AttributeNames(), (std::vector<std::string>{"empty", "format", "format_version",
                                                             "scale", "scene", "utf8"}));
  const Group axes = file.OpenGroup("axes");
  EXPECT_EQ(axes.ReadStringArrayAttribute("order"), order);
  EXPECT_EQ(axes.ReadStringAttribute("replaced"), "second");
  EXPECT_FALSE(axes.HasAttribute("temporary"));
  // A scalar string also reads as a one-element array.
  EXPECT_EQ(file.ReadStringArrayAttribute("format"), std::vector<std::string>{"wrc-table"});
}

TEST(Hdf5Wrapper, FixedLengthStringsRoundTrip) {
  // Tables touched by NumPy/h5py tools may hold fixed-length strings; the reader takes both.
  ScratchFile scratch("fixed");
  const std::vector<std::string> order = {"y", "roll", "spin"};
  {
    File file = File::Create(scratch.path());
    file.WriteStringAttribute("format", "wrc-table", StringStorage::kFixed);
    file.WriteStringAttribute("empty", "", StringStorage::kFixed);
    file.WriteStringArrayAttribute("order", order, StringStorage::kFixed);
  }
  const File file = File::Open(scratch.path());
  EXPECT_EQ(file.OpenAttribute("format").Type().ElementSize(), 9u);  // Fixed: 9 bytes.
  EXPECT_EQ(file.ReadStringAttribute("format"), "wrc-table");
  EXPECT_EQ(file.ReadStringAttribute("empty"), "");
  // Padded to 4 bytes ("roll"), the padding is not part of the values.
  EXPECT_EQ(file.ReadStringArrayAttribute("order"), order);
}

TEST(Hdf5Wrapper, MembersKeepCreationOrder) {
  ScratchFile scratch("members");
  {
    File file = File::Create(scratch.path());
    Group outputs = file.CreateGroup("outputs");
    for (const char* name : {"fz", "fx", "my", "contact_y"}) {
      outputs.WriteDataset<double>(name, {1}, {0.0});
    }
    file.CreateGroup("zeta");
    file.CreateGroup("alpha");
  }
  const File file = File::Open(scratch.path());
  EXPECT_EQ(file.OpenGroup("outputs").MemberNames(),
            (std::vector<std::string>{"fz", "fx", "my", "contact_y"}));
  EXPECT_EQ(file.MemberNames(), (std::vector<std::string>{"outputs", "zeta", "alpha"}));
  EXPECT_EQ(file.Kind("outputs"), LinkKind::kGroup);
  EXPECT_EQ(file.OpenGroup("outputs").Kind("fx"), LinkKind::kDataset);
  EXPECT_EQ(file.Kind("nothing"), LinkKind::kMissing);
  EXPECT_EQ(file.OpenGroup("outputs").OpenDataset("fx").Path(), "/outputs/fx");
}

TEST(Hdf5Wrapper, BlocksWriteAndReadHyperslabs) {
  ScratchFile scratch("blocks");
  File file = File::Create(scratch.path());
  Dataset dataset = file.CreateDataset<double>("grid", {4, 3}, CompressedChecked());
  dataset.Write(std::vector<double>(12, -1.0));
  const std::vector<double> block = {1.0, 2.0, 3.0, 4.0};
  dataset.WriteBlock<double>({1, 1}, {2, 2}, block.data());
  const std::vector<double> all = dataset.Read<double>();
  EXPECT_EQ(all, (std::vector<double>{-1, -1, -1, -1, 1, 2, -1, 3, 4, -1, -1, -1}));
  std::vector<double> row(3);
  dataset.ReadBlock<double>({2, 0}, {1, 3}, row.data());
  EXPECT_EQ(row, (std::vector<double>{-1, 3, 4}));
  file.Remove("grid");
  EXPECT_FALSE(file.Exists("grid"));
}

TEST(Hdf5Wrapper, FailuresNameFileObjectAndProblem) {
  ScratchFile scratch("errors");
  {
    File file = File::Create(scratch.path());
    file.WriteStringAttribute("format", "wrc-table");
    file.WriteDataset<double>("values", {3}, {1.0, 2.0, 300.0});
    file.WriteDataset<double>("fractions", {2}, {0.5, 1.0});
  }
  const std::string missing = scratch.path() + ".missing";
  ExpectError([&] { File::Open(missing); }, {missing, "cannot open"});
  ExpectError([&] { File::Create(scratch.path(), /*overwrite=*/false); },
              {scratch.path(), "cannot create"});
  File file = File::Open(scratch.path(), File::Mode::kReadWrite);
  ExpectError([&] { file.OpenDataset("absent"); }, {scratch.path() + ":/absent", "missing"});
  ExpectError([&] { file.OpenGroup("values"); }, {"/values", "not a group"});
  ExpectError([&] { file.ReadIntAttribute("format"); },
              {"attribute 'format'", "expected an integer, found string"});
  ExpectError([&] { file.ReadStringAttribute("absent"); }, {"attribute 'absent'", "missing"});
  const Dataset values = file.OpenDataset("values");
  // 300 does not fit int8: HDF5 would clamp to 127, the wrapper refuses.
  ExpectError([&] { values.Read<std::int8_t>(); }, {"/values", "does not fit"});
  // 0.5 is not an integer: truncation is refused as well.
  ExpectError([&] { file.OpenDataset("fractions").Read<std::int32_t>(); }, {"/fractions"});
  Dataset writable = file.OpenDataset("values");
  ExpectError([&] { writable.Write(std::vector<double>{1.0}); }, {"/values", "writing 1 values"});
  ExpectError([&] { writable.WriteBlock<double>({2}, {2}, nullptr); }, {"/values", "exceeds"});
  ExpectError([&] { file.CreateGroup("values"); }, {"/values", "cannot create group"});
}

TEST(Hdf5Wrapper, Fletcher32DetectsCorruptedData) {
  ScratchFile scratch("corrupt");
  // A recognisable byte pattern, stored uncompressed (chunked, checksummed) so it can be found.
  std::vector<double> values(64);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 1234.5678 + static_cast<double>(i);
  {
    File file = File::Create(scratch.path());
    DatasetOptions options;
    options.fletcher32 = true;
    file.WriteDataset("checked", {64}, values, options);
  }
  std::vector<char> bytes;
  {
    std::ifstream in(scratch.path(), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  char pattern[sizeof(double)];
  std::memcpy(pattern, &values[10], sizeof pattern);
  auto found = std::search(bytes.begin(), bytes.end(), pattern, pattern + sizeof pattern);
  ASSERT_NE(found, bytes.end());
  *found ^= 0x01;  // One flipped bit in the stored data.
  {
    std::ofstream out(scratch.path(), std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  const File file = File::Open(scratch.path());
  ExpectError([&] { file.OpenDataset("checked").Read<double>(); }, {"/checked", "cannot read"});
}

// String datasets (the generator's /errors/message): UTF-8, long and empty texts come back
// unchanged, with and without the table's filters; reading numbers from them is an error.
TEST(Hdf5Wrapper, StringDatasetsRoundTrip) {
  ScratchFile scratch("strings");
  const std::vector<std::string> values = {"", "no contact at y = 200 mm", std::string(100000, 'x'),
                                           "\u00b5m \u00b0 \u03bc"};
  {
    File file = File::Create(scratch.path());
    file.WriteStringDataset("plain", values);
    const Dataset checked = file.WriteStringDataset("checked", values, CompressedChecked());
    EXPECT_TRUE(checked.HasFletcher32());
    EXPECT_TRUE(checked.HasDeflate());
  }
  const File file = File::Open(scratch.path());
  EXPECT_EQ(file.OpenDataset("plain").ReadStrings(), values);
  EXPECT_EQ(file.OpenDataset("checked").ReadStrings(), values);
  EXPECT_EQ(file.OpenDataset("checked").Type().Describe(), "string");
  ExpectError([&] { file.OpenDataset("plain").Read<double>(); }, {"/plain", "expected numbers"});
}

TEST(Hdf5Wrapper, StringDatasetErrorsNameTheObject) {
  ScratchFile scratch("strings_bad");
  File file = File::Create(scratch.path());
  ExpectError([&] { file.WriteStringDataset("empty", {}); }, {"/empty", "at least one value"});
  file.WriteDataset<double>("numbers", {2}, {1.0, 2.0});
  ExpectError([&] { file.OpenDataset("numbers").ReadStrings(); },
              {"/numbers", "expected strings", "float64"});
}

}  // namespace
}  // namespace wrc::h5
