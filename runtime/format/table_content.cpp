// The checks both table readers share, and the choice of reader by the file's first bytes.

#include "runtime/format/table_content.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "runtime/format/flat_table.h"
#include "runtime/hdf5/table_schema.h"
#include "wrc/runtime.hpp"

#ifdef WRC_RUNTIME_HDF5
#include "runtime/format/hdf5_content.h"
#endif

namespace wrc::format {
namespace {

constexpr auto kOkStatus = static_cast<std::int8_t>(schema::StoredStatus::kOk);

// Throws when the file cannot be opened for reading.
void RequireReadable(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw TableError(WRC_ERR_FILE, path + ": cannot open: " + std::strerror(errno));
}

void CheckNames(const std::vector<std::string>& names, const char* what, const std::string& where) {
  std::set<std::string> seen;
  for (const std::string& name : names) {
    if (name.empty()) Invalid(where, std::string("an empty ") + what + " name");
    if (!seen.insert(name).second) Invalid(where, std::string(what) + " \"" + name + "\" twice");
  }
}

void CheckAxes(const TableContent& content, const std::string& where) {
  if (content.axes.empty()) Invalid(where + "/axes", "no axes");
  if (content.axes.size() > static_cast<std::size_t>(WRC_MAX_AXES)) {
    Invalid(where + "/axes", std::to_string(content.axes.size()) + " axes, at most " +
                                 std::to_string(WRC_MAX_AXES) + " are supported");
  }
  std::vector<std::string> names;
  std::vector<std::uint64_t> shape;
  for (const AxisContent& axis : content.axes) {
    const std::string axis_where = where + "/axes/" + axis.name;
    if (axis.values.empty()) Invalid(axis_where, "is empty");
    if (axis.values.size() > kMaxAxisNodes) {
      Invalid(axis_where, "has " + std::to_string(axis.values.size()) + " nodes, more than the " +
                              std::to_string(kMaxAxisNodes) + " a table axis may have");
    }
    CheckAxisValues(axis.values, axis_where);
    names.push_back(axis.name);
    shape.push_back(axis.values.size());
  }
  CheckNames(names, "axis", where + "/axes");
  const std::uint64_t nodes = CountNodes(shape, where + "/axes");
  if (content.status.size() != nodes) {
    Invalid(where + "/status", "holds " + std::to_string(content.status.size()) +
                                   " nodes, the axes make " + std::to_string(nodes));
  }
}

// A node that solved fine must carry finite numbers; failed nodes may hold NaN, which a lookup
// reports as WRC_ERR_NO_DATA rather than returning it.
void CheckNodeValues(const TableContent& content, const std::string& where) {
  const std::size_t n_out = content.outputs.size();
  for (std::size_t node = 0; node < content.num_nodes(); ++node) {
    for (std::size_t k = 0; k < n_out; ++k) {
      const double value = content.values[node * n_out + k];
      const std::string output_where = where + "/outputs/" + content.outputs[k].name;
      if (std::abs(value) > WRC_VALUE_MAX_MAGNITUDE && std::isfinite(value)) {
        std::ostringstream text;
        text << "value " << value << " at node " << NodeText(content, node) << " is beyond ±"
             << WRC_VALUE_MAX_MAGNITUDE;
        Invalid(output_where, text.str());
      }
      if (!std::isfinite(value) && content.status[node] == kOkStatus) {
        Invalid(output_where,
                "non-finite value at node " + NodeText(content, node) + " whose /status is 0 (ok)");
      }
    }
  }
}

}  // namespace

void Invalid(const std::string& where, const std::string& problem) {
  throw TableError(WRC_ERR_FORMAT, where + ": " + problem);
}

void CheckAxisValues(const std::vector<double>& values, const std::string& where) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::ostringstream problem;
    problem.precision(17);
    if (!std::isfinite(values[i])) {
      problem << "value " << i << " is not finite";
    } else if (std::abs(values[i]) > WRC_AXIS_MAX_MAGNITUDE) {
      problem << "value " << i << " (" << values[i] << ") is beyond ±" << WRC_AXIS_MAX_MAGNITUDE;
    } else if (i > 0 && !(values[i] > values[i - 1])) {
      problem << "values must be strictly ascending, but value " << i << " (" << values[i]
              << ") follows " << values[i - 1];
    } else if (i > 0) {
      const double step = values[i] - values[i - 1];
      const double magnitude = std::max(std::abs(values[i]), std::abs(values[i - 1]));
      if (step < WRC_AXIS_MIN_STEP || step < WRC_AXIS_MIN_RELATIVE_STEP * magnitude) {
        problem << "values " << i - 1 << " and " << i << " (" << values[i - 1] << ", " << values[i]
                << ") are too close: a step must be at least " << WRC_AXIS_MIN_STEP << " and "
                << WRC_AXIS_MIN_RELATIVE_STEP << " of the values' magnitude";
      }
    }
    if (!problem.str().empty()) Invalid(where, problem.str());
  }
}

