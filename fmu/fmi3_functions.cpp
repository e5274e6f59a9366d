// The FMI 3.0 C API of the wheelset FMU (co-simulation): every function of the standard is
// exported, those of the interfaces and capabilities the FMU does not declare (model exchange,
// scheduled execution, event mode, FMU state, derivatives, clocks) as refusals that return
// fmi3Error, so that an importer which binds every symbol finds them. No exception crosses the
// C boundary: one that reaches it is logged and returned as fmi3Error (fmi3Fatal when memory
// ran out).

#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <utility>

#include "fmu/c_boundary.h"
#include "fmu/fmi3_types.h"
#include "fmu/instance.h"
#include "fmu/variables.h"

// The C API below is written in the standard's type names.
using wrc::fmu::Instance;
using wrc::fmu::fmi3::Binary, wrc::fmu::fmi3::Boolean, wrc::fmu::fmi3::Byte, wrc::fmu::fmi3::Clock;
using wrc::fmu::fmi3::ClockUpdateCallback, wrc::fmu::fmi3::DependencyKind;
using wrc::fmu::fmi3::Float32, wrc::fmu::fmi3::Float64, wrc::fmu::fmi3::FMUState;
using wrc::fmu::fmi3::InstanceEnvironment, wrc::fmu::fmi3::IntermediateUpdateCallback;
using wrc::fmu::fmi3::Int16, wrc::fmu::fmi3::Int32, wrc::fmu::fmi3::Int64, wrc::fmu::fmi3::Int8;
using wrc::fmu::fmi3::IntervalQualifier, wrc::fmu::fmi3::LockPreemptionCallback;
using wrc::fmu::fmi3::kError, wrc::fmu::fmi3::kFatal, wrc::fmu::fmi3::kOK;
using wrc::fmu::fmi3::LogMessageCallback, wrc::fmu::fmi3::Status, wrc::fmu::fmi3::String;
using wrc::fmu::fmi3::UInt16, wrc::fmu::fmi3::UInt32, wrc::fmu::fmi3::UInt64, wrc::fmu::fmi3::UInt8;
using wrc::fmu::fmi3::UnlockPreemptionCallback, wrc::fmu::fmi3::ValueReference;

using wrc::fmu::Guard, wrc::fmu::NoVariablesOfType, wrc::fmu::Unsupported;

namespace {

// Get or Set of scalars: FMI 3.0 passes the number of values too, one per reference here.
template <typename Access>
Status Each(void* instance, const char* function, const ValueReference vrs[], size_t n,
            size_t n_values, Access&& access) {
  if (n != n_values) {
    return Guard(instance, function, [&](Instance& i) {
      return i.Refuse(function, "nValues differs from nValueReferences");
    });
  }
  return wrc::fmu::Each(instance, function, vrs, n, access);
}

}  // namespace

#define WRC_FMI3 extern "C" __attribute__((visibility("default")))

// ---- common functions ----------------------------------------------------------------------

WRC_FMI3 const char* fmi3GetVersion(void) { return "3.0"; }

WRC_FMI3 Status fmi3SetDebugLogging(Instance* instance, Boolean on, size_t, const String[]) {
  return Guard(instance, "fmi3SetDebugLogging", [&](Instance& i) {
    i.SetLogging(on);
    return kOK;
  });
}

WRC_FMI3 void* fmi3InstantiateCoSimulation(String name, String token, String resources, Boolean,
                                           Boolean logging_on, Boolean event_mode_used, Boolean,
                                           const ValueReference[], size_t,
                                           InstanceEnvironment environment,
                                           LogMessageCallback logger, IntermediateUpdateCallback) {
  auto refuse = [&](const std::string& why) -> void* {
    if (logger != nullptr) {
      logger(environment, kError, "logStatusError",
             ("fmi3InstantiateCoSimulation: " + why).c_str());
    }
    return nullptr;
  };
  if (token == nullptr || std::strcmp(token, wrc::fmu::kInstantiationToken) != 0) {
    return refuse("the instantiation token is not this FMU's (" +
                  std::string(wrc::fmu::kInstantiationToken) + ")");
  }
  if (resources == nullptr || resources[0] == '\0') return refuse("no resource path");
  if (event_mode_used) return refuse("the FMU has no event mode");
  try {
    wrc::fmu::LogSink sink;
    if (logger != nullptr) {
      sink = [logger, environment](Status status, const char* category, const char* message) {
        logger(environment, status, category, message);
      };
    }
    return new Instance(name != nullptr ? name : "", resources, logging_on, std::move(sink));
  } catch (const std::exception& e) {
    return refuse(e.what());
  }
}

