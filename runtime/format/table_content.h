#pragma once
/// @file table_content.h
/// What a table file holds for a lookup, read and checked, from either of the two formats: the
/// HDF5 table the generator writes (docs/reference/table-layout.md; hdf5_content.cpp) and the
/// flat table `wrc export` makes of it for runtimes built without HDF5 (flat_table.h). The
/// runtime indexes it for lookups (runtime/table_load.cpp); the exporter writes it flat. Both
/// readers end in the same checks (CheckContent), so a table is refused for the same reasons
/// whichever way it is stored.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "wrc/runtime.h"

namespace wrc::format {

/// Most nodes on one axis: 2^24. Generated axes have tens to thousands of nodes; a longer one
/// can only be a damaged file, refused before anything is allocated for it.
inline constexpr std::uint64_t kMaxAxisNodes = std::uint64_t{1} << 24;

/// Most nodes in a table: 2^32, 34 GB per output. Any table a machine can hold is far smaller;
/// the bound keeps the node count and every offset within std::size_t.
inline constexpr std::uint64_t kMaxTableNodes = std::uint64_t{1} << 32;

/// Doubles the readers reserve past the values, so that the runtime can pad them without a copy:
/// with more than 8 outputs its multilinear kernel reads whole chunks of 8 and may run up to 7
/// doubles past the last datum (runtime/kernels.inc).
inline constexpr std::size_t kValuePadding = 8;

struct AxisContent {
  std::string name;
  std::string unit;
  std::vector<double> values;  ///< Strictly ascending (CheckAxisValues).
};

struct OutputContent {
  std::string name;
  std::string unit;
};

struct TableContent {
  std::string path;
  /// Why the table should be replaced though it loaded (an unsealed HDF5 table); empty: none.
  std::string warning;
  /// The root string attributes (format, wrc_version, scene, ...).
  std::map<std::string, std::string, std::less<>> attributes;
  /// The root float64 attributes (the fixed state of table_schema.h; none in older tables).
  std::map<std::string, double, std::less<>> numbers;
  /// In storage order: the nodes are row-major over the axes, the last varying fastest.
  std::vector<AxisContent> axes;
  std::vector<OutputContent> outputs;
  /// Per node, its outputs side by side: values[node * outputs.size() + k].
  std::vector<double> values;
  /// Per node, how its solve ended (schema::StoredStatus; 0 ok).
  std::vector<std::int8_t> status;

  std::size_t num_nodes() const { return status.size(); }
};

/// Reads the table at `path` in whichever format it is stored, and checks it. Throws
/// TableError (wrc/runtime.hpp): WRC_ERR_FILE when it cannot be read, WRC_ERR_FORMAT when it is
/// not a valid table, each naming the file, the object and the problem.
TableContent ReadTableContent(const std::string& path);

// ---- the checks both readers share ------------------------------------------------------------

/// Throws TableError(WRC_ERR_FORMAT) with "where: problem".
[[noreturn]] void Invalid(const std::string& where, const std::string& problem);

/// The node values of one axis obey the limits of include/wrc/runtime.h: finite, strictly
/// ascending, and spaced so that no step, span or reciprocal overflows or loses the position
/// within a cell.
void CheckAxisValues(const std::vector<double>& values, const std::string& where);

/// The axis lengths `shape`, multiplied without overflow: throws when they make more than
/// kMaxTableNodes nodes (a product that wrapped would size the data wrongly).
std::uint64_t CountNodes(const std::vector<std::uint64_t>& shape, const std::string& where);

/// The checks of a whole table once read: axes (count, names, values), outputs (count, names),
/// data sizes, and every node's values against its status (a node that solved must hold finite
/// values within WRC_VALUE_MAX_MAGNITUDE). `where` prefixes each message ("file:").
void CheckContent(const TableContent& content, const std::string& where);

/// "(y=1, fz=5000, ...)": the coordinates of a node, for messages.
std::string NodeText(const TableContent& content, std::size_t node);

}  // namespace wrc::format
