#pragma once
/// @file hdf5_content.h
/// The HDF5 table's reader (docs/reference/table-layout.md): only in a runtime built with HDF5
/// (WRC_RUNTIME_HDF5). The seal is checked before HDF5 parses a byte (runtime/hdf5/seal.h).

#include <string>

#include "runtime/format/table_content.h"

namespace wrc::format {

/// Reads and checks an HDF5 table; throws TableError as ReadTableContent.
TableContent ReadHdf5Content(const std::string& path);

}  // namespace wrc::format
