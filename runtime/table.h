#pragma once
/// @file table.h
/// The in-memory table behind a wrc_table handle: loading (table_load.cpp) and interpolation
/// (table_eval.cpp, table_cubic.cpp). Internal to wrc_runtime; users see include/wrc/runtime.h.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/format/table_content.h"
#include "runtime/node_memory.h"
#include "wrc/runtime.h"
#include "wrc/runtime.hpp"

namespace wrc::runtime {

constexpr int kMaxAxes = WRC_MAX_AXES;
/// Most corners of one half of a cell's axes: 2^ceil(kMaxAxes / 2) (kernels.h: kMaxHalf).
constexpr std::size_t kMaxHalfCorners = std::size_t{1} << ((kMaxAxes + 1) / 2);

struct Kernels;  // kernels.h

/// Doubles allocated past the end of the value array: with more than 8 outputs the multilinear
/// kernel reads whole chunks of 8 and may run up to 7 doubles past the last datum (kernels.inc).
/// (The cubic kernel reads exactly its cell's data.) The readers reserve them.
constexpr std::size_t kReadPadding = format::kValuePadding;

/// Records the calling thread's error message (printf-style; never allocates). Implemented in
/// c_api.cpp next to wrc_last_error().
void SetLastError(const char* format, ...) __attribute__((format(printf, 1, 2)));

struct Axis {
  std::string name;
  std::string unit;
  std::vector<double> values;  ///< Strictly ascending.
  /// 1 / (values[i + 1] - values[i]) per cell: evaluation multiplies instead of dividing.
  std::vector<double> inverse_steps;
  /// Nearly uniform spacing: the cell is found from (x - first) / mean step and a short walk.
  bool nearly_uniform = false;
  double inverse_mean_step = 0.0;
  /// Otherwise (a refined axis): per bucket of equal width, the cell of its left end
  /// (table_load.cpp: IndexBuckets), buckets + 1 entries.
  std::vector<int> bucket_cell;
  double inverse_bucket_width = 0.0;
};

struct Output {
  std::string name;
  std::string unit;
};

/// Bits of the per-cell flag arrays.
enum CellFlag : std::uint8_t {
  kCellStatus = WRC_FLAG_STATUS,  ///< A node entering the result has non-zero status.
  kCellNonFinite = 4,             ///< A corner node holds a non-finite value.
};

class Table {
 public:
  /// Reads and validates the file; throws TableError (wrc/runtime.hpp) with the WRC_ERR_* code
  /// and a message naming file, object and problem.
  static Table Load(const std::string& path);

  // Move-only: lookup_ points into the axes' vectors, whose buffers survive moves, not copies.
  Table(Table&&) noexcept = default;
  Table& operator=(Table&&) noexcept = default;
  Table(const Table&) = delete;
  Table& operator=(const Table&) = delete;

  int num_axes() const { return static_cast<int>(axes_.size()); }
  int num_outputs() const { return static_cast<int>(outputs_.size()); }
  const Axis& axis(int i) const { return axes_[static_cast<std::size_t>(i)]; }
  const Output& output(int i) const { return outputs_[static_cast<std::size_t>(i)]; }
  const std::string& path() const { return path_; }
  /// Why the table should be replaced though it loaded (an unsealed table); empty: none.
  const std::string& warning() const { return warning_; }
  /// Root string attributes (format, wrc_version, scene, ...).
  const std::map<std::string, std::string, std::less<>>& attributes() const { return attributes_; }
  /// Root float64 attributes (the fixed state of table_schema.h).
  const std::map<std::string, double, std::less<>>& numbers() const { return numbers_; }

  std::size_t num_nodes() const { return num_nodes_; }
  /// The grid data as loaded: per node (row-major over the axes), one value per output.
  const double* node_values() const { return values_.data(); }
  /// /status per node.
  const std::int8_t* node_status() const { return status_.data(); }

  int interpolation() const { return interpolation_; }
  /// Switches mode; builds the cubic node data on first use (may throw std::bad_alloc).
  void SetInterpolation(int mode);
  int storage() const { return storage_; }
  /// WRC_STORAGE_FLOAT64 or _FLOAT32: makes or drops the float copies (may throw
  /// std::bad_alloc).
  void SetStorage(int storage);

  /// Interpolates; d_out may be null. Returns flags >= 0 or a negative WRC_ERR_* code after
  /// SetLastError. Thread-safe, allocation-free.
  int Eval(const double* point, double* out, double* d_out) const noexcept;

