// The `wrc` Python module: tables and wheelsets of the runtime over numpy arrays. Every value
// comes from the C API (wrc/runtime.h) called point by point, so results are the C API's to the
// bit; the loops run without the GIL.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>
#include <iterator>
#include <limits>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <string>
#include <vector>

#include "wrc/runtime.hpp"

namespace py = pybind11;

namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Ints = py::array_t<int, py::array::c_style>;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// A table shared by Python objects (wheelsets keep theirs alive). The mutex lets evaluations
// run concurrently from Python threads while a mode switch waits for them.
struct PyTable {
  explicit PyTable(const std::string& path) : table(CheckedPath(path)) {}
  // A Python string may hold NUL, which would end the C path early and open another file.
  static const std::string& CheckedPath(const std::string& path) {
    if (path.find('\0') != std::string::npos) throw py::value_error("path: contains a NUL byte");
    return path;
  }
  wrc::Table table;
  mutable std::shared_mutex mode_mutex;
};

std::vector<py::ssize_t> AxisShape(const wrc::Table& t) {
  std::vector<py::ssize_t> shape;
  for (int a = 0; a < t.num_axes(); ++a) shape.push_back(t.axis_size(a));
  return shape;
}

py::ssize_t NodeCount(const wrc::Table& t) {
  py::ssize_t n = 1;
  for (const py::ssize_t size : AxisShape(t)) n *= size;
  return n;
}

// points as (N, n_axes); a single point (n_axes,) counts as N = 1.
// Real numbers only: forcecast would turn None into NaN and drop an imaginary part silently.
Doubles RealArray(const py::handle& value, const std::string& what) {
  const py::array raw = py::array::ensure(value);
  if (!raw) throw py::type_error(what + ": expected an array of numbers");
  const char kind = raw.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
    throw py::type_error(what + ": expected real numbers, got an array of dtype " +
                         std::string(py::str(raw.dtype())));
  }
  Doubles a = Doubles::ensure(raw);
  if (!a) throw py::type_error(what + ": expected an array of numbers");
  return a;
}

Doubles PointsArray(const wrc::Table& t, const py::handle& points) {
  Doubles a = RealArray(points, "points");
  const py::ssize_t n_axes = t.num_axes();
  if (a.ndim() == 1 && a.shape(0) == n_axes) return a.reshape({py::ssize_t{1}, n_axes});
  if (a.ndim() != 2 || a.shape(1) != n_axes) {
    throw py::value_error("points: expected shape (N, " + std::to_string(n_axes) + ") or (" +
                          std::to_string(n_axes) + ",), one coordinate per axis");
  }
  return a;
}

// Evaluates every point; a failed point (negative code in flags) gets NaN values.
void EvalPoints(const wrc_table* t, const double* points, py::ssize_t n, int n_axes, int n_out,
                double* values, double* derivatives, int* flags) {
  const py::ssize_t n_deriv = static_cast<py::ssize_t>(n_out) * n_axes;
  for (py::ssize_t i = 0; i < n; ++i) {
    double* v = values + i * n_out;
    double* d = derivatives != nullptr ? derivatives + i * n_deriv : nullptr;
    const double* p = points + i * n_axes;
    flags[i] = d != nullptr ? wrc_table_eval_deriv(t, p, v, d) : wrc_table_eval(t, p, v);
    if (flags[i] >= 0) continue;
    for (int k = 0; k < n_out; ++k) v[k] = kNan;
    for (py::ssize_t k = 0; d != nullptr && k < n_deriv; ++k) d[k] = kNan;
  }
}

// An instance made by __new__ without __init__ has no C++ object behind it, and pybind11 hands
// its methods whatever the memory holds: every method reaches its object through this check.
template <class T>
T& Constructed(py::handle self) {
  auto* instance = reinterpret_cast<py::detail::instance*>(self.ptr());
  const py::detail::value_and_holder v_h =
      instance->get_value_and_holder(py::detail::get_type_info(typeid(T)));
  if (!v_h || !v_h.holder_constructed() || v_h.value_ptr() == nullptr) {
    throw py::type_error(py::str(py::type::handle_of(self).attr("__name__")).cast<std::string>() +
                         " object is not initialised: create it with its constructor");
  }
  return *static_cast<T*>(v_h.value_ptr());
}

