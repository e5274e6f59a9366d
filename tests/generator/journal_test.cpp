// The journal of `wrc generate`: records round-trip bit for bit, a torn or damaged tail is
// dropped without losing what precedes it, and journals of other runs are refused.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>

#include "generator/journal.h"
#include "tests/generator/generator_test_util.h"
#include "wrc/core/errors.h"

namespace wrc::gen {
namespace {

using test::ScratchDir;

JournalHeader Header(char fill = 'a') { return JournalHeader{std::string(32, fill), 100, 3}; }

PointResult Result(double base, PointStatus status = PointStatus::kOk, std::string message = {}) {
  PointResult result;
  result.status = status;
  result.solve_time_s = 0.125f;
  result.z = base / 7.0;
  result.values = {base, -base / 3.0, std::numeric_limits<double>::quiet_NaN()};
  result.message = std::move(message);
  return result;
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void ExpectSameResult(const PointResult& a, const PointResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.solve_time_s, b.solve_time_s);
  EXPECT_TRUE(SameBits(a.z, b.z));
  ASSERT_EQ(a.values.size(), b.values.size());
  for (std::size_t i = 0; i < a.values.size(); ++i) EXPECT_TRUE(SameBits(a.values[i], b.values[i]));
  EXPECT_EQ(a.message, b.message);
}

TEST(Crc32, KnownCheckValue) {
  // The standard check value of CRC-32/ISO-HDLC (zlib, PNG, Ethernet).
  EXPECT_EQ(Crc32("123456789"), 0xCBF43926u);
  EXPECT_EQ(Crc32(""), 0u);
}

TEST(Journal, RecordsRoundTripBitForBit) {
  std::string bytes = EncodeHeader(Header());
  bytes += EncodeRecord(7, Result(1.0 / 3.0));
  bytes += EncodeRecord(99, Result(-2.5e-300, PointStatus::kError, "at y = 200 mm: no rail"));
  const JournalContents contents = ParseJournal(bytes, "test");
  EXPECT_EQ(contents.header.fingerprint, Header().fingerprint);
  EXPECT_EQ(contents.header.point_count, 100u);
  EXPECT_EQ(contents.header.output_count, 3u);
  EXPECT_EQ(contents.valid_bytes, bytes.size());
  ASSERT_EQ(contents.records.size(), 2u);
  EXPECT_EQ(contents.records[0].index, 7u);
  ExpectSameResult(contents.records[0].result, Result(1.0 / 3.0));
  EXPECT_EQ(contents.records[1].index, 99u);
  ExpectSameResult(contents.records[1].result,
                   Result(-2.5e-300, PointStatus::kError, "at y = 200 mm: no rail"));
}

TEST(Journal, TornLastRecordIsDroppedAndEverythingBeforeKept) {
  const std::string head =
      EncodeHeader(Header()) + EncodeRecord(1, Result(1.0)) + EncodeRecord(2, Result(2.0));
  const std::string last = EncodeRecord(3, Result(3.0, PointStatus::kNotConverged, "limit"));
  // Every possible tear inside the last record: a kill can stop a write anywhere.
  for (std::size_t cut = 0; cut < last.size(); ++cut) {
    const JournalContents contents = ParseJournal(head + last.substr(0, cut), "test");
    ASSERT_EQ(contents.records.size(), 2u) << "cut " << cut;
    EXPECT_EQ(contents.valid_bytes, head.size());
    EXPECT_EQ(contents.file_bytes, head.size() + cut);
  }
  EXPECT_EQ(ParseJournal(head + last, "test").records.size(), 3u);
}

TEST(Journal, DamagedRecordEndsTheIntactPrefix) {
  const std::string first = EncodeHeader(Header()) + EncodeRecord(1, Result(1.0));
  std::string second = EncodeRecord(2, Result(2.0));
  second[20] ^= 0x10;  // one flipped bit in a value: the CRC must catch it
  const std::string bytes = first + second + EncodeRecord(3, Result(3.0));
  const JournalContents contents = ParseJournal(bytes, "test");
  ASSERT_EQ(contents.records.size(), 1u);
  EXPECT_EQ(contents.valid_bytes, first.size());
}

TEST(Journal, RecordsOutsideTheHeaderCountsAreDamage) {
  const std::string bytes = EncodeHeader(Header()) + EncodeRecord(1, Result(1.0)) +
                            EncodeRecord(100, Result(2.0));  // index == point count
  EXPECT_EQ(ParseJournal(bytes, "test").records.size(), 1u);
  PointResult short_result = Result(1.0);
  short_result.values.pop_back();
  EXPECT_EQ(
      ParseJournal(EncodeHeader(Header()) + EncodeRecord(1, short_result), "t").records.size(), 0u);
}

TEST(Journal, HeaderProblemsAreReported) {
  EXPECT_THROW(ParseJournal("this is some other file, long enough to hold a header, surely yes",
                            "other.txt"),
               InputError);
  std::string bytes = EncodeHeader(Header());
  bytes[20] ^= 0x01;
  try {
    ParseJournal(bytes, "t.h5.journal");
    ADD_FAILURE() << "a damaged header was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("header is damaged"), std::string::npos) << e.what();
  }
  // A header torn by a crash right after creation holds nothing worth keeping.
  const JournalContents torn = ParseJournal(EncodeHeader(Header()).substr(0, 30), "t");
  EXPECT_EQ(torn.valid_bytes, 0u);
  EXPECT_TRUE(torn.records.empty());
}

TEST(Journal, ConcatenatedRecordsDecodeOrThrow) {
  const std::string bytes = EncodeRecord(4, Result(4.0)) + EncodeRecord(5, Result(5.0));
  const std::vector<JournalRecord> records = DecodeRecords(bytes);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].index, 5u);
  EXPECT_THROW(DecodeRecords(bytes.substr(0, bytes.size() - 1)), std::runtime_error);
}

