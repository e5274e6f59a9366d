// The C API of include/wrc/runtime.h. Every function catches all exceptions here: nothing
// propagates into C callers.

#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <utility>

#include "runtime/table.h"
#include "wrc/runtime.h"

struct wrc_table {
  wrc::runtime::Table table;
};

namespace wrc::runtime {
namespace {

// Per-thread message buffer: thread-local so concurrent failures do not mix, a fixed array so
// that reporting an error in wrc_table_eval does not allocate.
thread_local char t_last_error[1024] = "";

}  // namespace

void SetLastError(const char* format, ...) {
  va_list arguments;
  va_start(arguments, format);
  std::vsnprintf(t_last_error, sizeof t_last_error, format, arguments);
  va_end(arguments);
}

}  // namespace wrc::runtime

namespace {

using wrc::runtime::SetLastError;

bool CheckTable(const wrc_table* t, const char* function) {
  if (t != nullptr) return true;
  SetLastError("%s: the table handle is NULL", function);
  return false;
}

bool CheckAxis(const wrc_table* t, int i, const char* function) {
  if (!CheckTable(t, function)) return false;
  if (i >= 0 && i < t->table.num_axes()) return true;
  SetLastError("%s: %s: axis index %d out of range [0, %d)", function, t->table.path().c_str(), i,
               t->table.num_axes());
  return false;
}

bool CheckOutput(const wrc_table* t, int i, const char* function) {
  if (!CheckTable(t, function)) return false;
  if (i >= 0 && i < t->table.num_outputs()) return true;
  SetLastError("%s: %s: output index %d out of range [0, %d)", function, t->table.path().c_str(), i,
               t->table.num_outputs());
  return false;
}

int Evaluate(const wrc_table* t, const double* point, double* out, double* d_out,
             const char* function) {
  if (!CheckTable(t, function)) return WRC_ERR_NULL_POINTER;
  if (point == nullptr || out == nullptr) {
    SetLastError("%s: %s: %s is NULL", function, t->table.path().c_str(),
                 point == nullptr ? "point" : "out");
    return WRC_ERR_NULL_POINTER;
  }
  return t->table.Eval(point, out, d_out);  // noexcept
}

}  // namespace

