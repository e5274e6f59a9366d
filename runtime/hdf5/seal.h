#pragma once
/// @file seal.h
/// A table's seal: a SHA-256 of every byte of the file after HDF5's user block, kept in that
/// block, so that a reader proves the file intact before HDF5 parses a byte of it. HDF5 1.10
/// can crash on damaged metadata even where its checksums catch the damage (its error path
/// frees memory it never set), so a damaged table must not reach HDF5 at all.

#include <cstddef>
#include <string>
#include <string_view>

#include "runtime/hdf5/hdf5.h"

namespace wrc::h5 {

/// The user block HDF5 leaves to the application at the start of a sealed file: the smallest
/// HDF5 allows, and room for the seal's record.
inline constexpr std::size_t kUserBlockSize = 512;

/// SHA-256 of bytes as 64 lowercase hex digits, through nettle: the one digest wrc computes (the
/// seal's, and the profile and scene hashes a table records).
std::string Sha256Hex(std::string_view bytes);

/// Writes the seal of a closed file created with a user block of kUserBlockSize bytes. Throws
/// Error when the file cannot be read or written.
void SealFile(const std::string& path);

/// A sealed file that does not match its seal: damaged, truncated, extended or edited.
class SealError : public Error {
 public:
  using Error::Error;
};

/// A file in HDF5's earliest format (superblock version 0 or 1: no metadata checksums), which
/// File::Open refuses unless asked to read it: HDF5 1.10 can crash on a damaged byte of it.
class EarliestFormatError : public Error {
 public:
  using Error::Error;
};

enum class SealStatus {
  kIntact,    ///< Sealed, and every byte matches its seal.
  kUnsealed,  ///< An HDF5 file from before seals, with metadata checksums: signature at byte 0.
  /// An HDF5 file from before seals in HDF5's earliest format (superblock version 0 or 1).
  kUnsealedEarliest,
};

/// Checks a file before HDF5 opens it: kIntact, kUnsealed or kUnsealedEarliest. Throws SealError
/// naming the file when it is damaged (its bytes do not match its seal, or the seal itself is
/// damaged), and Error when it is neither sealed nor HDF5 or cannot be read.
SealStatus CheckSeal(const std::string& path);

}  // namespace wrc::h5
