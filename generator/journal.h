#pragma once
// The journal of a `wrc generate` run (TABLE.h5.journal): a header naming the scene, then one
// record per finished point, appended as points finish. Records carry a CRC-32, so a record
// torn by a crash (kill -9, power loss) is recognised and dropped; everything before it is
// kept. All integers are little-endian, so a journal moves between machines.
//
//   header  "WRCJRNL1" u32 version, u32 output count, u64 point count, 32-byte fingerprint,
//           u32 CRC-32 of the preceding bytes                                    (60 bytes)
//   record  u32 magic "WRCP", u32 payload length, payload, u32 CRC-32 of magic..payload
//   payload u64 point index, i8 status, f32 solve time, f64 z, u32 n, n × f64 values,
//           u32 message length, message bytes

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "wrc/generator/generator.h"

namespace wrc::gen {

/// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320, as zlib and PNG use).
std::uint32_t Crc32(std::string_view bytes);

/// What a journal is about: the fingerprint identifies the scene (text, profile bytes, warm
/// start setting); the counts guard against a damaged header.
struct JournalHeader {
  std::string fingerprint;  ///< 32 raw bytes (a SHA-256 digest).
  std::uint64_t point_count = 0;
  std::uint32_t output_count = 0;
};

/// Bytes of a header.
std::string EncodeHeader(const JournalHeader& header);
/// Bytes of a record.
std::string EncodeRecord(std::uint64_t index, const PointResult& result);

/// A finished point read back from a journal.
struct JournalRecord {
  std::uint64_t index = 0;
  PointResult result;
};

/// Decodes concatenated records (as EncodeRecord makes them, e.g. sent by another rank);
/// throws std::runtime_error when the bytes are not exactly whole, intact records.
std::vector<JournalRecord> DecodeRecords(std::string_view bytes);

/// A journal as read from disk.
struct JournalContents {
  JournalHeader header;
  /// Records in file order (a point appears once; a repeated index keeps the first record).
  std::vector<JournalRecord> records;
  /// Length of the intact prefix (header and whole records). Bytes past it are a torn or
  /// damaged tail, dropped when the journal is continued.
  std::uint64_t valid_bytes = 0;
  std::uint64_t file_bytes = 0;
};

/// Parses journal bytes; `source` names the file in messages. Throws InputError when the bytes
/// do not start with an intact journal header. A header that is itself incomplete (a crash
/// right after creating the file) reads as a journal without records and valid_bytes 0.
JournalContents ParseJournal(std::string_view bytes, const std::string& source);

/// An open journal, locked against a second writer (flock), appended to with write(2) so that a
/// killed process loses nothing it has appended; Sync() makes the data survive a lost machine.
class JournalWriter {
 public:
  /// Creates a new journal and writes the header (fails if the file exists).
  static JournalWriter Create(const std::filesystem::path& path, const JournalHeader& header);
  /// Opens an existing journal, reads it and truncates it to its intact prefix (valid_bytes;
  /// 0 rewrites the header). The contents read are returned in *contents.
  static JournalWriter Continue(const std::filesystem::path& path, const JournalHeader& header,
                                JournalContents* contents);

  JournalWriter(JournalWriter&& other) noexcept;
  JournalWriter& operator=(JournalWriter&&) = delete;
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  ~JournalWriter();

  /// Appends bytes (whole records); throws std::runtime_error on a write error (disk full).
  void Append(std::string_view bytes);
  /// Flushes the appended records to the disk (fdatasync).
  void Sync();
  /// Syncs and closes (releasing the lock); the file stays.
  void Close();

 private:
  JournalWriter(int fd, std::filesystem::path path) : fd_(fd), path_(std::move(path)) {}
  int fd_ = -1;
  std::filesystem::path path_;
};

}  // namespace wrc::gen