py::tuple Evaluate(const PyTable& self, const py::handle& points, bool derivatives) {
  const wrc::Table& t = self.table;
  const Doubles p = PointsArray(t, points);
  const py::ssize_t n = p.shape(0);
  const int n_axes = t.num_axes(), n_out = t.num_outputs();
  Doubles values({n, static_cast<py::ssize_t>(n_out)});
  Doubles d =
      derivatives ? Doubles({n, static_cast<py::ssize_t>(n_out), py::ssize_t{n_axes}}) : Doubles(0);
  Ints flags(n);
  const double* in = p.data();
  double* out = values.mutable_data();
  double* d_out = derivatives ? d.mutable_data() : nullptr;
  int* f = flags.mutable_data();
  {
    py::gil_scoped_release release;
    std::shared_lock lock(self.mode_mutex);
    EvalPoints(t.get(), in, n, n_axes, n_out, out, d_out, f);
  }
  return derivatives ? py::make_tuple(values, d, flags) : py::make_tuple(values, flags);
}

// A failed point as a Python exception: the last one, whose reason wrc_last_error() still holds
// (evaluation ran in this thread).
void RaiseOnError(const Ints& flags) {
  const int* f = flags.data();
  for (py::ssize_t i = flags.shape(0); i-- > 0;) {
    if (f[i] < 0) {
      throw py::value_error("point " + std::to_string(i) + ": " + wrc_last_error() + " (code " +
                            std::to_string(f[i]) + ")");
    }
  }
}

// The arrays handed out are copies of the table's data: read-only, so that a write fails
// instead of seeming to change the table.
template <typename Array>
Array ReadOnly(Array array) {
  array.attr("setflags")(false);
  return array;
}

py::dict AxesDict(const wrc::Table& t) {
  py::dict axes;
  for (int a = 0; a < t.num_axes(); ++a) {
    const double* values = wrc_table_axis_values(t.get(), a);
    axes[py::str(t.axis_name(a))] = ReadOnly(Doubles(t.axis_size(a), values));
  }
  return axes;
}

// Output k on the grid: an array shaped like the axes.
Doubles OutputGrid(const wrc::Table& t, int k) {
  Doubles grid(AxisShape(t));
  const double* nodes = wrc_table_node_values(t.get());
  double* out = grid.mutable_data();
  const py::ssize_t n = NodeCount(t);
  for (py::ssize_t i = 0; i < n; ++i) out[i] = nodes[i * t.num_outputs() + k];
  return grid;
}

py::dict OutputsDict(const wrc::Table& t) {
  py::dict outputs;
  for (int k = 0; k < t.num_outputs(); ++k) {
    outputs[py::str(t.output_name(k))] = ReadOnly(OutputGrid(t, k));
  }
  return outputs;
}

py::array_t<std::int8_t> StatusGrid(const wrc::Table& t) {
  py::array_t<std::int8_t> grid(AxisShape(t));
  std::memcpy(grid.mutable_data(), wrc_table_node_status(t.get()),
              static_cast<std::size_t>(NodeCount(t)));
  return ReadOnly(grid);
}

void SetInterpolation(PyTable& self, const std::string& mode) {
  if (mode != "linear" && mode != "cubic") {
    throw py::value_error("interpolation: 'linear' or 'cubic', not '" + mode + "'");
  }
  py::gil_scoped_release release;
  std::unique_lock lock(self.mode_mutex);
  self.table.set_interpolation(mode == "linear" ? wrc::Interpolation::kLinear
                                                : wrc::Interpolation::kCubic);
}

