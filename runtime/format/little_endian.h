#pragma once
/// @file little_endian.h
/// Little-endian fields in byte strings, independent of the machine's byte order: the flat
/// table (flat_table.h) and the generator's journal are written and read with these.

#include <cstdint>
#include <cstring>
#include <string>

namespace wrc::le {

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

}  // namespace wrc::le