 private:
  /// Cell of one axis coordinate: lower node index, local coordinate t in [0, 1], step h.
  /// (No member initialisers: Eval fills what it uses, nothing is zeroed per call.)
  struct CellCoordinate {
    int index;
    double t;
    double step;
    double inverse_step;
  };
  /// Everything Eval needs about the point, computed once for both modes.
  struct Located {
    int flags;
    std::size_t base_node;           ///< Node at the cell's lower corner.
    CellCoordinate cell[kMaxAxes];   ///< Per active axis.
    bool derivative_zero[kMaxAxes];  ///< Per active axis: clamped outside the range.
  };

  /// What locating a coordinate on an active axis needs, gathered in one place.
  struct AxisLookup {
    const double* nodes;
    const double* inverse_steps;
    double first;  ///< nodes[0]
    double last;   ///< nodes[size - 1]
    int size;
    int axis;  ///< Index into the point.
    bool nearly_uniform;
    double inverse_mean_step;
    const int* bucket_cell;
    int buckets;
    double inverse_bucket_width;
    std::size_t node_stride;
  };

  Table() = default;
  /// The table of checked content: axes indexed, values padded, cell flags set.
  static Table FromContent(format::TableContent content);
  /// Fills active_axes_, node strides and lookup_ once axes_ is final.
  void IndexAxes();
  /// Offsets, in doubles, of a cell's corners from its lower corner when each node holds
  /// node_block doubles: offset[0] for the lower half of the active axes, offset[1] for the upper
  /// half (kernels.h).
  void CornerOffsets(std::size_t node_block, std::size_t (*offset)[kMaxHalfCorners]) const;
  /// Locates the point's cell; or a negative code (NaN) after SetLastError.
  int Locate(const double* point, Located& located) const noexcept;
  int ReportNan(int axis) const noexcept;
  void EvalLinear(const Located& located, double* out, double* d_out) const noexcept;
  void EvalCubic(const Located& located, double* out, double* d_out) const noexcept;
  void BuildCubic();
  /// A cell with a failed (non-finite) corner, in either mode: per output the multilinear
  /// weights renormalised over the corners with a finite value (runtime/README.md). Returns
  /// flags, or WRC_ERR_NO_DATA after SetLastError when every corner of an output failed.
  int EvalValidCorners(const Located& located, int flags, double* out,
                       double* d_out) const noexcept;

  std::string path_;
  std::vector<Axis> axes_;
  std::vector<Output> outputs_;
  std::map<std::string, std::string, std::less<>> attributes_;
  std::map<std::string, double, std::less<>> numbers_;
  std::string warning_;  // less<>: lookup by const char*

  std::vector<int> active_axes_;          ///< Axes with more than one node, ascending.
  AxisLookup lookup_[kMaxAxes];           ///< Per active axis.
  const Kernels* kernels_ = nullptr;      ///< Summation kernels for this CPU.
  std::vector<std::size_t> node_stride_;  ///< Per axis, in nodes (row-major).
  std::size_t num_nodes_ = 0;

  NodeMemory<double> values_;               ///< num_nodes × num_outputs (+ kReadPadding).
  std::vector<std::int8_t> status_;         ///< num_nodes.
  std::vector<std::uint8_t> linear_flags_;  ///< Per cell: kCellStatus | kCellNonFinite.
  /// Offsets in values_ of a cell's corners: CornerOffsets(num_outputs).
  std::size_t linear_offset_[2][kMaxHalfCorners] = {};

  int interpolation_ = WRC_INTERP_LINEAR;
  /// Cubic node data: per node, per output, per subset S of active axes (bit j = active axis j):
  /// the mixed derivative ∂^|S| f / ∏_{j∈S} ∂x_j estimated by limited slopes. Built by
  /// SetInterpolation (the only allocation of cubic mode), empty until then. The node data start
  /// at hermite_[hermite_start_], on a cache-line boundary.
  NodeMemory<double> hermite_;
  std::size_t hermite_start_ = 0;
  /// Offsets in hermite_, in doubles, of the corners of a cell relative to its lower corner:
  /// [0] lower-half corners (active axes 0 .. L-1), [1] upper-half ones (kernels.h).
  std::size_t cubic_offset_[2][kMaxHalfCorners] = {};
  std::vector<std::uint8_t> cubic_flags_;

  int storage_ = WRC_STORAGE_FLOAT64;
  /// With float32 storage: values_ and the cubic data as floats, same layout and offsets (the
  /// cubic data then live here only: hermite_ is dropped).
  NodeMemory<float> values32_;
  NodeMemory<float> hermite32_;
};

}  // namespace wrc::runtime