void SetStorage(PyTable& self, const std::string& storage) {
  if (storage != "float64" && storage != "float32") {
    throw py::value_error("storage: 'float64' or 'float32', not '" + storage + "'");
  }
  py::gil_scoped_release release;
  std::unique_lock lock(self.mode_mutex);
  self.table.set_storage(storage == "float64" ? wrc::Storage::kFloat64 : wrc::Storage::kFloat32);
}

// ------------------------------------------------------------------------------------------
// Wheelsets

struct PyWheelset {
  PyWheelset(std::shared_ptr<PyTable> l, std::shared_ptr<PyTable> r)
      : left(std::move(l)),
        right(std::move(r)),
        wheelset(left && right     ? wrc::WheelsetTable(left->table, right->table)
                 : left != nullptr ? wrc::WheelsetTable(left->table)
                                   : wrc::WheelsetTable(right->table)) {}
  std::shared_ptr<PyTable> left, right;  // kept alive: the wheelset borrows them
  wrc::WheelsetTable wheelset;
};

// A table argument: None, or a constructed Table (not one made by __new__ alone).
std::shared_ptr<PyTable> TableArgument(const py::object& table, const char* name) {
  if (table.is_none()) return nullptr;
  if (!py::isinstance<PyTable>(table)) {
    throw py::type_error(std::string("Wheelset: ") + name + " must be a wrc.Table or None");
  }
  Constructed<PyTable>(table);
  return table.cast<std::shared_ptr<PyTable>>();
}

std::shared_ptr<PyWheelset> MakeWheelset(const py::object& left_table,
                                         const py::object& right_table) {
  std::shared_ptr<PyTable> left = TableArgument(left_table, "left");
  std::shared_ptr<PyTable> right = TableArgument(right_table, "right");
  if (!left && !right) throw py::value_error("Wheelset: give a left or a right table, or both");
  return std::make_shared<PyWheelset>(std::move(left), std::move(right));
}

// One state component: a scalar or an array of N values.
struct Column {
  Doubles values;
};

// The number of states: 1, or the common size of the array arguments.
py::ssize_t StateCount(const std::vector<Column>& columns) {
  py::ssize_t n = 1;
  for (const Column& c : columns) {
    const py::ssize_t size = c.values.size();
    if (size == 1) continue;
    if (n != 1 && size != n) throw py::value_error("Wheelset.eval: arrays of different sizes");
    n = size;
  }
  return n;
}