TEST(JournalWriter, ContinueDropsTheTornTailAndAppends) {
  ScratchDir dir("journal_continue");
  const auto path = dir / "t.h5.journal";
  {
    JournalWriter writer = JournalWriter::Create(path, Header());
    writer.Append(EncodeRecord(1, Result(1.0)));
    writer.Append(EncodeRecord(2, Result(2.0)).substr(0, 17));  // torn by a crash
  }
  {
    JournalContents contents;
    JournalWriter writer = JournalWriter::Continue(path, Header(), &contents);
    ASSERT_EQ(contents.records.size(), 1u);
    EXPECT_LT(contents.valid_bytes, contents.file_bytes);
    writer.Append(EncodeRecord(2, Result(2.0)));
  }
  const JournalContents contents = ParseJournal(test::ReadFile(path), "t");
  ASSERT_EQ(contents.records.size(), 2u);
  EXPECT_EQ(contents.valid_bytes, contents.file_bytes);
  ExpectSameResult(contents.records[1].result, Result(2.0));
}

TEST(JournalWriter, RefusesAJournalOfAnotherRun) {
  ScratchDir dir("journal_other");
  const auto path = dir / "t.h5.journal";
  JournalWriter::Create(path, Header('a')).Close();
  JournalContents contents;
  try {
    JournalWriter::Continue(path, Header('b'), &contents);
    ADD_FAILURE() << "a journal of another scene was continued";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("different"), std::string::npos) << message;
    EXPECT_NE(message.find("t.h5.journal"), std::string::npos) << message;
  }
}

// A journal linked to a device that reads without end, or larger than any run of the header's
// points writes (a sparse file here), is refused before it is read into memory.
TEST(JournalWriter, ReadsAreBounded) {
  ScratchDir dir("journal_bounded");
  const auto device = dir / "device.journal";
  std::filesystem::create_symlink("/dev/zero", device);
  const auto huge = dir / "huge.journal";
  JournalWriter::Create(huge, Header()).Close();
  std::filesystem::resize_file(huge, std::uintmax_t{1} << 40);  // 1 TiB, sparse
  for (const auto& [path, problem] : {std::pair{device, "not a regular file"},
                                      std::pair{huge, "more than a run of 100 points"}}) {
    JournalContents contents;
    try {
      JournalWriter::Continue(path, Header(), &contents);
      ADD_FAILURE() << path << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
    }
  }
}

TEST(JournalWriter, OneWriterAtATime) {
  ScratchDir dir("journal_lock");
  const auto path = dir / "t.h5.journal";
  JournalWriter first = JournalWriter::Create(path, Header());
  JournalContents contents;
  try {
    JournalWriter::Continue(path, Header(), &contents);
    ADD_FAILURE() << "a second writer got the journal";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("in use"), std::string::npos) << e.what();
  }
  EXPECT_THROW(JournalWriter::Create(path, Header()), InputError);  // exists
}

}  // namespace
}  // namespace wrc::gen
