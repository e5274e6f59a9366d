// The FMI 2.0 C API of the wheelset FMU (co-simulation), for importers that take FMI 2.0 only:
// the same instance as the FMI 3.0 functions (instance.h) behind the older names. As there,
// every function of the co-simulation interface is exported, the unprovided ones as refusals,
// and no exception crosses the C boundary.

#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <utility>

#include "fmu/c_boundary.h"
#include "fmu/fmi2_types.h"
#include "fmu/instance.h"
#include "fmu/variables.h"

// The C API below is written in the standard's type names.
using wrc::fmu::Instance;
using wrc::fmu::fmi2::Boolean, wrc::fmu::fmi2::Byte, wrc::fmu::fmi2::CallbackFunctions;
using wrc::fmu::fmi2::FMUstate, wrc::fmu::fmi2::Integer, wrc::fmu::fmi2::Real;
using wrc::fmu::fmi2::Status, wrc::fmu::fmi2::StatusKind, wrc::fmu::fmi2::String;
using wrc::fmu::fmi2::ValueReference;
namespace fmi3 = wrc::fmu::fmi3;

namespace {

Status From(fmi3::Status s) { return static_cast<Status>(s); }

// A file: URI (file:///a/b, file:/a/b, file://localhost/a/b, %XX escapes) as a path.
std::string PathOfUri(const char* uri) {
  std::string text = uri;
  if (text.rfind("file://localhost/", 0) == 0)
    text.erase(0, 16);
  else if (text.rfind("file:///", 0) == 0)
    text.erase(0, 7);
  else if (text.rfind("file:/", 0) == 0)
    text.erase(0, 5);
  else
    return "";
  std::string path;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '%' && i + 2 < text.size()) {
      path += static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      path += text[i];
    }
  }
  return path;
}

// The shared boundary (c_boundary.h) with FMI 2.0's status type.
template <typename Body>
Status Guard2(void* instance, const char* function, Body&& body) {
  return From(wrc::fmu::Guard(instance, function, body));
}

template <typename Access>
Status Each2(void* instance, const char* function, const ValueReference vrs[], size_t n,
             Access&& access) {
  return From(wrc::fmu::Each(instance, function, vrs, n, access));
}

Status Unsupported2(void* instance, const char* function, const char* why) {
  return From(wrc::fmu::Unsupported(instance, function, why));
}

}  // namespace

#define WRC_FMI2 extern "C" __attribute__((visibility("default")))

WRC_FMI2 const char* fmi2GetTypesPlatform(void) { return "default"; }
WRC_FMI2 const char* fmi2GetVersion(void) { return "2.0"; }

WRC_FMI2 Status fmi2SetDebugLogging(Instance* instance, Boolean on, size_t, const String[]) {
  return Guard2(instance, "fmi2SetDebugLogging", [&](Instance& i) {
    i.SetLogging(on != 0);
    return fmi3::kOK;
  });
}

WRC_FMI2 void* fmi2Instantiate(String name, wrc::fmu::fmi2::Type type, String guid,
                               String resource_uri, const CallbackFunctions* functions, Boolean,
                               Boolean logging_on) {
  const std::string instance_name = name != nullptr ? name : "";
  const auto logger = functions != nullptr ? functions->logger : nullptr;
  const auto environment = functions != nullptr ? functions->component_environment : nullptr;
  auto refuse = [&](const std::string& why) -> void* {
    if (logger != nullptr) {
      logger(environment, instance_name.c_str(), wrc::fmu::fmi2::kError, "logStatusError", "%s",
             ("fmi2Instantiate: " + why).c_str());
    }
    return nullptr;
  };
  if (type != wrc::fmu::fmi2::kCoSimulation) return refuse("the FMU implements co-simulation only");
  if (guid == nullptr || std::strcmp(guid, wrc::fmu::kInstantiationToken) != 0) {
    return refuse("the GUID is not this FMU's (" + std::string(wrc::fmu::kInstantiationToken) +
                  ")");
  }
  const std::string resources = resource_uri != nullptr ? PathOfUri(resource_uri) : "";
  if (resources.empty()) return refuse("the resource location is not a file: URI");
  wrc::fmu::LogSink sink;
  if (logger != nullptr) {
    sink = [logger, environment, instance_name](fmi3::Status status, const char* category,
                                                const char* message) {
      logger(environment, instance_name.c_str(), static_cast<Status>(status), category, "%s",
             message);
    };
  }
  try {
    return new Instance(instance_name, resources, logging_on != 0, std::move(sink));
  } catch (const std::exception& e) {
    return refuse(e.what());
  }
}

WRC_FMI2 void fmi2FreeInstance(Instance* instance) { delete instance; }

WRC_FMI2 Status fmi2SetupExperiment(Instance* instance, Boolean, Real, Real, Boolean, Real) {
  return Guard2(instance, "fmi2SetupExperiment", [](Instance&) { return fmi3::kOK; });
}
WRC_FMI2 Status fmi2EnterInitializationMode(Instance* instance) {
  return Guard2(instance, "fmi2EnterInitializationMode",
                [](Instance& i) { return i.EnterInitialization(); });
}
WRC_FMI2 Status fmi2ExitInitializationMode(Instance* instance) {
  return Guard2(instance, "fmi2ExitInitializationMode",
                [](Instance& i) { return i.ExitInitialization(); });
}
WRC_FMI2 Status fmi2Terminate(Instance* instance) {
  return Guard2(instance, "fmi2Terminate", [](Instance& i) { return i.Terminate(); });
}
WRC_FMI2 Status fmi2Reset(Instance* instance) {
  return Guard2(instance, "fmi2Reset", [](Instance& i) { return i.Reset(); });
}