py::dict WheelsetEval(const PyWheelset& self, const py::kwargs& kwargs) {
  static constexpr const char* kNames[] = {"y",        "z",       "roll",    "yaw",      "vy",
                                           "vroll",    "vyaw",    "omega",   "velocity", "fz_left",
                                           "fz_right", "mu_left", "mu_right"};
  std::vector<Column> columns;
  for (const char* name : kNames) {
    const bool unknown = std::strncmp(name, "fz", 2) == 0 || std::strncmp(name, "mu", 2) == 0;
    const bool required = std::strcmp(name, "velocity") == 0 || std::strcmp(name, "omega") == 0;
    if (!kwargs.contains(name) && required) {
      throw py::type_error(std::string("Wheelset.eval: ") + name + " is required");
    }
    py::object value = kwargs.contains(name) ? py::reinterpret_borrow<py::object>(kwargs[name])
                                             : py::float_(unknown ? kNan : 0.0);
    columns.push_back({RealArray(value, std::string("Wheelset.eval: ") + name)});
  }
  for (const auto& item : kwargs) {
    const std::string key = py::str(item.first);
    bool known = false;
    for (const char* name : kNames) known = known || key == name;
    if (!known) throw py::type_error("Wheelset.eval: unknown argument '" + key + "'");
  }
  const py::ssize_t n = StateCount(columns);
  Doubles force({n, py::ssize_t{2}, py::ssize_t{3}}), moment({n, py::ssize_t{2}, py::ssize_t{3}});
  Doubles contact_y({n, py::ssize_t{2}}), contact_angle({n, py::ssize_t{2}});
  Doubles t_gamma({n, py::ssize_t{2}});
  Doubles total_force({n, py::ssize_t{3}}), total_moment({n, py::ssize_t{3}});
  Ints flags({n, py::ssize_t{2}}), code(n);
  // Raw pointers, taken while the GIL is held; a size-1 column repeats its value (stride 0).
  const double* in[std::size(kNames)];
  py::ssize_t stride[std::size(kNames)];
  for (std::size_t c = 0; c < columns.size(); ++c) {
    in[c] = columns[c].values.data();
    stride[c] = columns[c].values.size() == 1 ? 0 : 1;
  }
  double* f_out = force.mutable_data();
  double* m_out = moment.mutable_data();
  double* y_out = contact_y.mutable_data();
  double* a_out = contact_angle.mutable_data();
  double* g_out = t_gamma.mutable_data();
  double* tf_out = total_force.mutable_data();
  double* tm_out = total_moment.mutable_data();
  int* flag_out = flags.mutable_data();
  int* code_out = code.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) {
      auto at = [&](int c) { return in[c][i * stride[c]]; };
      wrc_wheelset_state s;
      s.y = at(0), s.z = at(1), s.roll = at(2), s.yaw = at(3), s.vy = at(4), s.vroll = at(5);
      s.vyaw = at(6), s.omega = at(7), s.velocity = at(8);
      s.fz[WRC_LEFT] = at(9), s.fz[WRC_RIGHT] = at(10);
      s.mu[WRC_LEFT] = at(11), s.mu[WRC_RIGHT] = at(12);
      wrc_wheelset_result r;
      code_out[i] = self.wheelset.try_eval(s, r);
      const bool failed = code_out[i] < 0;
      for (int side = 0; side < 2; ++side) {
        const wrc_wheel_contact& c = r.wheel[side];
        for (int j = 0; j < 3; ++j) {
          f_out[(i * 2 + side) * 3 + j] = failed ? kNan : c.force[j];
          m_out[(i * 2 + side) * 3 + j] = failed ? kNan : c.moment[j];
        }
        y_out[i * 2 + side] = failed ? kNan : c.contact_y;
        a_out[i * 2 + side] = failed ? kNan : c.contact_angle;
        g_out[i * 2 + side] = failed ? kNan : c.t_gamma;
        flag_out[i * 2 + side] = failed ? code_out[i] : c.flags;
      }
      for (int j = 0; j < 3; ++j) {
        tf_out[i * 3 + j] = failed ? kNan : r.force[j];
        tm_out[i * 3 + j] = failed ? kNan : r.moment[j];
      }
    }
  }
  py::dict result;
  result["force"] = force;
  result["moment"] = moment;
  result["contact_y"] = contact_y;
  result["contact_angle"] = contact_angle;
  result["t_gamma"] = t_gamma;
  result["flags"] = flags;
  result["total_force"] = total_force;
  result["total_moment"] = total_moment;
  result["code"] = code;
  return result;
}

}  // namespace

