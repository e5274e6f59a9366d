#pragma once
// One instance of the wheelset FMU: its variables, its mode in the FMI 3.0 co-simulation state
// machine, and the wheelset of the runtime it evaluates. The wheelset is a stateless algebraic
// unit: its outputs are functions of its inputs, evaluated when an input changed and an output
// is read, or at each fmi3DoStep (allocation-free then).
//
// Methods return an FMI status and report a refusal through the importer's logger; nothing
// throws out of them except std::bad_alloc from the constructor.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fmu/fmi3_types.h"
#include "wrc/runtime.h"

namespace wrc::fmu {

/// Where an instance's messages go: the importer's logger, whichever FMI version's it is.
/// (FMI 2.0 and 3.0 number their statuses OK to Fatal alike.)
using LogSink = std::function<void(fmi3::Status, const char* category, const char* message)>;

class Instance {
 public:
  enum class Mode { kInstantiated, kInitialization, kStep, kTerminated };

  /// Reads the start values from resource_path (the FMU's resources folder). Throws
  /// std::runtime_error naming the problem when they cannot be read.
  Instance(std::string name, std::string resource_path, bool logging, LogSink log);
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  fmi3::Status EnterInitialization();
  fmi3::Status ExitInitialization();
  fmi3::Status DoStep(double time, double step);
  fmi3::Status Terminate();
  fmi3::Status Reset();

  fmi3::Status GetFloat64(fmi3::ValueReference vr, double* value);
  fmi3::Status SetFloat64(fmi3::ValueReference vr, double value);
  fmi3::Status GetInt32(fmi3::ValueReference vr, std::int32_t* value);
  fmi3::Status GetInt64(fmi3::ValueReference vr, std::int64_t* value);
  fmi3::Status SetInt64(fmi3::ValueReference vr, std::int64_t value);
  /// FMI 2.0's Integer functions: the Int32 outputs and the enumeration.
  fmi3::Status GetInteger(fmi3::ValueReference vr, std::int32_t* value);
  fmi3::Status SetInteger(fmi3::ValueReference vr, std::int32_t value);
  fmi3::Status GetString(fmi3::ValueReference vr, const char** value);
  fmi3::Status SetString(fmi3::ValueReference vr, const char* value);

  void SetLogging(bool on) { logging_ = on; }
  /// Reports through the importer's logger: errors always, the rest when logging is on.
  void Log(fmi3::Status status, const std::string& message) const;
  /// Logs "<function>: <message>" as an error and returns fmi3Error.
  fmi3::Status Refuse(const char* function, const std::string& message) const;

 private:
  fmi3::Status CheckAccess(const char* function, fmi3::ValueReference vr, int type, bool set);
  fmi3::Status Evaluate();
  fmi3::Status Load();
  void Unload();
  void ApplyStartValues();
  void WriteOutputs(const wrc_wheelset_result& result, int status);
  std::string TablePath(const std::string& name) const;

  std::string name_, resources_;
  bool logging_;
  LogSink log_;
  Mode mode_ = Mode::kInstantiated;
  std::vector<std::string> start_;  // start value text, by value reference ("" when none)
  std::vector<double> real_;        // Float64 variables in FMU units, by value reference
  std::vector<std::int32_t> int_;   // Int32 and Enumeration variables, by value reference
  std::string table_[2];            // right_table, left_table
  bool dirty_ = true;               // an input changed since the outputs were evaluated
  wrc_table* tables_[2] = {nullptr, nullptr};  // [WRC_LEFT], [WRC_RIGHT]
  wrc_wheelset* wheelset_ = nullptr;
};

}  // namespace wrc::fmu
