#include "generator/journal.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include "runtime/format/little_endian.h"
#include "wrc/core/errors.h"

namespace wrc::gen {
namespace {

constexpr char kHeaderMagic[8] = {'W', 'R', 'C', 'J', 'R', 'N', 'L', '1'};
constexpr std::uint32_t kJournalVersion = 1;
constexpr std::size_t kFingerprintBytes = 32;
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + kFingerprintBytes + 4;
constexpr std::uint32_t kRecordMagic = 0x50435257;  // "WRCP" read as little-endian bytes
// Fixed part of a payload: index, status, time, z, value count, message length.
constexpr std::size_t kPayloadFixedBytes = 8 + 1 + 4 + 8 + 4 + 4;
// No real record comes near this (values and a message of a few hundred bytes); a larger
// length field can only be damage, and reading past it would swallow intact records.
constexpr std::uint32_t kMaxPayloadBytes = 1u << 20;

constexpr std::array<std::uint32_t, 256> MakeCrcTable() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int bit = 0; bit < 8; ++bit) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}
constexpr std::array<std::uint32_t, 256> kCrcTable = MakeCrcTable();

using le::PutF32;
using le::PutF64;
using le::PutU32;
using le::PutU64;

using le::Reader;

// Decodes one record at the reader's offset; false when it is incomplete or damaged (the
// reader's offset is then meaningless).
bool DecodeRecord(std::string_view bytes, Reader& reader, JournalRecord* record) {
  if (reader.remaining() < 8) return false;
  const std::size_t start = reader.offset();
  if (reader.U32() != kRecordMagic) return false;
  const std::uint32_t length = reader.U32();
  if (length < kPayloadFixedBytes || length > kMaxPayloadBytes) return false;
  if (reader.remaining() < static_cast<std::size_t>(length) + 4) return false;
  Reader payload = reader;
  reader.Take(length);
  const std::uint32_t stored_crc = reader.U32();
  if (Crc32(bytes.substr(start, 8 + static_cast<std::size_t>(length))) != stored_crc) return false;

  record->index = payload.U64();
  const auto status = static_cast<std::int8_t>(payload.U8());
  if (status < 0 || status >= kPointStatusCount) return false;
  record->result.status = static_cast<PointStatus>(status);
  record->result.solve_time_s = payload.F32();
  record->result.z = payload.F64();
  const std::uint64_t n_values = payload.U32();
  if (kPayloadFixedBytes + 8 * n_values > length) return false;
  record->result.values.resize(static_cast<std::size_t>(n_values));
  for (double& v : record->result.values) v = payload.F64();
  const std::uint64_t message_length = payload.U32();
  if (kPayloadFixedBytes + 8 * n_values + message_length != length) return false;
  record->result.message = std::string(payload.Take(static_cast<std::size_t>(message_length)));
  return true;
}

}  // namespace

std::uint32_t Crc32(std::string_view bytes) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const char byte : bytes) {
    c = kCrcTable[(c ^ static_cast<unsigned char>(byte)) & 0xFFu] ^ (c >> 8);
  }
  return c ^ 0xFFFFFFFFu;
}

std::string EncodeHeader(const JournalHeader& header) {
  if (header.fingerprint.size() != kFingerprintBytes) {
    throw std::invalid_argument("journal fingerprint must have 32 bytes");
  }
  std::string out(kHeaderMagic, sizeof kHeaderMagic);
  PutU32(out, kJournalVersion);
  PutU32(out, header.output_count);
  PutU64(out, header.point_count);
  out += header.fingerprint;
  PutU32(out, Crc32(out));
  return out;
}

std::string EncodeRecord(std::uint64_t index, const PointResult& result) {
  std::string payload;
  PutU64(payload, index);
  payload += static_cast<char>(static_cast<std::int8_t>(result.status));
  PutF32(payload, result.solve_time_s);
  PutF64(payload, result.z);
  PutU32(payload, static_cast<std::uint32_t>(result.values.size()));
  for (const double v : result.values) PutF64(payload, v);
  // A message longer than the record limit could only be a runaway exception text; keep its
  // start so the record stays readable.
  const std::size_t room = kMaxPayloadBytes - payload.size() - 4;
  const std::string_view message = std::string_view(result.message).substr(0, room);
  PutU32(payload, static_cast<std::uint32_t>(message.size()));
  payload += message;

  std::string out;
  out.reserve(payload.size() + 12);
  PutU32(out, kRecordMagic);
  PutU32(out, static_cast<std::uint32_t>(payload.size()));
  out += payload;
  PutU32(out, Crc32(out));
  return out;
}

