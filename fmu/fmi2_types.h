#pragma once
// The types of the FMI 2.0 C API that the wheelset FMU exports and its tests import, as the
// standard specifies them (FMI 2.0.5, section 2.1.2 "Platform Dependent Definitions" and 2.1.3
// "Status Returned by Functions"), declared here for the reason fmi3_types.h gives.

#include <cstddef>

namespace wrc::fmu::fmi2 {

using Component = void*;
using ComponentEnvironment = void*;
using FMUstate = void*;
using ValueReference = unsigned int;
using Real = double;
using Integer = int;
using Boolean = int;  // fmi2True 1, fmi2False 0
using Char = char;
using String = const Char*;
using Byte = char;

enum Status : int { kOK = 0, kWarning = 1, kDiscard = 2, kError = 3, kFatal = 4, kPending = 5 };
enum Type : int { kModelExchange = 0, kCoSimulation = 1 };
enum StatusKind : int { kDoStepStatus, kPendingStatus, kLastSuccessfulTime, kTerminated };

/// The importer's logger: the message is a printf format, its arguments follow.
using CallbackLogger = void (*)(ComponentEnvironment, String instance_name, Status, String category,
                                String message, ...);
struct CallbackFunctions {
  CallbackLogger logger;
  void* (*allocate_memory)(std::size_t n, std::size_t size);
  void (*free_memory)(void*);
  void (*step_finished)(ComponentEnvironment, Status);
  ComponentEnvironment component_environment;
};

}  // namespace wrc::fmu::fmi2
