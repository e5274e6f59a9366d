#pragma once
/// @file flat_table.h
/// The flat table (`.wrct`): what a lookup needs of a table in one little-endian file that a
/// runtime reads with a short parser and no HDF5, for targets that cannot link HDF5 (real-time
/// boxes, rapid-prototyping units) and for hosts that must not parse HDF5 metadata. `wrc export`
/// writes it from an HDF5 table; a runtime built with or without HDF5 reads it.
///
/// Layout, version 2 (docs/reference/table-layout.md, "The flat table"); version 1, read too, is
/// the same with no numbers (its fourth count 0):
///
///     offset  bytes
///          0      8  magic 89 57 52 43 54 0D 0A 1A ("\x89WRCT\r\n\x1a", as PNG's: a text-mode
///                    copy or a 7-bit channel damages it visibly)
///          8      4  u32 version (2)
///         12      4  u32 flags (0; none defined)
///         16      8  u64 size of the whole file in bytes
///         24     32  SHA-256 of every byte from offset 56 to the end
///         56      8  u64 reserved (0)
///         64         u32 attributes, u32 axes, u32 outputs, u32 numbers
///                    per attribute: string key, string value
///                    per number: string key, f64 value
///                    per axis: string name, string unit, u64 nodes, f64 × nodes
///                    per output: string name, string unit
///                    zero bytes to the next multiple of 8 of the offset
///                    f64 × nodes × outputs: per node (row-major over the axes, the last
///                    fastest) its outputs side by side
///                    i8 × nodes: each node's status (0 ok, 1 no contact, 2 not converged, 3 error)
///
/// A string is a u32 byte count and that many bytes (UTF-8, no terminator). Integers are
/// unsigned little-endian, f64 IEEE 754 binary64 little-endian. Nothing follows the status.
/// Profiles and error messages stay in the HDF5 table: the flat one holds what a lookup reads.

#include <array>
#include <string>
#include <string_view>

#include "runtime/format/table_content.h"

namespace wrc::format {

inline constexpr std::array<char, 8> kFlatMagic = {'\x89', 'W', 'R', 'C', 'T', '\r', '\n', '\x1a'};
inline constexpr std::uint32_t kFlatVersion = 2;
/// The oldest version this build reads.
inline constexpr std::uint32_t kFlatEarliestVersion = 1;
/// Bytes before the body; the digest covers everything from kFlatDigestEnd on.
inline constexpr std::size_t kFlatHeaderSize = 64;
inline constexpr std::size_t kFlatDigestOffset = 24;
inline constexpr std::size_t kFlatDigestEnd = 56;

/// Whether `leading` (a file's first bytes) starts with the flat table's magic.
bool IsFlatTable(std::string_view leading);

/// Whether the file at `path` starts with the magic (false when it cannot be read).
bool IsFlatTableFile(const std::string& path);

/// The flat file of `content` (already checked: the exporter reads it with ReadTableContent).
std::string EncodeFlatTable(const TableContent& content);

/// The content of a flat table's bytes, checked as ReadTableContent checks. `path` names the
/// file in messages. With `check_digest` false the digest is not compared (a fuzzer's way past
/// it to the parser); everything else is still checked.
TableContent DecodeFlatTable(std::string_view bytes, const std::string& path,
                             bool check_digest = true);

/// Reads the whole file and decodes it. Throws TableError (WRC_ERR_FILE, WRC_ERR_FORMAT).
TableContent ReadFlatTable(const std::string& path);

/// Writes EncodeFlatTable(content) to `path` through a temporary file in the same folder,
/// renamed into place once complete and flushed: an interrupted export leaves no partial
/// table. Throws TableError(WRC_ERR_FILE) when it cannot be written.
void WriteFlatTable(const TableContent& content, const std::string& path);

}  // namespace wrc::format