std::vector<JournalRecord> DecodeRecords(std::string_view bytes) {
  std::vector<JournalRecord> records;
  Reader reader(bytes, 0);
  while (reader.remaining() > 0) {
    JournalRecord record;
    if (!DecodeRecord(bytes, reader, &record)) {
      throw std::runtime_error("malformed point records (" + std::to_string(bytes.size()) +
                               " bytes) from another rank");
    }
    records.push_back(std::move(record));
  }
  return records;
}

JournalContents ParseJournal(std::string_view bytes, const std::string& source) {
  JournalContents contents;
  contents.file_bytes = bytes.size();
  if (bytes.size() < kHeaderBytes) {
    // A crash between creating the file and writing its header: nothing to keep. Bytes that
    // do not even start like a journal are someone else's file, though.
    const std::size_t n = std::min(bytes.size(), sizeof kHeaderMagic);
    if (bytes.substr(0, n) != std::string_view(kHeaderMagic, n)) {
      throw InputError(source + ": not a wrc journal (it does not start with WRCJRNL1)");
    }
    return contents;
  }
  if (bytes.substr(0, sizeof kHeaderMagic) != std::string_view(kHeaderMagic, sizeof kHeaderMagic)) {
    throw InputError(source + ": not a wrc journal (it does not start with WRCJRNL1)");
  }
  Reader reader(bytes, sizeof kHeaderMagic);
  const std::uint32_t version = reader.U32();
  contents.header.output_count = reader.U32();
  contents.header.point_count = reader.U64();
  contents.header.fingerprint = std::string(reader.Take(kFingerprintBytes));
  const std::uint32_t stored_crc = reader.U32();
  if (Crc32(bytes.substr(0, kHeaderBytes - 4)) != stored_crc) {
    throw InputError(source +
                     ": the journal header is damaged (CRC mismatch); delete the file "
                     "to start over");
  }
  if (version != kJournalVersion) {
    throw InputError(source + ": journal format version " + std::to_string(version) +
                     ", this wrc reads version " + std::to_string(kJournalVersion));
  }
  contents.valid_bytes = kHeaderBytes;
  std::unordered_set<std::uint64_t> seen;
  while (reader.remaining() > 0) {
    JournalRecord record;
    if (!DecodeRecord(bytes, reader, &record)) break;  // torn or damaged tail: stop here
    if (record.index >= contents.header.point_count ||
        record.result.values.size() != contents.header.output_count) {
      break;  // cannot belong to this journal: treat as damage
    }
    contents.valid_bytes = reader.offset();
    if (seen.insert(record.index).second) contents.records.push_back(std::move(record));
  }
  return contents;
}

// ---------------------------------------------------------------------------------------------
// JournalWriter

namespace {

[[noreturn]] void FailErrno(const std::filesystem::path& path, const std::string& what) {
  throw InputError(path.string() + ": " + what + ": " + std::strerror(errno));
}

void WriteAll(int fd, std::string_view bytes, const std::filesystem::path& path) {
  while (!bytes.empty()) {
    const ssize_t written = ::write(fd, bytes.data(), bytes.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      throw InputError(path.string() + ": cannot append to the journal: " + std::strerror(errno));
    }
    bytes.remove_prefix(static_cast<std::size_t>(written));
  }
}

// A second `wrc generate` on the same table would interleave records with ours.
void LockOrFail(int fd, const std::filesystem::path& path) {
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK) {
      throw InputError(path.string() +
                       ": in use by another running `wrc generate` for the same table");
    }
    errno = error;
    FailErrno(path, "cannot lock the journal");
  }
}

// Makes a new directory entry durable (the file's own fsync does not cover its name).
void SyncDirectoryOf(const std::filesystem::path& path) {
  const std::filesystem::path dir =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the data itself is synced
  ::fsync(fd);
  ::close(fd);
}

