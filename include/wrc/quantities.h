#pragma once
/// @file quantities.h
/// The quantities a table is made of, defined once for every part of wrc: the scene parser
/// admits them, the generator stores them with their units, the runtime's wheelset API mirrors
/// and folds them, and the tools report them (docs/reference/table-layout.md). How an output is
/// taken from a solve is the solver's (OutputValue in wrc/core/wheelrail.h); everything else
/// about a quantity is here. Header-only, no dependencies: the runtime includes it too.
///
/// Adding a table output is an entry in kOutputQuantities and its case in OutputValue.

#include <cstddef>
#include <iterator>
#include <string_view>

namespace wrc {

/// A quantity of a wheelset's state, as seen by one wheel: what a table axis may stand for, and
/// what the wheelset API reads at a table's fixed value when it is not an axis.
struct StateQuantity {
  std::string_view name;
  std::string_view unit;  ///< As stored in a table ("mm", "N", "rad", "rad/s", "mm/s", "-").
  /// Sign under the mirror image in the track's x–z plane: a left wheel is read from a right
  /// wheel's table with its lateral quantities negated.
  double mirror;
  bool scene_axis;  ///< A scene may vary it on a table axis (vroll enters through yaw only).
};

/// In the wheelset API's order. `y_wheel` is the lateral position of the wheel at its contact,
/// y − r0·roll (r0 the nominal radius): a wheelset roll of φ moves the wheel's running surface
/// sideways by about r0·φ at the rail, so the tread-to-flange transition lies at nearly the same
/// y_wheel for every roll, where on a y axis it moves by ±r0·φ. It replaces `y` on a table that
/// also varies roll.
inline constexpr StateQuantity kStateQuantities[] = {
    {"y", "mm", -1.0, true},       {"z", "mm", 1.0, true},     {"fz", "N", 1.0, true},
    {"roll", "rad", -1.0, true},   {"yaw", "rad", -1.0, true}, {"spin", "-", 1.0, true},
    {"omega", "rad/s", 1.0, true}, {"vy", "mm/s", -1.0, true}, {"vroll", "rad/s", -1.0, false},
    {"vyaw", "rad/s", -1.0, true}, {"mu", "-", 1.0, true},     {"y_wheel", "mm", -1.0, true},
};
inline constexpr int kStateQuantityCount = static_cast<int>(std::size(kStateQuantities));

/// What a table stores for an output at a point without contact.
enum class AtNoContact {
  kZero,       ///< no contact, no force (or power, or patch)
  kUndefined,  ///< NaN: a contact location or a patch to judge does not exist
  kSolved,     ///< the solver's value: z with a prescribed fz, fz with a prescribed z
};

/// Whether a scene without `table.outputs` gets the output.
enum class DefaultOutput { kNo, kYes, kWithPrescribedFz };

/// A table output.
struct OutputQuantity {
  std::string_view name;
  std::string_view unit;  ///< As stored in a table ("N", "N*mm", "mm", "rad", "N/mm^2", "W", "-").
  double mirror;          ///< Sign under the mirror image in the track's x–z plane.
  /// A force, whose error is measured relative to the local wheel load (refinement, verify).
  bool force;
  DefaultOutput default_output;
  AtNoContact at_no_contact;
};

/// In the order of the default outputs. Tγ, frictional power and fatigue indices are the same
/// for a wheel and its mirror image (mirror +1); moments about x and z and lateral positions
/// change sign.
inline constexpr OutputQuantity kOutputQuantities[] = {
    {"fx", "N", 1.0, true, DefaultOutput::kYes, AtNoContact::kZero},
    {"fy", "N", -1.0, true, DefaultOutput::kYes, AtNoContact::kZero},
    {"fz", "N", 1.0, true, DefaultOutput::kYes, AtNoContact::kSolved},
    {"mx", "N*mm", -1.0, false, DefaultOutput::kYes, AtNoContact::kZero},
    {"my", "N*mm", 1.0, false, DefaultOutput::kYes, AtNoContact::kZero},
    {"mz", "N*mm", -1.0, false, DefaultOutput::kYes, AtNoContact::kZero},
    {"fx_ws", "N", 1.0, true, DefaultOutput::kNo, AtNoContact::kZero},
    {"fy_ws", "N", -1.0, true, DefaultOutput::kNo, AtNoContact::kZero},
    {"fz_ws", "N", 1.0, true, DefaultOutput::kNo, AtNoContact::kZero},
    {"n_patches", "-", 1.0, false, DefaultOutput::kYes, AtNoContact::kZero},
    {"contact_y", "mm", -1.0, false, DefaultOutput::kYes, AtNoContact::kUndefined},
    {"contact_angle", "rad", -1.0, false, DefaultOutput::kYes, AtNoContact::kUndefined},
    {"pmax", "N/mm^2", 1.0, false, DefaultOutput::kYes, AtNoContact::kZero},
    {"z", "mm", 1.0, false, DefaultOutput::kWithPrescribedFz, AtNoContact::kSolved},
    {"t_gamma", "N", 1.0, false, DefaultOutput::kNo, AtNoContact::kZero},
    {"frictional_power", "W", 1.0, false, DefaultOutput::kNo, AtNoContact::kZero},
    {"t_gamma_slip", "N", 1.0, false, DefaultOutput::kNo, AtNoContact::kZero},
    {"fi_surf_rail", "-", 1.0, false, DefaultOutput::kNo, AtNoContact::kUndefined},
    {"fi_surf_wheel", "-", 1.0, false, DefaultOutput::kNo, AtNoContact::kUndefined},
    {"rolling_radius", "mm", 1.0, false, DefaultOutput::kNo, AtNoContact::kUndefined},
    {"wheel_contact_y", "mm", -1.0, false, DefaultOutput::kNo, AtNoContact::kUndefined},
};

/// The state quantity of that name, or nullptr.
constexpr const StateQuantity* FindStateQuantity(std::string_view name) {
  for (const StateQuantity& q : kStateQuantities) {
    if (q.name == name) return &q;
  }
  return nullptr;
}

/// Its index in kStateQuantities, or -1.
constexpr int StateQuantityIndex(std::string_view name) {
  const StateQuantity* q = FindStateQuantity(name);
  return q == nullptr ? -1 : static_cast<int>(q - kStateQuantities);
}

/// The output of that name, or nullptr.
constexpr const OutputQuantity* FindOutputQuantity(std::string_view name) {
  for (const OutputQuantity& q : kOutputQuantities) {
    if (q.name == name) return &q;
  }
  return nullptr;
}

/// A scene axis name (a state quantity a scene may vary).
constexpr bool IsSceneAxisName(std::string_view name) {
  const StateQuantity* q = FindStateQuantity(name);
  return q != nullptr && q->scene_axis;
}

/// True for the force outputs, whose errors are measured relative to the local wheel load.
constexpr bool IsForceOutput(std::string_view name) {
  const OutputQuantity* q = FindOutputQuantity(name);
  return q != nullptr && q->force;
}

/// Unit of an axis or output as stored in a table; empty for an unknown name.
constexpr std::string_view QuantityUnit(std::string_view name) {
  if (const StateQuantity* q = FindStateQuantity(name)) return q->unit;
  if (const OutputQuantity* q = FindOutputQuantity(name)) return q->unit;
  return {};
}

namespace quantities_check {
// A quantity that is both an axis and an output (z, fz) is one quantity: one unit, one sign.
constexpr bool OutputsAgreeWithStates() {
  for (const OutputQuantity& out : kOutputQuantities) {
    const StateQuantity* state = FindStateQuantity(out.name);
    if (state != nullptr && (state->unit != out.unit || state->mirror != out.mirror)) return false;
  }
  return true;
}
static_assert(OutputsAgreeWithStates(), "z and fz differ between kStateQuantities and outputs");
}  // namespace quantities_check

}  // namespace wrc