extern "C" {

int wrc_table_open(const char* path, wrc_table** out) {
  if (out == nullptr) {
    SetLastError("wrc_table_open: out is NULL");
    return WRC_ERR_NULL_POINTER;
  }
  *out = nullptr;
  if (path == nullptr) {
    SetLastError("wrc_table_open: path is NULL");
    return WRC_ERR_NULL_POINTER;
  }
  try {
    *out = new wrc_table{wrc::runtime::Table::Load(path)};
    return 0;
  } catch (const wrc::TableError& error) {
    SetLastError("wrc_table_open: %s", error.what());
    return error.code();
  } catch (const std::bad_alloc&) {
    SetLastError("wrc_table_open: %s: out of memory", path);
    return WRC_ERR_OUT_OF_MEMORY;
  } catch (const std::exception& error) {
    SetLastError("wrc_table_open: %s: internal error: %s", path, error.what());
    return WRC_ERR_INTERNAL;
  } catch (...) {
    SetLastError("wrc_table_open: %s: internal error", path);
    return WRC_ERR_INTERNAL;
  }
}

void wrc_table_close(wrc_table* t) { delete t; }

int wrc_table_num_axes(const wrc_table* t) {
  return CheckTable(t, "wrc_table_num_axes") ? t->table.num_axes() : WRC_ERR_NULL_POINTER;
}

int wrc_table_num_outputs(const wrc_table* t) {
  return CheckTable(t, "wrc_table_num_outputs") ? t->table.num_outputs() : WRC_ERR_NULL_POINTER;
}

const char* wrc_table_axis_name(const wrc_table* t, int i) {
  return CheckAxis(t, i, "wrc_table_axis_name") ? t->table.axis(i).name.c_str() : nullptr;
}

int wrc_table_axis_size(const wrc_table* t, int i) {
  if (!CheckAxis(t, i, "wrc_table_axis_size")) {
    return t == nullptr ? WRC_ERR_NULL_POINTER : WRC_ERR_INVALID_ARGUMENT;
  }
  return static_cast<int>(t->table.axis(i).values.size());
}

const double* wrc_table_axis_values(const wrc_table* t, int i) {
  return CheckAxis(t, i, "wrc_table_axis_values") ? t->table.axis(i).values.data() : nullptr;
}

const double* wrc_table_node_values(const wrc_table* t) {
  return CheckTable(t, "wrc_table_node_values") ? t->table.node_values() : nullptr;
}

const signed char* wrc_table_node_status(const wrc_table* t) {
  return CheckTable(t, "wrc_table_node_status")
             ? reinterpret_cast<const signed char*>(t->table.node_status())
             : nullptr;
}

const char* wrc_table_output_name(const wrc_table* t, int i) {
  return CheckOutput(t, i, "wrc_table_output_name") ? t->table.output(i).name.c_str() : nullptr;
}

int wrc_table_eval(const wrc_table* t, const double* point, double* out) {
  return Evaluate(t, point, out, nullptr, "wrc_table_eval");
}

const char* wrc_last_error(void) { return wrc::runtime::t_last_error; }

int wrc_table_eval_deriv(const wrc_table* t, const double* point, double* out, double* d_out) {
  return Evaluate(t, point, out, d_out, "wrc_table_eval_deriv");
}

int wrc_table_set_interpolation(wrc_table* t, int mode) {
  if (!CheckTable(t, "wrc_table_set_interpolation")) return WRC_ERR_NULL_POINTER;
  if (mode != WRC_INTERP_LINEAR && mode != WRC_INTERP_CUBIC) {
    SetLastError(
        "wrc_table_set_interpolation: %s: unknown mode %d (WRC_INTERP_LINEAR = %d, "
        "WRC_INTERP_CUBIC = %d)",
        t->table.path().c_str(), mode, WRC_INTERP_LINEAR, WRC_INTERP_CUBIC);
    return WRC_ERR_INVALID_ARGUMENT;
  }
  try {
    t->table.SetInterpolation(mode);
    return 0;
  } catch (const std::bad_alloc&) {
    SetLastError("wrc_table_set_interpolation: %s: out of memory for the cubic node data",
                 t->table.path().c_str());
    return WRC_ERR_OUT_OF_MEMORY;
  } catch (...) {
    SetLastError("wrc_table_set_interpolation: %s: internal error", t->table.path().c_str());
    return WRC_ERR_INTERNAL;
  }
}

int wrc_table_interpolation(const wrc_table* t) {
  return CheckTable(t, "wrc_table_interpolation") ? t->table.interpolation() : WRC_ERR_NULL_POINTER;
}

int wrc_table_set_storage(wrc_table* t, int storage) {
  if (!CheckTable(t, "wrc_table_set_storage")) return WRC_ERR_NULL_POINTER;
  if (storage != WRC_STORAGE_FLOAT64 && storage != WRC_STORAGE_FLOAT32) {
    SetLastError(
        "wrc_table_set_storage: %s: unknown storage %d (WRC_STORAGE_FLOAT64 = %d, "
        "WRC_STORAGE_FLOAT32 = %d)",
        t->table.path().c_str(), storage, WRC_STORAGE_FLOAT64, WRC_STORAGE_FLOAT32);
    return WRC_ERR_INVALID_ARGUMENT;
  }
  try {
    t->table.SetStorage(storage);
    return 0;
  } catch (const std::bad_alloc&) {
    SetLastError("wrc_table_set_storage: %s: out of memory for the float32 copy",
                 t->table.path().c_str());
    return WRC_ERR_OUT_OF_MEMORY;
  } catch (...) {
    SetLastError("wrc_table_set_storage: %s: internal error", t->table.path().c_str());
    return WRC_ERR_INTERNAL;
  }
}

int wrc_table_storage(const wrc_table* t) {
  return CheckTable(t, "wrc_table_storage") ? t->table.storage() : WRC_ERR_NULL_POINTER;
}

int wrc_table_axis_index(const wrc_table* t, const char* name) {
  if (!CheckTable(t, "wrc_table_axis_index")) return WRC_ERR_NULL_POINTER;
  if (name == nullptr) {
    SetLastError("wrc_table_axis_index: name is NULL");
    return WRC_ERR_NULL_POINTER;
  }
  for (int i = 0; i < t->table.num_axes(); ++i) {
    if (t->table.axis(i).name == name) return i;
  }
  SetLastError("wrc_table_axis_index: %s: no axis named '%s'", t->table.path().c_str(), name);
  return WRC_ERR_NOT_FOUND;
}

int wrc_table_output_index(const wrc_table* t, const char* name) {
  if (!CheckTable(t, "wrc_table_output_index")) return WRC_ERR_NULL_POINTER;
  if (name == nullptr) {
    SetLastError("wrc_table_output_index: name is NULL");
    return WRC_ERR_NULL_POINTER;
  }
  for (int i = 0; i < t->table.num_outputs(); ++i) {
    if (t->table.output(i).name == name) return i;
  }
  SetLastError("wrc_table_output_index: %s: no output named '%s'", t->table.path().c_str(), name);
  return WRC_ERR_NOT_FOUND;
}

const char* wrc_table_axis_unit(const wrc_table* t, int i) {
  return CheckAxis(t, i, "wrc_table_axis_unit") ? t->table.axis(i).unit.c_str() : nullptr;
}

const char* wrc_table_output_unit(const wrc_table* t, int i) {
  return CheckOutput(t, i, "wrc_table_output_unit") ? t->table.output(i).unit.c_str() : nullptr;
}

const char* wrc_table_attribute(const wrc_table* t, const char* name) {
  if (!CheckTable(t, "wrc_table_attribute")) return nullptr;
  if (name == nullptr) {
    SetLastError("wrc_table_attribute: name is NULL");
    return nullptr;
  }
  const auto& attributes = t->table.attributes();
  const auto found = attributes.find(name);  // Transparent comparator: no std::string built.
  if (found == attributes.end()) {
    SetLastError("wrc_table_attribute: %s: no string attribute '%s' on /", t->table.path().c_str(),
                 name);
    return nullptr;
  }
  return found->second.c_str();
}

int wrc_table_number_attribute(const wrc_table* t, const char* name, double* value) {
  if (!CheckTable(t, "wrc_table_number_attribute")) return WRC_ERR_NULL_POINTER;
  if (name == nullptr || value == nullptr) {
    SetLastError("wrc_table_number_attribute: %s is NULL", name == nullptr ? "name" : "value");
    return WRC_ERR_NULL_POINTER;
  }
  const auto& numbers = t->table.numbers();
  const auto found = numbers.find(name);
  if (found == numbers.end()) {
    SetLastError("wrc_table_number_attribute: %s: no number attribute '%s' on /",
                 t->table.path().c_str(), name);
    return WRC_ERR_NOT_FOUND;
  }
  *value = found->second;
  return WRC_OK;
}

const char* wrc_table_warning(const wrc_table* t) {
  if (!CheckTable(t, "wrc_table_warning")) return nullptr;
  const std::string& warning = t->table.warning();
  return warning.empty() ? nullptr : warning.c_str();
}

}  // extern "C"