std::uint64_t CountNodes(const std::vector<std::uint64_t>& shape, const std::string& where) {
  std::uint64_t nodes = 1;
  std::string lengths;
  for (const std::uint64_t length : shape) {
    lengths += (lengths.empty() ? "" : ",") + std::to_string(length);
    if (length == 0) Invalid(where, "axes of lengths [" + lengths + "]: an axis without nodes");
    if (length > kMaxTableNodes / nodes) {
      Invalid(where, "axes of lengths [" + lengths + "] (and any after them) make more than " +
                         std::to_string(kMaxTableNodes) + " nodes");
    }
    nodes *= length;
  }
  return nodes;
}

void CheckContent(const TableContent& content, const std::string& where) {
  CheckAxes(content, where);
  if (content.outputs.empty()) Invalid(where + "/outputs", "holds no outputs");
  std::vector<std::string> names;
  for (const OutputContent& output : content.outputs) names.push_back(output.name);
  CheckNames(names, "output", where + "/outputs");
  if (content.values.size() / content.outputs.size() != content.num_nodes() ||
      content.values.size() % content.outputs.size() != 0) {
    Invalid(where + "/outputs", "hold " + std::to_string(content.values.size()) +
                                    " values, not one per node and output");
  }
  CheckNodeValues(content, where);
}

std::string NodeText(const TableContent& content, std::size_t node) {
  std::ostringstream text;
  text << '(';
  std::size_t stride = content.num_nodes();
  for (std::size_t a = 0; a < content.axes.size(); ++a) {
    const std::vector<double>& values = content.axes[a].values;
    stride /= values.size();
    text << (a ? ", " : "") << content.axes[a].name << '=' << values[node / stride % values.size()];
  }
  text << ')';
  return text.str();
}

TableContent ReadTableContent(const std::string& path) {
  std::error_code ignored;
  if (!std::filesystem::exists(path, ignored)) {
    throw TableError(WRC_ERR_FILE, path + ": no such file");
  }
  // A reader would block on a FIFO and read a device without end: regular files only.
  if (!std::filesystem::is_regular_file(path, ignored)) {
    throw TableError(WRC_ERR_FILE, path + ": not a regular file");
  }
  RequireReadable(path);  // a file that cannot be opened says why, whichever reader it was for
  if (IsFlatTableFile(path)) return ReadFlatTable(path);
#ifdef WRC_RUNTIME_HDF5
  return ReadHdf5Content(path);
#else
  throw TableError(WRC_ERR_FORMAT,
                   path +
                       ": not a flat table (.wrct); this runtime was built without HDF5 "
                       "(WRC_RUNTIME_HDF5=OFF) and reads flat tables only: convert an HDF5 table "
                       "with `wrc export TABLE.h5 -o TABLE.wrct`");
#endif
}

}  // namespace wrc::format