WRC_FMI2 Status fmi2GetReal(Instance* instance, const ValueReference vrs[], size_t n,
                            Real values[]) {
  return Each2(instance, "fmi2GetReal", vrs, n, [&](Instance& i, ValueReference vr, size_t k) {
    return i.GetFloat64(vr, &values[k]);
  });
}
WRC_FMI2 Status fmi2SetReal(Instance* instance, const ValueReference vrs[], size_t n,
                            const Real values[]) {
  return Each2(instance, "fmi2SetReal", vrs, n, [&](Instance& i, ValueReference vr, size_t k) {
    return i.SetFloat64(vr, values[k]);
  });
}
WRC_FMI2 Status fmi2GetInteger(Instance* instance, const ValueReference vrs[], size_t n,
                               Integer values[]) {
  return Each2(instance, "fmi2GetInteger", vrs, n, [&](Instance& i, ValueReference vr, size_t k) {
    return i.GetInteger(vr, &values[k]);
  });
}
WRC_FMI2 Status fmi2SetInteger(Instance* instance, const ValueReference vrs[], size_t n,
                               const Integer values[]) {
  return Each2(instance, "fmi2SetInteger", vrs, n, [&](Instance& i, ValueReference vr, size_t k) {
    return i.SetInteger(vr, values[k]);
  });
}
WRC_FMI2 Status fmi2GetString(Instance* instance, const ValueReference vrs[], size_t n,
                              String values[]) {
  return Each2(instance, "fmi2GetString", vrs, n, [&](Instance& i, ValueReference vr, size_t k) {
    return i.GetString(vr, &values[k]);
  });
}
WRC_FMI2 Status fmi2SetString(Instance* instance, const ValueReference vrs[], size_t n,
                              const String values[]) {
  return Each2(instance, "fmi2SetString", vrs, n, [&](Instance& i, ValueReference vr, size_t k) {
    return i.SetString(vr, values[k]);
  });
}
WRC_FMI2 Status fmi2GetBoolean(Instance* instance, const ValueReference[], size_t n, Boolean[]) {
  return From(wrc::fmu::NoVariablesOfType(instance, "fmi2GetBoolean", n));
}
WRC_FMI2 Status fmi2SetBoolean(Instance* instance, const ValueReference[], size_t n,
                               const Boolean[]) {
  return From(wrc::fmu::NoVariablesOfType(instance, "fmi2SetBoolean", n));
}

WRC_FMI2 Status fmi2DoStep(Instance* instance, Real time, Real step, Boolean) {
  return Guard2(instance, "fmi2DoStep", [&](Instance& i) { return i.DoStep(time, step); });
}
WRC_FMI2 Status fmi2CancelStep(Instance* instance) {
  return Unsupported2(instance, "fmi2CancelStep", "fmi2DoStep never returns fmi2Pending");
}

#define WRC_FMI2_UNSUPPORTED(name, why, ...)              \
  WRC_FMI2 Status name(Instance* instance, __VA_ARGS__) { \
    return Unsupported2(instance, #name, why);            \
  }
#define WRC_NO_STATE "canGetAndSetFMUstate is false"
WRC_FMI2_UNSUPPORTED(fmi2GetFMUstate, WRC_NO_STATE, FMUstate*)
WRC_FMI2_UNSUPPORTED(fmi2SetFMUstate, WRC_NO_STATE, FMUstate)
WRC_FMI2_UNSUPPORTED(fmi2FreeFMUstate, WRC_NO_STATE, FMUstate*)
WRC_FMI2_UNSUPPORTED(fmi2SerializedFMUstateSize, WRC_NO_STATE, FMUstate, size_t*)
WRC_FMI2_UNSUPPORTED(fmi2SerializeFMUstate, WRC_NO_STATE, FMUstate, Byte[], size_t)
WRC_FMI2_UNSUPPORTED(fmi2DeSerializeFMUstate, WRC_NO_STATE, const Byte[], size_t, FMUstate*)
WRC_FMI2_UNSUPPORTED(fmi2GetDirectionalDerivative, "the FMU provides no derivatives",
                     const ValueReference[], size_t, const ValueReference[], size_t, const Real[],
                     Real[])
WRC_FMI2_UNSUPPORTED(fmi2SetRealInputDerivatives, "canInterpolateInputs is false",
                     const ValueReference[], size_t, const Integer[], const Real[])
WRC_FMI2_UNSUPPORTED(fmi2GetRealOutputDerivatives, "maxOutputDerivativeOrder is 0",
                     const ValueReference[], size_t, const Integer[], Real[])
WRC_FMI2_UNSUPPORTED(fmi2GetStatus, "fmi2DoStep never returns fmi2Pending", const StatusKind,
                     Status*)
WRC_FMI2_UNSUPPORTED(fmi2GetRealStatus, "fmi2DoStep never returns fmi2Pending", const StatusKind,
                     Real*)
WRC_FMI2_UNSUPPORTED(fmi2GetIntegerStatus, "fmi2DoStep never returns fmi2Pending", const StatusKind,
                     Integer*)
WRC_FMI2_UNSUPPORTED(fmi2GetBooleanStatus, "fmi2DoStep never returns fmi2Pending", const StatusKind,
                     Boolean*)
WRC_FMI2_UNSUPPORTED(fmi2GetStringStatus, "fmi2DoStep never returns fmi2Pending", const StatusKind,
                     String*)
