#pragma once
/// @file little_endian.h
/// wrc's one byte codec: little-endian fields in byte strings, independent of the machine's
/// byte order. The flat table (flat_table.h), the generator's journal and its MPI messages are
/// written with Put* and read with Reader (or, in the flat table's reader, with the Load*
/// functions under its own messages).

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace wrc::le {

inline void PutU8(std::string& out, std::uint8_t v) { out += static_cast<char>(v); }

inline void PutU32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
}

inline void PutU64(std::string& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out += static_cast<char>((v >> (8 * i)) & 0xFF);
}

inline void PutF64(std::string& out, double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  PutU64(out, bits);
}

inline void PutF32(std::string& out, float v) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  PutU32(out, bits);
}

/// The unsigned integer of the `bytes` bytes (at most 8) at p.
inline std::uint64_t LoadUnsigned(const char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= std::uint64_t{static_cast<std::uint8_t>(p[i])} << (8 * i);
  return v;
}

inline double LoadF64(const char* p) {
  const std::uint64_t bits = LoadUnsigned(p, 8);
  double v = 0.0;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

inline float LoadF32(const char* p) {
  const auto bits = static_cast<std::uint32_t>(LoadUnsigned(p, 4));
  float v = 0.0f;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

/// Reads the fields Put* writes, checked: a read past the end yields zeros (an empty view) and
/// marks the reader failed. A decoder reads a message through and checks ok() (or AtEnd())
/// once; what a failure means is the caller's (a torn journal record, a malformed message).
class Reader {
 public:
  explicit Reader(std::string_view bytes, std::size_t offset = 0)
      : bytes_(bytes),
        offset_(offset <= bytes.size() ? offset : bytes.size()),
        ok_(offset <= bytes.size()) {}

  bool ok() const { return ok_; }
  /// Every byte read, none missing.
  bool AtEnd() const { return ok_ && offset_ == bytes_.size(); }
  std::size_t offset() const { return offset_; }
  std::size_t remaining() const { return bytes_.size() - offset_; }

  std::string_view Take(std::size_t n) {
    if (n > remaining()) {
      ok_ = false;
      offset_ = bytes_.size();
      return {};
    }
    const std::string_view part = bytes_.substr(offset_, n);
    offset_ += n;
    return part;
  }
  /// The unsigned integer of the next `n` bytes (at most 8).
  std::uint64_t Unsigned(int n) {
    const std::string_view part = Take(static_cast<std::size_t>(n));
    return part.empty() ? 0 : LoadUnsigned(part.data(), n);
  }
  std::uint8_t U8() { return static_cast<std::uint8_t>(Unsigned(1)); }
  std::uint32_t U32() { return static_cast<std::uint32_t>(Unsigned(4)); }
  std::uint64_t U64() { return Unsigned(8); }
  double F64() {
    const std::string_view part = Take(8);
    return part.empty() ? 0.0 : LoadF64(part.data());
  }
  float F32() {
    const std::string_view part = Take(4);
    return part.empty() ? 0.0f : LoadF32(part.data());
  }

 private:
  std::string_view bytes_;
  std::size_t offset_;
  bool ok_;
};

}  // namespace wrc::le