WRC_FMI3 void* fmi3InstantiateModelExchange(String, String, String, Boolean, Boolean,
                                            InstanceEnvironment environment,
                                            LogMessageCallback logger) {
  if (logger != nullptr) {
    logger(environment, kError, "logStatusError", "the FMU implements co-simulation only");
  }
  return nullptr;
}

WRC_FMI3 void* fmi3InstantiateScheduledExecution(String, String, String, Boolean, Boolean,
                                                 InstanceEnvironment environment,
                                                 LogMessageCallback logger, ClockUpdateCallback,
                                                 LockPreemptionCallback, UnlockPreemptionCallback) {
  return fmi3InstantiateModelExchange(nullptr, nullptr, nullptr, false, false, environment, logger);
}

WRC_FMI3 void fmi3FreeInstance(Instance* instance) { delete instance; }

WRC_FMI3 Status fmi3EnterInitializationMode(Instance* instance, Boolean, Float64, Float64, Boolean,
                                            Float64) {
  return Guard(instance, "fmi3EnterInitializationMode",
               [](Instance& i) { return i.EnterInitialization(); });
}

WRC_FMI3 Status fmi3ExitInitializationMode(Instance* instance) {
  return Guard(instance, "fmi3ExitInitializationMode",
               [](Instance& i) { return i.ExitInitialization(); });
}

WRC_FMI3 Status fmi3EnterEventMode(Instance* instance) {
  return Unsupported(instance, "fmi3EnterEventMode", "the FMU has no event mode");
}

WRC_FMI3 Status fmi3Terminate(Instance* instance) {
  return Guard(instance, "fmi3Terminate", [](Instance& i) { return i.Terminate(); });
}

WRC_FMI3 Status fmi3Reset(Instance* instance) {
  return Guard(instance, "fmi3Reset", [](Instance& i) { return i.Reset(); });
}

// ---- getting and setting variables -----------------------------------------------------------

WRC_FMI3 Status fmi3GetFloat64(Instance* instance, const ValueReference vrs[], size_t n,
                               Float64 values[], size_t n_values) {
  return Each(
      instance, "fmi3GetFloat64", vrs, n, n_values,
      [&](Instance& i, ValueReference vr, size_t k) { return i.GetFloat64(vr, &values[k]); });
}

WRC_FMI3 Status fmi3SetFloat64(Instance* instance, const ValueReference vrs[], size_t n,
                               const Float64 values[], size_t n_values) {
  return Each(
      instance, "fmi3SetFloat64", vrs, n, n_values,
      [&](Instance& i, ValueReference vr, size_t k) { return i.SetFloat64(vr, values[k]); });
}

WRC_FMI3 Status fmi3GetInt32(Instance* instance, const ValueReference vrs[], size_t n,
                             Int32 values[], size_t n_values) {
  return Each(instance, "fmi3GetInt32", vrs, n, n_values,
              [&](Instance& i, ValueReference vr, size_t k) { return i.GetInt32(vr, &values[k]); });
}

WRC_FMI3 Status fmi3GetInt64(Instance* instance, const ValueReference vrs[], size_t n,
                             Int64 values[], size_t n_values) {
  return Each(instance, "fmi3GetInt64", vrs, n, n_values,
              [&](Instance& i, ValueReference vr, size_t k) { return i.GetInt64(vr, &values[k]); });
}

WRC_FMI3 Status fmi3SetInt64(Instance* instance, const ValueReference vrs[], size_t n,
                             const Int64 values[], size_t n_values) {
  return Each(instance, "fmi3SetInt64", vrs, n, n_values,
              [&](Instance& i, ValueReference vr, size_t k) { return i.SetInt64(vr, values[k]); });
}

WRC_FMI3 Status fmi3GetString(Instance* instance, const ValueReference vrs[], size_t n,
                              String values[], size_t n_values) {
  return Each(
      instance, "fmi3GetString", vrs, n, n_values,
      [&](Instance& i, ValueReference vr, size_t k) { return i.GetString(vr, &values[k]); });
}

WRC_FMI3 Status fmi3SetString(Instance* instance, const ValueReference vrs[], size_t n,
                              const String values[], size_t n_values) {
  return Each(instance, "fmi3SetString", vrs, n, n_values,
              [&](Instance& i, ValueReference vr, size_t k) { return i.SetString(vr, values[k]); });
}

WRC_FMI3 Status fmi3SetInt32(Instance* instance, const ValueReference[], size_t n, const Int32[],
                             size_t) {
  return Guard(instance, "fmi3SetInt32", [&](Instance& i) {
    return n == 0 ? kOK : i.Refuse("fmi3SetInt32", "the Int32 variables are outputs");
  });
}