PYBIND11_MODULE(wrc, m) {
  m.doc() = "wrc runtime: precomputed wheel-rail contact tables and wheelsets over numpy arrays";
  py::register_exception<wrc::TableError>(m, "TableError", PyExc_RuntimeError);
  m.attr("__version__") = WRC_VERSION;
  m.attr("FLAG_CLAMPED") = WRC_FLAG_CLAMPED;
  m.attr("FLAG_STATUS") = WRC_FLAG_STATUS;
  m.attr("FLAG_FIXED") = WRC_FLAG_FIXED;
  m.attr("LEFT") = WRC_LEFT;
  m.attr("RIGHT") = WRC_RIGHT;

  py::class_<PyTable, std::shared_ptr<PyTable>>(m, "Table", "An open wrc table (read fully).")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def_property_readonly(
          "axis_names", [](py::handle s) { return Constructed<PyTable>(s).table.axis_names(); })
      .def_property_readonly(
          "output_names", [](py::handle s) { return Constructed<PyTable>(s).table.output_names(); })
      .def_property_readonly(
          "axes", [](py::handle s) { return AxesDict(Constructed<PyTable>(s).table); },
          "{name: node coordinates}, in axis order")
      .def_property_readonly(
          "outputs", [](py::handle s) { return OutputsDict(Constructed<PyTable>(s).table); },
          "{name: grid values shaped like the axes}")
      .def_property_readonly("status",
                             [](py::handle s) { return StatusGrid(Constructed<PyTable>(s).table); })
      .def("axis_unit",
           [](py::handle s, int i) { return Constructed<PyTable>(s).table.axis_unit(i); })
      .def("output_unit",
           [](py::handle s, int i) { return Constructed<PyTable>(s).table.output_unit(i); })
      .def_property_readonly(
          "warning",
          [](py::handle s) -> py::object {
            const std::string text = Constructed<PyTable>(s).table.warning();
            if (text.empty()) return py::none();
            return py::str(text);
          },
          "why the table should be replaced although it loaded (unsealed), or None")
      .def("attribute",
           [](py::handle s, const std::string& n) {
             // A NUL would end the C name early and read another attribute.
             if (n.find('\0') != std::string::npos) {
               throw py::value_error("attribute: the name contains a NUL byte");
             }
             return Constructed<PyTable>(s).table.attribute(n);
           })
      .def_property(
          "interpolation",
          [](py::handle s) {
            return Constructed<PyTable>(s).table.interpolation() == wrc::Interpolation::kCubic
                       ? "cubic"
                       : "linear";
          },
          [](py::handle s, const std::string& mode) {
            SetInterpolation(Constructed<PyTable>(s), mode);
          })
      .def_property(
          "storage",
          [](py::handle s) {
            return Constructed<PyTable>(s).table.storage() == wrc::Storage::kFloat32 ? "float32"
                                                                                     : "float64";
          },
          [](py::handle s, const std::string& storage) {
            SetStorage(Constructed<PyTable>(s), storage);
          },
          "What lookups read: 'float64' (the table's doubles) or 'float32' (a float copy: half "
          "the memory traffic, values within the float rounding of the node data)")
      .def(
          "eval",
          [](py::handle s, const py::handle& points) {
            py::tuple r = Evaluate(Constructed<PyTable>(s), points, false);
            RaiseOnError(r[1].cast<Ints>());
            return py::object(r[0]);
          },
          py::arg("points"),
          "Values (N, n_outputs) at points (N, n_axes); raises ValueError if a point fails.")
      .def(
          "eval_flags",
          [](py::handle s, const py::handle& points) {
            return Evaluate(Constructed<PyTable>(s), points, false);
          },
          py::arg("points"), "(values, flags): flags per point as wrc_table_eval returns them.")
      .def(
          "eval_deriv",
          [](py::handle s, const py::handle& points) {
            return Evaluate(Constructed<PyTable>(s), points, true);
          },
          py::arg("points"),
          "(values, derivatives (N, n_outputs, n_axes), flags), as wrc_table_eval_deriv.");

  py::class_<PyWheelset, std::shared_ptr<PyWheelset>>(m, "Wheelset",
                                                      "Both wheels of a wheelset from tables.")
      .def(py::init(&MakeWheelset), py::arg("left") = py::none(), py::arg("right") = py::none())
      .def(
          "set_rail_origin",
          [](py::handle s, int side, double y, double z) {
            Constructed<PyWheelset>(s).wheelset.set_rail_origin(side, y, z);
          },
          py::arg("side"), py::arg("y"), py::arg("z"))
      .def(
          "eval",
          [](py::handle s, const py::kwargs& kwargs) {
            return WheelsetEval(Constructed<PyWheelset>(s), kwargs);
          },
          "eval(y=0, z=0, roll=0, yaw=0, vy=0, vroll=0, vyaw=0, omega, velocity, fz_left, "
          "fz_right, mu_left, mu_right): scalars or arrays of one size N; returns a dict of "
          "arrays (force, moment (N, 2, 3); contact_y, contact_angle, t_gamma, flags (N, 2); "
          "total_force, total_moment (N, 3); code (N,)).");
}
