#pragma once
// The types of the FMI 3.0 C API that the wheelset FMU exports and its tests import, as the
// standard specifies them (FMI 3.0, section 2.2.2 "Platform Dependent Definitions" and 2.2.3
// "Status Returned by Functions"). Declared here, not included from the standard's headers, so
// that the build needs nothing outside Debian; the names and layouts are the standard's.

#include <cstddef>
#include <cstdint>

namespace wrc::fmu::fmi3 {

using Instance = void*;
using InstanceEnvironment = void*;
using FMUState = void*;
using ValueReference = std::uint32_t;
using Float32 = float;
using Float64 = double;
using Int8 = std::int8_t;
using UInt8 = std::uint8_t;
using Int16 = std::int16_t;
using UInt16 = std::uint16_t;
using Int32 = std::int32_t;
using UInt32 = std::uint32_t;
using Int64 = std::int64_t;
using UInt64 = std::uint64_t;
using Boolean = bool;  // C99 _Bool in the standard's C headers: the same ABI
using Char = char;
using String = const Char*;
using Byte = std::uint8_t;
using Binary = const Byte*;
using Clock = bool;

enum Status : int { kOK = 0, kWarning = 1, kDiscard = 2, kError = 3, kFatal = 4 };
enum DependencyKind : int { kIndependent, kConstant, kFixed, kTunable, kDiscrete, kDependent };
enum IntervalQualifier : int { kNotYetKnown, kUnchanged, kChanged };

using LogMessageCallback = void (*)(InstanceEnvironment, Status, String category, String message);
using IntermediateUpdateCallback = void (*)(InstanceEnvironment, Float64, Boolean, Boolean, Boolean,
                                            Boolean, Boolean*, Float64*);
using ClockUpdateCallback = void (*)(InstanceEnvironment);
using LockPreemptionCallback = void (*)();
using UnlockPreemptionCallback = void (*)();

}  // namespace wrc::fmu::fmi3