#define WRC_FMI3_NO_TYPE(Type)                                                                \
  WRC_FMI3 Status fmi3Get##Type(Instance* instance, const ValueReference[], size_t n, Type[], \
                                size_t) {                                                     \
    return NoVariablesOfType(instance, "fmi3Get" #Type, n);                                   \
  }                                                                                           \
  WRC_FMI3 Status fmi3Set##Type(Instance* instance, const ValueReference[], size_t n,         \
                                const Type[], size_t) {                                       \
    return NoVariablesOfType(instance, "fmi3Set" #Type, n);                                   \
  }
WRC_FMI3_NO_TYPE(Float32)
WRC_FMI3_NO_TYPE(Int8)
WRC_FMI3_NO_TYPE(UInt8)
WRC_FMI3_NO_TYPE(Int16)
WRC_FMI3_NO_TYPE(UInt16)
WRC_FMI3_NO_TYPE(UInt32)
WRC_FMI3_NO_TYPE(UInt64)
WRC_FMI3_NO_TYPE(Boolean)
#undef WRC_FMI3_NO_TYPE

WRC_FMI3 Status fmi3GetBinary(Instance* instance, const ValueReference[], size_t n, size_t[],
                              Binary[], size_t) {
  return NoVariablesOfType(instance, "fmi3GetBinary", n);
}
WRC_FMI3 Status fmi3SetBinary(Instance* instance, const ValueReference[], size_t n, const size_t[],
                              const Binary[], size_t) {
  return NoVariablesOfType(instance, "fmi3SetBinary", n);
}
WRC_FMI3 Status fmi3GetClock(Instance* instance, const ValueReference[], size_t n, Clock[]) {
  return NoVariablesOfType(instance, "fmi3GetClock", n);
}
WRC_FMI3 Status fmi3SetClock(Instance* instance, const ValueReference[], size_t n, const Clock[]) {
  return NoVariablesOfType(instance, "fmi3SetClock", n);
}

// ---- co-simulation ---------------------------------------------------------------------------

WRC_FMI3 Status fmi3DoStep(Instance* instance, Float64 time, Float64 step, Boolean,
                           Boolean* event_handling_needed, Boolean* terminate,
                           Boolean* early_return, Float64* last_successful_time) {
  return Guard(instance, "fmi3DoStep", [&](Instance& i) {
    if (event_handling_needed == nullptr || terminate == nullptr || early_return == nullptr ||
        last_successful_time == nullptr) {
      return i.Refuse("fmi3DoStep", "NULL output argument");
    }
    const Status status = i.DoStep(time, step);
    *event_handling_needed = false;
    *terminate = false;
    *early_return = false;
    *last_successful_time = status < kError ? time + step : time;
    return status;
  });
}

WRC_FMI3 Status fmi3EnterStepMode(Instance* instance) {
  return Unsupported(instance, "fmi3EnterStepMode", "the FMU has no event mode");
}

WRC_FMI3 Status fmi3GetOutputDerivatives(Instance* instance, const ValueReference[], size_t,
                                         const Int32[], Float64[], size_t) {
  return Unsupported(instance, "fmi3GetOutputDerivatives", "maxOutputDerivativeOrder is 0");
}

// ---- what the FMU does not provide -----------------------------------------------------------

#define WRC_FMI3_UNSUPPORTED(name, why, ...)              \
  WRC_FMI3 Status name(Instance* instance, __VA_ARGS__) { \
    return Unsupported(instance, #name, why);             \
  }
#define WRC_NO_STATE "canGetAndSetFMUState is false"
#define WRC_NO_DERIVATIVES "the FMU provides no derivatives"
#define WRC_NO_CLOCKS "the FMU has no clocks"
#define WRC_NO_ME "the FMU implements co-simulation only"
WRC_FMI3_UNSUPPORTED(fmi3GetNumberOfVariableDependencies, "every output depends on every input",
                     ValueReference, size_t*)
WRC_FMI3_UNSUPPORTED(fmi3GetVariableDependencies, "every output depends on every input",
                     ValueReference, size_t[], ValueReference[], size_t[], DependencyKind[], size_t)
WRC_FMI3_UNSUPPORTED(fmi3GetFMUState, WRC_NO_STATE, FMUState*)
WRC_FMI3_UNSUPPORTED(fmi3SetFMUState, WRC_NO_STATE, FMUState)
WRC_FMI3_UNSUPPORTED(fmi3FreeFMUState, WRC_NO_STATE, FMUState*)
WRC_FMI3_UNSUPPORTED(fmi3SerializedFMUStateSize, WRC_NO_STATE, FMUState, size_t*)
WRC_FMI3_UNSUPPORTED(fmi3SerializeFMUState, WRC_NO_STATE, FMUState, Byte[], size_t)
WRC_FMI3_UNSUPPORTED(fmi3DeserializeFMUState, WRC_NO_STATE, const Byte[], size_t, FMUState*)
WRC_FMI3_UNSUPPORTED(fmi3GetDirectionalDerivative, WRC_NO_DERIVATIVES, const ValueReference[],
                     size_t, const ValueReference[], size_t, const Float64[], size_t, Float64[],
                     size_t)
WRC_FMI3_UNSUPPORTED(fmi3GetAdjointDerivative, WRC_NO_DERIVATIVES, const ValueReference[], size_t,
                     const ValueReference[], size_t, const Float64[], size_t, Float64[], size_t)
WRC_FMI3_UNSUPPORTED(fmi3GetIntervalDecimal, WRC_NO_CLOCKS, const ValueReference[], size_t,
                     Float64[], IntervalQualifier[])
WRC_FMI3_UNSUPPORTED(fmi3GetIntervalFraction, WRC_NO_CLOCKS, const ValueReference[], size_t,
                     UInt64[], UInt64[], IntervalQualifier[])
WRC_FMI3_UNSUPPORTED(fmi3GetShiftDecimal, WRC_NO_CLOCKS, const ValueReference[], size_t, Float64[])
WRC_FMI3_UNSUPPORTED(fmi3GetShiftFraction, WRC_NO_CLOCKS, const ValueReference[], size_t, UInt64[],
                     UInt64[])
WRC_FMI3_UNSUPPORTED(fmi3SetIntervalDecimal, WRC_NO_CLOCKS, const ValueReference[], size_t,
                     const Float64[])
WRC_FMI3_UNSUPPORTED(fmi3SetIntervalFraction, WRC_NO_CLOCKS, const ValueReference[], size_t,
                     const UInt64[], const UInt64[])
WRC_FMI3_UNSUPPORTED(fmi3SetShiftDecimal, WRC_NO_CLOCKS, const ValueReference[], size_t,
                     const Float64[])
WRC_FMI3_UNSUPPORTED(fmi3SetShiftFraction, WRC_NO_CLOCKS, const ValueReference[], size_t,
                     const UInt64[], const UInt64[])
WRC_FMI3_UNSUPPORTED(fmi3UpdateDiscreteStates, "the FMU has no event mode", Boolean*, Boolean*,
                     Boolean*, Boolean*, Boolean*, Float64*)
WRC_FMI3_UNSUPPORTED(fmi3CompletedIntegratorStep, WRC_NO_ME, Boolean, Boolean*, Boolean*)
WRC_FMI3_UNSUPPORTED(fmi3SetTime, WRC_NO_ME, Float64)
WRC_FMI3_UNSUPPORTED(fmi3SetContinuousStates, WRC_NO_ME, const Float64[], size_t)
WRC_FMI3_UNSUPPORTED(fmi3GetContinuousStateDerivatives, WRC_NO_ME, Float64[], size_t)
WRC_FMI3_UNSUPPORTED(fmi3GetEventIndicators, WRC_NO_ME, Float64[], size_t)
WRC_FMI3_UNSUPPORTED(fmi3GetContinuousStates, WRC_NO_ME, Float64[], size_t)
WRC_FMI3_UNSUPPORTED(fmi3GetNominalsOfContinuousStates, WRC_NO_ME, Float64[], size_t)
WRC_FMI3_UNSUPPORTED(fmi3GetNumberOfEventIndicators, WRC_NO_ME, size_t*)
WRC_FMI3_UNSUPPORTED(fmi3GetNumberOfContinuousStates, WRC_NO_ME, size_t*)
WRC_FMI3_UNSUPPORTED(fmi3ActivateModelPartition, "the FMU has no scheduled execution",
                     ValueReference, Float64)

#define WRC_FMI3_UNSUPPORTED_VOID(name, why) \
  WRC_FMI3 Status name(Instance* instance) { return Unsupported(instance, #name, why); }
WRC_FMI3_UNSUPPORTED_VOID(fmi3EnterConfigurationMode, "the FMU has no structural parameters")
WRC_FMI3_UNSUPPORTED_VOID(fmi3ExitConfigurationMode, "the FMU has no structural parameters")
WRC_FMI3_UNSUPPORTED_VOID(fmi3EvaluateDiscreteStates, "the FMU has no event mode")
WRC_FMI3_UNSUPPORTED_VOID(fmi3EnterContinuousTimeMode, WRC_NO_ME)
