#pragma once
// The wheelset FMU's variables: one list that the FMU's binary serves and `wrc fmu` writes into
// modelDescription.xml, so that a value reference, a name, a unit and its scale to the runtime's
// units have one home. The FMU speaks SI units (m, N, N·m), as FMI importers expect; the runtime
// speaks mm and N·mm (include/wrc/runtime.h).

#include <cstdint>
#include <string>
#include <vector>

namespace wrc::fmu {

/// What the binary and the modelDescription.xml must agree on: a new variable layout changes
/// it, so that an FMU whose XML and binary come from different layouts refuses to start.
inline constexpr const char* kInstantiationToken = "{wrc-wheelset-fmu-layout-1}";
inline constexpr const char* kModelIdentifier = "wrc_wheelset";

enum class Type { kFloat64, kInt32, kString, kEnumeration };
enum class Causality { kIndependent, kParameter, kInput, kOutput };

struct Variable {
  std::uint32_t value_reference;  ///< Its index in Variables().
  std::string name;
  Type type;
  Causality causality;
  const char* unit;  ///< SI unit name of UnitDefinitions, "" for none.
  /// Runtime units per FMU unit (1000 for m → mm and N·m → N·mm, else 1).
  double scale;
  std::string description;
};

/// Value references, in the order of Variables().
enum Vr : std::uint32_t {
  kTime,
  kRightTable,
  kLeftTable,
  kInterpolation,
  kLeftRailOriginY,
  kLeftRailOriginZ,
  kRightRailOriginY,
  kRightRailOriginZ,
  // Inputs: the wheelset state of wrc_wheelset_state.
  kY,
  kZ,
  kRoll,
  kYaw,
  kVy,
  kVroll,
  kVyaw,
  kOmega,
  kVelocity,
  kLeftWheelLoad,
  kRightWheelLoad,
  kLeftMu,
  kRightMu,
  // Outputs per wheel: kLeftFx + k and kRightFx + k for the k-th of kWheelOutputs.
  kLeftFx,
  kRightFx = kLeftFx + 10,
  // Outputs on the wheelset.
  kWheelsetFx = kRightFx + 10,
  kStatus = kWheelsetFx + 6,
  kNumVariables
};

/// The values of the interpolation enumeration (FMI enumerations count from 1; the runtime's
/// WRC_INTERP_* from 0).
inline constexpr int kInterpolationLinear = 1;
inline constexpr int kInterpolationCubic = 2;

/// Per wheel: fx fy fz mx my mz contact_y contact_angle t_gamma flags.
inline constexpr int kWheelOutputs = 10;
inline constexpr int kFlagsOffset = 9;

/// The type's name in FMI 3.0 ("Float64", "Int32", "String", "Enumeration").
const char* TypeName(Type type);

/// All kNumVariables variables, indexed by value reference.
const std::vector<Variable>& Variables();

}  // namespace wrc::fmu
