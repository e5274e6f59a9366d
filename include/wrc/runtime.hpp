#pragma once
/// @file runtime.hpp
/// Thin, header-only C++17 layer over the C API of wrc/runtime.h: an RAII wrc::Table and
/// exceptions instead of error codes. Method names mirror the C functions (wrc_table_eval →
/// Table::eval) so that the C documentation applies unchanged.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "wrc/runtime.h"

namespace wrc {

/// A failure reported by the runtime; code() is the WRC_ERR_* value, what() the message of
/// wrc_last_error().
class TableError : public std::runtime_error {
 public:
  TableError(int code, const std::string& message) : std::runtime_error(message), code_(code) {}
  int code() const noexcept { return code_; }

 private:
  int code_;
};

/// Interpolation modes of WRC_INTERP_*.
enum class Interpolation : int { kLinear = WRC_INTERP_LINEAR, kCubic = WRC_INTERP_CUBIC };
enum class Storage : int { kFloat64 = WRC_STORAGE_FLOAT64, kFloat32 = WRC_STORAGE_FLOAT32 };

/// An open table. Move-only; closes the handle on destruction. Const methods may be called from
/// several threads at once (the eval family is thread-safe and, unless it throws, allocation-free).
class Table {
 public:
  /// Opens and validates a table file. Throws TableError (WRC_ERR_FILE, WRC_ERR_FORMAT, ...).
  explicit Table(const std::string& path) {
    const int code = wrc_table_open(path.c_str(), &handle_);
    if (code != 0) Throw(code);
  }
  Table(Table&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  Table& operator=(Table&& other) noexcept {
    if (this != &other) {
      wrc_table_close(handle_);
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }
  Table(const Table&) = delete;
  Table& operator=(const Table&) = delete;
  ~Table() { wrc_table_close(handle_); }

  int num_axes() const { return wrc_table_num_axes(handle_); }
  int num_outputs() const { return wrc_table_num_outputs(handle_); }
  std::string axis_name(int i) const { return CheckedString(wrc_table_axis_name(handle_, i)); }
  std::string axis_unit(int i) const { return CheckedString(wrc_table_axis_unit(handle_, i)); }
  int axis_size(int i) const { return Checked(wrc_table_axis_size(handle_, i)); }
  /// Node coordinates of axis i (a copy).
  std::vector<double> axis_values(int i) const {
    const double* values = wrc_table_axis_values(handle_, i);
    if (values == nullptr) Throw(WRC_ERR_INVALID_ARGUMENT);
    return std::vector<double>(values, values + axis_size(i));
  }
  std::string output_name(int i) const { return CheckedString(wrc_table_output_name(handle_, i)); }
  std::string output_unit(int i) const { return CheckedString(wrc_table_output_unit(handle_, i)); }
  /// Index of an axis by name; throws TableError (WRC_ERR_NOT_FOUND) when absent.
  int axis_index(const std::string& name) const {
    return Checked(wrc_table_axis_index(handle_, name.c_str()));
  }
  /// Index of an output by name; throws TableError (WRC_ERR_NOT_FOUND) when absent.
  int output_index(const std::string& name) const {
    return Checked(wrc_table_output_index(handle_, name.c_str()));
  }
  std::vector<std::string> axis_names() const {
    std::vector<std::string> names;
    for (int i = 0; i < num_axes(); ++i) names.push_back(axis_name(i));
    return names;
  }
  std::vector<std::string> output_names() const {
    std::vector<std::string> names;
    for (int i = 0; i < num_outputs(); ++i) names.push_back(output_name(i));
    return names;
  }
  /// Why the table should be replaced although it loaded (an unsealed table); empty: none.
  std::string warning() const {
    const char* text = wrc_table_warning(handle_);
    return text != nullptr ? text : "";
  }
  /// A string attribute of the root group (wrc_version, scene, ...); throws when absent.
  std::string attribute(const std::string& name) const {
    return CheckedString(wrc_table_attribute(handle_, name.c_str()), WRC_ERR_NOT_FOUND);
  }
  /// A float64 attribute of the root group (the fixed state: wheelset_velocity, fixed_y, ...);
  /// throws when absent.
  double number_attribute(const std::string& name) const {
    double value = 0.0;
    Checked(wrc_table_number_attribute(handle_, name.c_str(), &value));
    return value;
  }

  /// Not to be called while other threads evaluate this table (see wrc_table_set_interpolation).
  void set_interpolation(Interpolation mode) {
    Checked(wrc_table_set_interpolation(handle_, static_cast<int>(mode)));
  }
  Interpolation interpolation() const {
    return static_cast<Interpolation>(Checked(wrc_table_interpolation(handle_)));
  }
  /// What lookups read (see wrc_table_set_storage); not concurrently with evaluations.
  void set_storage(Storage storage) {
    Checked(wrc_table_set_storage(handle_, static_cast<int>(storage)));
  }
  Storage storage() const { return static_cast<Storage>(Checked(wrc_table_storage(handle_))); }

  /// Interpolates all outputs at point (num_axes() values) into out (num_outputs() values).
  /// Returns the flags WRC_FLAG_CLAMPED | WRC_FLAG_STATUS (0 when neither); throws TableError on
  /// errors (NaN input, no data).
  int eval(const double* point, double* out) const {
    return Checked(wrc_table_eval(handle_, point, out));
  }
  /// Also the derivatives, d_out[k * num_axes() + a] = ∂out[k]/∂point[a].
  int eval(const double* point, double* out, double* d_out) const {
    return Checked(wrc_table_eval_deriv(handle_, point, out, d_out));
  }
  /// Convenience form returning a new vector (allocates); flags optional.
  std::vector<double> eval(const std::vector<double>& point, int* flags = nullptr) const {
    if (static_cast<int>(point.size()) != num_axes()) {
      throw TableError(WRC_ERR_INVALID_ARGUMENT,
                       "wrc::Table::eval: point has " + std::to_string(point.size()) +
                           " coordinates, the table " + std::to_string(num_axes()) + " axes");
    }
    std::vector<double> out(static_cast<std::size_t>(num_outputs()));
    const int result = eval(point.data(), out.data());
    if (flags != nullptr) *flags = result;
    return out;
  }
  /// The raw C result (flags or a negative WRC_ERR_* code) without exceptions.
  int try_eval(const double* point, double* out, double* d_out = nullptr) const noexcept {
    return wrc_table_eval_deriv(handle_, point, out, d_out);
  }

  /// The C handle, for calls this class does not wrap. Owned by this object.
  wrc_table* get() const noexcept { return handle_; }

 private:
  [[noreturn]] static void Throw(int code) { throw TableError(code, wrc_last_error()); }
  static int Checked(int code) {
    if (code < 0) Throw(code);
    return code;
  }
  static std::string CheckedString(const char* text, int code = WRC_ERR_INVALID_ARGUMENT) {
    if (text == nullptr) Throw(code);
    return text;
  }

  wrc_table* handle_ = nullptr;
};

/// Both wheels of a wheelset, each read from a table (see wrc_wheelset_create). The tables are
/// borrowed: they must outlive this object. Move-only; eval() is thread-safe and, unless it
/// throws, allocation-free. (Named apart from the solver's wrc::Wheelset, its geometry.)
class WheelsetTable {
 public:
  /// A state with the defaults of wrc_wheelset_state_init (zeros, fz and mu unknown).
  struct State : wrc_wheelset_state {
    State() : wrc_wheelset_state() { wrc_wheelset_state_init(this); }
  };
  using Result = wrc_wheelset_result;

  /// One table for both wheels: the other side reads it mirrored.
  explicit WheelsetTable(const Table& table) : WheelsetTable(nullptr, &table) {}
  /// A table for each side (either may be made for either side).
  WheelsetTable(const Table& left, const Table& right) : WheelsetTable(&left, &right) {}
  WheelsetTable(WheelsetTable&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  WheelsetTable& operator=(WheelsetTable&& other) noexcept {
    if (this != &other) {
      wrc_wheelset_destroy(handle_);
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }
  WheelsetTable(const WheelsetTable&) = delete;
  WheelsetTable& operator=(const WheelsetTable&) = delete;
  ~WheelsetTable() { wrc_wheelset_destroy(handle_); }

  /// Rail origin (y, z) in the track frame, mm, for the total moment; side WRC_LEFT/WRC_RIGHT.
  void set_rail_origin(int side, double y, double z) {
    Checked(wrc_wheelset_set_rail_origin(handle_, side, y, z));
  }
  /// Evaluates both wheels; returns their flags or'ed, throws TableError on errors.
  int eval(const wrc_wheelset_state& state, Result& result) const {
    return Checked(wrc_wheelset_eval(handle_, &state, &result));
  }
  Result eval(const wrc_wheelset_state& state, int* flags = nullptr) const {
    Result result;
    const int code = eval(state, result);
    if (flags != nullptr) *flags = code;
    return result;
  }
  /// The raw C result without exceptions.
  int try_eval(const wrc_wheelset_state& state, Result& result) const noexcept {
    return wrc_wheelset_eval(handle_, &state, &result);
  }
  wrc_wheelset* get() const noexcept { return handle_; }

 private:
  WheelsetTable(const Table* left, const Table* right) {
    Checked(wrc_wheelset_create(left != nullptr ? left->get() : nullptr,
                                right != nullptr ? right->get() : nullptr, &handle_));
  }
  static int Checked(int code) {
    if (code < 0) throw TableError(code, wrc_last_error());
    return code;
  }

  wrc_wheelset* handle_ = nullptr;
};

}  // namespace wrc