// The most a journal of `header`'s run can hold: each point's record (its outputs, status, time
// and a message of up to a few kilobytes) written up to eight times over by retries and resumes.
// A journal beyond it is not one this run wrote, and is not read into memory.
std::uint64_t MaxJournalBytes(const JournalHeader& header) {
  constexpr std::uint64_t kRecordOverhead = 8192;
  return 1024 + 8 * header.point_count * (8 * std::uint64_t{header.output_count} + kRecordOverhead);
}

// A journal is a regular file of bounded size: a link to a device (/dev/zero) or a FIFO would be
// read without end.
void RequireReadableJournal(int fd, const std::filesystem::path& path,
                            const JournalHeader& header) {
  struct stat info {};
  if (::fstat(fd, &info) != 0) FailErrno(path, "cannot inspect the journal");
  if (!S_ISREG(info.st_mode)) {
    throw InputError(path.string() +
                     ": the journal is not a regular file; delete it to start over");
  }
  if (static_cast<std::uint64_t>(info.st_size) > MaxJournalBytes(header)) {
    throw InputError(path.string() + ": the journal holds " + std::to_string(info.st_size) +
                     " bytes, more than a run of " + std::to_string(header.point_count) +
                     " points writes; it is not this run's journal, delete it to start over");
  }
}

std::string ReadWholeFile(int fd, const std::filesystem::path& path) {
  std::string bytes;
  char buffer[1 << 16];
  if (::lseek(fd, 0, SEEK_SET) < 0) FailErrno(path, "cannot read the journal");
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0) {
      if (errno == EINTR) continue;
      FailErrno(path, "cannot read the journal");
    }
    if (got == 0) break;
    bytes.append(buffer, static_cast<std::size_t>(got));
  }
  return bytes;
}

}  // namespace

JournalWriter JournalWriter::Create(const std::filesystem::path& path,
                                    const JournalHeader& header) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) FailErrno(path, "cannot create the journal");
  LockOrFail(fd, path);
  JournalWriter writer(fd, path);
  writer.Append(EncodeHeader(header));
  writer.Sync();
  SyncDirectoryOf(path);
  return writer;
}

JournalWriter JournalWriter::Continue(const std::filesystem::path& path,
                                      const JournalHeader& header, JournalContents* contents) {
  const int fd = ::open(path.c_str(), O_RDWR | O_APPEND | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) FailErrno(path, "cannot open the journal");
  try {
    RequireReadableJournal(fd, path, header);
  } catch (...) {
    ::close(fd);
    throw;
  }
  LockOrFail(fd, path);
  JournalWriter writer(fd, path);
  *contents = ParseJournal(ReadWholeFile(fd, path), path.string());
  if (contents->valid_bytes > 0 && (contents->header.fingerprint != header.fingerprint ||
                                    contents->header.point_count != header.point_count ||
                                    contents->header.output_count != header.output_count)) {
    throw InputError(path.string() +
                     ": this journal belongs to a different run (another scene text, other "
                     "profile files or another warm-start setting), so its points cannot be "
                     "reused; resume with the scene it was started with, or delete the journal "
                     "to start over");
  }
  if (contents->valid_bytes < contents->file_bytes) {
    if (::ftruncate(fd, static_cast<off_t>(contents->valid_bytes)) != 0) {
      FailErrno(path, "cannot drop the torn end of the journal");
    }
  }
  if (contents->valid_bytes == 0) {
    contents->header = header;
    writer.Append(EncodeHeader(header));
  }
  writer.Sync();
  return writer;
}

JournalWriter::JournalWriter(JournalWriter&& other) noexcept
    : fd_(other.fd_), path_(std::move(other.path_)) {
  other.fd_ = -1;
}

JournalWriter::~JournalWriter() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

void JournalWriter::Append(std::string_view bytes) { WriteAll(fd_, bytes, path_); }

void JournalWriter::Sync() {
  if (fd_ >= 0 && ::fdatasync(fd_) != 0) {
    throw InputError(path_.string() +
                     ": cannot flush the journal to disk: " + std::strerror(errno));
  }
}

void JournalWriter::Close() {
  if (fd_ < 0) return;
  Sync();
  ::close(fd_);
  fd_ = -1;
}

}  // namespace wrc::gen
