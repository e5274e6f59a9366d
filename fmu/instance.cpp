#include "fmu/instance.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "fmu/start_values.h"
#include "fmu/variables.h"

namespace wrc::fmu {
namespace {

std::string ReadStartValuesText(const std::string& resources) {
  const std::string path = resources + kStartValuesFile;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

Instance::Instance(std::string name, std::string resource_path, bool logging, LogSink log)
    : name_(std::move(name)),
      resources_(std::move(resource_path)),
      logging_(logging),
      log_(std::move(log)),
      start_(kNumVariables),
      real_(kNumVariables, NAN),
      int_(kNumVariables, 0) {
  if (!resources_.empty() && resources_.back() != '/') resources_ += '/';
  try {
    for (const auto& [vr, text] : ParseStartValues(ReadStartValuesText(resources_))) {
      start_[vr] = text;
    }
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(resources_ + kStartValuesFile + ": " + e.what());
  }
  for (const Variable& v : Variables()) {
    const bool needs_start =
        v.causality == Causality::kParameter || v.causality == Causality::kInput;
    if (needs_start && start_[v.value_reference].empty() && v.type != Type::kString) {
      throw std::runtime_error(resources_ + kStartValuesFile + " gives no start value of " +
                               v.name);
    }
  }
  ApplyStartValues();
}

Instance::~Instance() { Unload(); }

void Instance::ApplyStartValues() {
  for (const Variable& v : Variables()) {
    const std::string& text = start_[v.value_reference];
    if (v.type == Type::kFloat64) real_[v.value_reference] = text.empty() ? NAN : std::stod(text);
    if (v.type == Type::kEnumeration && !text.empty()) int_[v.value_reference] = std::stoi(text);
  }
  table_[0] = start_[kRightTable];
  table_[1] = start_[kLeftTable];
  real_[kTime] = 0.0;
  dirty_ = true;
}

void Instance::Log(fmi3::Status status, const std::string& message) const {
  if (!log_ || (!logging_ && status < fmi3::kError)) return;
  const char* category = status >= fmi3::kError ? "logStatusError" : "logStatusWarning";
  log_(status, category, (name_ + ": " + message).c_str());
}

fmi3::Status Instance::Refuse(const char* function, const std::string& message) const {
  Log(fmi3::kError, std::string(function) + ": " + message);
  return fmi3::kError;
}

// ---- the mode machine ------------------------------------------------------------------------

fmi3::Status Instance::EnterInitialization() {
  if (mode_ != Mode::kInstantiated)
    return Refuse("entering initialization mode", "not instantiated");
  mode_ = Mode::kInitialization;
  return fmi3::kOK;
}

// The tables are loaded here at the latest (or at the first output read in initialization
// mode): the parameters that name them are fixed from now on.
fmi3::Status Instance::ExitInitialization() {
  if (mode_ != Mode::kInitialization) {
    return Refuse("exiting initialization mode", "not in initialization mode");
  }
  const fmi3::Status status = Evaluate();
  if (status >= fmi3::kError) return status;
  mode_ = Mode::kStep;
  return status;
}

fmi3::Status Instance::DoStep(double time, double step) {
  if (mode_ != Mode::kStep) return Refuse("doing a step", "not in step mode");
  if (!(step > 0.0) || !std::isfinite(time)) {
    return Refuse("doing a step", "the communication step must be > 0 from a finite time");
  }
  real_[kTime] = time + step;
  return Evaluate();
}

fmi3::Status Instance::Terminate() {
  if (mode_ != Mode::kStep && mode_ != Mode::kInitialization) {
    return Refuse("terminating", "neither in initialization nor in step mode");
  }
  mode_ = Mode::kTerminated;
  return fmi3::kOK;
}

fmi3::Status Instance::Reset() {
  Unload();
  ApplyStartValues();
  mode_ = Mode::kInstantiated;
  return fmi3::kOK;
}

// ---- variables -------------------------------------------------------------------------------

fmi3::Status Instance::CheckAccess(const char* function, fmi3::ValueReference vr, int type,
                                   bool set) {
  if (vr >= kNumVariables)
    return Refuse(function, "no variable has value reference " + std::to_string(vr));
  const Variable& v = Variables()[vr];
  if (static_cast<int>(v.type) != type) {
    return Refuse(function, v.name + " is of type " + TypeName(v.type));
  }
  if (mode_ == Mode::kTerminated && set) return Refuse(function, "the instance is terminated");
  if (!set) {
    if (v.causality == Causality::kOutput && mode_ == Mode::kInstantiated) {
      return Refuse(function, v.name + " is known from initialization mode on");
    }
    return fmi3::kOK;
  }
  switch (v.causality) {
    case Causality::kIndependent:
      return Refuse(function, "time advances with the steps");
    case Causality::kOutput:
      return Refuse(function, v.name + " is an output");
    case Causality::kParameter:
      if (mode_ == Mode::kStep || wheelset_ != nullptr) {
        return Refuse(function, v.name +
                                    " is a fixed parameter: it is set before the tables "
                                    "are loaded (before initialization ends)");
      }
      return fmi3::kOK;
    case Causality::kInput:
      dirty_ = true;
      return fmi3::kOK;
  }
  return fmi3::kOK;
}

// An output is written also when its lookup failed: NaN then, and status says why.
fmi3::Status Instance::GetFloat64(fmi3::ValueReference vr, double* value) {
  fmi3::Status status = CheckAccess("get", vr, static_cast<int>(Type::kFloat64), false);
  if (status != fmi3::kOK) return status;
  if (Variables()[vr].causality == Causality::kOutput) status = Evaluate();
  *value = real_[vr];
  return status;
}

fmi3::Status Instance::SetFloat64(fmi3::ValueReference vr, double value) {
  const fmi3::Status status = CheckAccess("set", vr, static_cast<int>(Type::kFloat64), true);
  if (status == fmi3::kOK) real_[vr] = value;
  return status;
}

fmi3::Status Instance::GetInt32(fmi3::ValueReference vr, std::int32_t* value) {
  fmi3::Status status = CheckAccess("get", vr, static_cast<int>(Type::kInt32), false);
  if (status != fmi3::kOK) return status;
  status = Evaluate();  // the Int32 variables are outputs
  *value = int_[vr];
  return status;
}

fmi3::Status Instance::GetInt64(fmi3::ValueReference vr, std::int64_t* value) {
  const fmi3::Status status = CheckAccess("get", vr, static_cast<int>(Type::kEnumeration), false);
  if (status == fmi3::kOK) *value = int_[vr];
  return status;
}

fmi3::Status Instance::SetInt64(fmi3::ValueReference vr, std::int64_t value) {
  fmi3::Status status = CheckAccess("set", vr, static_cast<int>(Type::kEnumeration), true);
  if (status == fmi3::kOK && value != kInterpolationLinear && value != kInterpolationCubic) {
    status = Refuse("set",
                    "interpolation is 1 (multilinear) or 2 (cubic), not " + std::to_string(value));
  }
  if (status == fmi3::kOK) int_[vr] = static_cast<std::int32_t>(value);
  return status;
}

fmi3::Status Instance::GetInteger(fmi3::ValueReference vr, std::int32_t* value) {
  if (vr < kNumVariables && Variables()[vr].type == Type::kEnumeration) {
    std::int64_t wide = 0;
    const fmi3::Status status = GetInt64(vr, &wide);
    *value = static_cast<std::int32_t>(wide);
    return status;
  }
  return GetInt32(vr, value);
}

fmi3::Status Instance::SetInteger(fmi3::ValueReference vr, std::int32_t value) {
  return SetInt64(vr, value);  // the enumeration is the only settable integer
}

fmi3::Status Instance::GetString(fmi3::ValueReference vr, const char** value) {
  const fmi3::Status status = CheckAccess("get", vr, static_cast<int>(Type::kString), false);
  if (status == fmi3::kOK) *value = table_[vr == kRightTable ? 0 : 1].c_str();
  return status;
}

fmi3::Status Instance::SetString(fmi3::ValueReference vr, const char* value) {
  fmi3::Status status = CheckAccess("set", vr, static_cast<int>(Type::kString), true);
  if (status == fmi3::kOK && value == nullptr) status = Refuse("set", "NULL string");
  if (status == fmi3::kOK) table_[vr == kRightTable ? 0 : 1] = value;
  return status;
}

// ---- the tables and the lookup ---------------------------------------------------------------

std::string Instance::TablePath(const std::string& name) const {
  return !name.empty() && name[0] == '/' ? name : resources_ + name;
}

fmi3::Status Instance::Load() {
  const std::string names[2] = {table_[1], table_[0]};  // [WRC_LEFT], [WRC_RIGHT]
  if (names[WRC_RIGHT].empty()) return Refuse("loading the tables", "right_table is empty");
  for (int side : {WRC_LEFT, WRC_RIGHT}) {
    if (names[side].empty()) continue;
    const std::string path = TablePath(names[side]);
    if (wrc_table_open(path.c_str(), &tables_[side]) != 0 ||
        wrc_table_set_interpolation(tables_[side], int_[kInterpolation] == kInterpolationCubic
                                                       ? WRC_INTERP_CUBIC
                                                       : WRC_INTERP_LINEAR) != 0) {
      const std::string reason = wrc_last_error();
      Unload();
      return Refuse("loading the tables", reason);
    }
  }
  if (wrc_wheelset_create(tables_[WRC_LEFT], tables_[WRC_RIGHT], &wheelset_) != 0) {
    const std::string reason = wrc_last_error();
    Unload();
    return Refuse("loading the tables", reason);
  }
  const fmi3::ValueReference origin[2] = {kLeftRailOriginY, kRightRailOriginY};
  for (int side : {WRC_LEFT, WRC_RIGHT}) {
    wrc_wheelset_set_rail_origin(wheelset_, side, 1000.0 * real_[origin[side]],
                                 1000.0 * real_[origin[side] + 1]);
  }
  return fmi3::kOK;
}

void Instance::Unload() {
  wrc_wheelset_destroy(wheelset_);
  wheelset_ = nullptr;
  for (wrc_table*& table : tables_) {
    wrc_table_close(table);
    table = nullptr;
  }
}

fmi3::Status Instance::Evaluate() {
  if (wheelset_ == nullptr) {
    const fmi3::Status status = Load();
    if (status != fmi3::kOK) return status;
  }
  if (!dirty_) return int_[kStatus] < 0 ? fmi3::kError : fmi3::kOK;
  wrc_wheelset_state state;
  wrc_wheelset_state_init(&state);
  double* const fields[] = {&state.y,
                            &state.z,
                            &state.roll,
                            &state.yaw,
                            &state.vy,
                            &state.vroll,
                            &state.vyaw,
                            &state.omega,
                            &state.velocity,
                            &state.fz[WRC_LEFT],
                            &state.fz[WRC_RIGHT],
                            &state.mu[WRC_LEFT],
                            &state.mu[WRC_RIGHT]};
  for (fmi3::ValueReference vr = kY; vr <= kRightMu; ++vr) {
    *fields[vr - kY] = real_[vr] * Variables()[vr].scale;
  }
  wrc_wheelset_result result;
  const int status = wrc_wheelset_eval(wheelset_, &state, &result);
  WriteOutputs(result, status);
  dirty_ = false;
  if (status < 0) return Refuse("the wheelset lookup", wrc_last_error());
  return fmi3::kOK;
}

void Instance::WriteOutputs(const wrc_wheelset_result& result, int status) {
  const auto& vars = Variables();
  auto put = [&](fmi3::ValueReference vr, double runtime_value) {
    real_[vr] = status < 0 ? NAN : runtime_value / vars[vr].scale;
  };
  const fmi3::ValueReference first[2] = {kLeftFx, kRightFx};
  for (int side : {WRC_LEFT, WRC_RIGHT}) {
    const wrc_wheel_contact& c = result.wheel[side];
    const fmi3::ValueReference vr = first[side];
    for (int i = 0; i < 3; ++i) {
      put(vr + i, c.force[i]);
      put(vr + 3 + i, c.moment[i]);
    }
    put(vr + 6, c.contact_y);
    put(vr + 7, c.contact_angle);
    put(vr + 8, c.t_gamma);
    int_[vr + kFlagsOffset] = status < 0 ? 0 : c.flags;
  }
  for (int i = 0; i < 3; ++i) {
    put(kWheelsetFx + i, result.force[i]);
    put(kWheelsetFx + 3 + i, result.moment[i]);
  }
  int_[kStatus] = status;
}

}  // namespace wrc::fmu
