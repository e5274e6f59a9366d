// The wheelset API of include/wrc/runtime.h: maps a wheelset's state to the axes of each
// wheel's table, evaluates both and assembles the forces in track coordinates.

#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <new>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "runtime/hdf5/table_schema.h"
#include "runtime/scene_values.h"
#include "runtime/table.h"
#include "wrc/quantities.h"
#include "wrc/runtime.h"

namespace {

using wrc::runtime::SceneNumber;
using wrc::runtime::SceneString;
using wrc::runtime::SetLastError;

// The wheelset's quantities (wrc/quantities.h), by their index in kStateQuantities.
constexpr int kQuantities = wrc::kStateQuantityCount;
constexpr int kY = wrc::StateQuantityIndex("y");
constexpr int kZ = wrc::StateQuantityIndex("z");
constexpr int kFz = wrc::StateQuantityIndex("fz");
constexpr int kRoll = wrc::StateQuantityIndex("roll");
constexpr int kYaw = wrc::StateQuantityIndex("yaw");
constexpr int kSpin = wrc::StateQuantityIndex("spin");
constexpr int kOmega = wrc::StateQuantityIndex("omega");
constexpr int kVy = wrc::StateQuantityIndex("vy");
constexpr int kVroll = wrc::StateQuantityIndex("vroll");
constexpr int kVyaw = wrc::StateQuantityIndex("vyaw");
constexpr int kMu = wrc::StateQuantityIndex("mu");
constexpr int kYWheel = wrc::StateQuantityIndex("y_wheel");

// The outputs the wheelset result reads.
enum Output { kFx, kFy, kFzOut, kMx, kMy, kMz, kContactY, kContactAngle, kTGamma, kOutputs };
constexpr std::string_view kOutputNames[kOutputs] = {
    "fx", "fy", "fz", "mx", "my", "mz", "contact_y", "contact_angle", "t_gamma"};

// Their signs under the mirror image, looked up in the registry once, at compile time: the
// lookup compares names, which an evaluation should not.
constexpr std::array<double, kOutputs> OutputMirrors() {
  std::array<double, kOutputs> mirror{};
  for (int k = 0; k < kOutputs; ++k) mirror[k] = wrc::FindOutputQuantity(kOutputNames[k])->mirror;
  return mirror;
}
constexpr std::array<double, kOutputs> kOutputMirror = OutputMirrors();

// Most outputs a table may have to be read here: the result buffer lives on the stack.
constexpr int kMaxOutputs = 64;

// One wheel: its table, whether it is read mirrored, and where each quantity goes.
struct Wheel {
  const wrc_table* table = nullptr;
  double mirror = 1.0;
  int n_axes = 0;
  int axis_quantity[WRC_MAX_AXES] = {};  // per axis
  double axis_first[WRC_MAX_AXES] = {};  // per axis: its range
  double axis_last[WRC_MAX_AXES] = {};
  double axis_slack[WRC_MAX_AXES] = {};  // per axis: what SnapToRange forgives
  // The quantities the table fixes (fixed[q] not NaN), for FixedFlag.
  int n_fixed = 0;
  int fixed_quantity[kQuantities] = {};
  int output_index[kOutputs] = {};  // -1: not in the table
  // The value the table was made with for each quantity that is not an axis (NaN: unknown, or
  // irrelevant such as z when fz was prescribed).
  double fixed[kQuantities] = {};
  // Velocities without an axis of their own, read on yaw (vy, vroll) and on spin (vyaw).
  bool fold_lateral = false;
  bool fold_longitudinal = false;
  double velocity = 0.0;        // V0, mm/s
  double nominal_radius = 0.0;  // r0, mm
  // Lateral distance of the wheel profile's origin from the wheelset centre, mm: the lever of
  // the yaw rate's longitudinal creepage.
  double lever = 0.0;
};

}  // namespace

struct wrc_wheelset {
  Wheel wheel[2];
  double origin[2][2] = {{NAN, NAN}, {NAN, NAN}};  // per rail: (y, z)
};

namespace {

enum class TypedState { kAbsent, kRead, kIncomplete };

// The fixed state from the table's typed attributes (runtime/hdf5/table_schema.h); absent in a
// table written before them. `left`: the table was made for a left wheel.
TypedState ReadTypedState(const wrc_table* table, Wheel& w, bool* left) {
  namespace schema = wrc::schema;
  if (wrc_table_number_attribute(table, schema::kWheelsetVelocity, &w.velocity) != WRC_OK) {
    return TypedState::kAbsent;
  }
  bool complete =
      wrc_table_number_attribute(table, schema::kWheelsetNominalRadius, &w.nominal_radius) ==
          WRC_OK &&
      wrc_table_number_attribute(table, schema::kWheelProfileOffset, &w.lever) == WRC_OK;
  for (int q = 0; q < kQuantities; ++q) {
    const std::string name = schema::kFixedPrefix + std::string(wrc::kStateQuantities[q].name);
    complete = complete && wrc_table_number_attribute(table, name.c_str(), &w.fixed[q]) == WRC_OK;
  }
  const char* side = wrc_table_attribute(table, schema::kWheelsetSide);
  if (!complete || side == nullptr) return TypedState::kIncomplete;  // wrc_last_error says what
  *left = std::strcmp(side, "left") == 0;
  return TypedState::kRead;
}

// Tables written before the typed attributes: the same values from the stored scene text,
// with the solver's defaults (include/wrc/core/case.h) where the scene leaves them out. Absent
// [state] keys are 0 except z/fz (one of them is given) and omega/spin (omega follows from
// spin, free rolling by default).
void ReadSceneState(const wrc_table* table, Wheel& w, bool* left) {
  const char* scene_attribute = wrc_table_attribute(table, wrc::schema::kScene);
  const std::string scene = scene_attribute != nullptr ? scene_attribute : "";
  w.velocity = SceneNumber(scene, "state", "velocity").value_or(NAN);
  w.nominal_radius = SceneNumber(scene, "wheelset", "nominal_radius").value_or(460.0);
  w.lever = 0.5 * SceneNumber(scene, "wheelset", "flange_back_distance").value_or(1360.0) -
            SceneNumber(scene, "wheelset", "flange_back_position").value_or(-70.0);
  *left = SceneString(scene, "wheelset", "side").value_or("right") == "left";
  for (int q = 0; q < kQuantities; ++q) {
    w.fixed[q] = SceneNumber(scene, "state", wrc::kStateQuantities[q].name).value_or(0.0);
  }
  w.fixed[kZ] = SceneNumber(scene, "state", "z").value_or(NAN);
  w.fixed[kFz] = SceneNumber(scene, "state", "fz").value_or(NAN);
  w.fixed[kMu] = SceneNumber(scene, "friction", "mu").value_or(NAN);
  const auto omega = SceneNumber(scene, "state", "omega");
  w.fixed[kSpin] = omega ? -*omega * w.nominal_radius / w.velocity - 1.0
                         : SceneNumber(scene, "state", "spin").value_or(0.0);
  w.fixed[kOmega] = -(w.velocity / w.nominal_radius) * (1.0 + w.fixed[kSpin]);
  w.fixed[kYWheel] = NAN;  // follows from y and roll, never fixed on its own
}

int QuantityOf(const char* axis_name) { return wrc::StateQuantityIndex(axis_name); }

// Reads what the wheel needs from its table; `side` is the wheel's side.
int SetUpWheel(const wrc_table* table, int side, Wheel& w) {
  bool left = false;
  const TypedState typed = ReadTypedState(table, w, &left);
  if (typed == TypedState::kIncomplete) {
    SetLastError("wrc_wheelset_create: the table's fixed state is incomplete: %s",
                 std::string(wrc_last_error()).c_str());
    return WRC_ERR_FORMAT;
  }
  if (typed == TypedState::kAbsent) ReadSceneState(table, w, &left);
  if (!(w.velocity > 0.0) || !(w.nominal_radius > 0.0)) {
    SetLastError("wrc_wheelset_create: the table gives no positive velocity and nominal radius");
    return WRC_ERR_FORMAT;
  }
  w.table = table;
  w.mirror = left == (side == WRC_LEFT) ? 1.0 : -1.0;
  bool has_axis[kQuantities] = {};
  for (int a = 0; a < wrc_table_num_axes(table); ++a) {
    const int q = QuantityOf(wrc_table_axis_name(table, a));
    if (q < 0) {
      SetLastError("wrc_wheelset_create: axis '%s' is not a wheelset quantity",
                   wrc_table_axis_name(table, a));
      return WRC_ERR_FORMAT;
    }
    w.axis_quantity[a] = q;
    w.axis_first[a] = wrc_table_axis_values(table, a)[0];
    w.axis_last[a] = wrc_table_axis_values(table, a)[wrc_table_axis_size(table, a) - 1];
    w.fixed[q] = NAN;
    has_axis[q] = true;
    // spin and omega are one quantity in two forms; so are y and y_wheel (given roll).
    if (q == kSpin || q == kOmega) w.fixed[kSpin] = w.fixed[kOmega] = NAN;
    if (q == kYWheel) w.fixed[kY] = NAN;
  }
  w.n_axes = wrc_table_num_axes(table);
  for (int a = 0; a < w.n_axes; ++a) {
    w.axis_slack[a] = 1e-12 * (w.axis_last[a] - w.axis_first[a] + std::fabs(w.axis_first[a]) +
                               std::fabs(w.axis_last[a]));
  }
  for (int q = 0; q < kQuantities; ++q) {
    if (!std::isnan(w.fixed[q])) w.fixed_quantity[w.n_fixed++] = q;
  }
  w.fold_lateral = has_axis[kYaw] && !has_axis[kVy] && !has_axis[kVroll];
  w.fold_longitudinal = (has_axis[kSpin] || has_axis[kOmega]) && !has_axis[kVyaw];
  if (wrc_table_num_outputs(table) > kMaxOutputs) {
    SetLastError("wrc_wheelset_create: the table has more than %d outputs", kMaxOutputs);
    return WRC_ERR_FORMAT;
  }
  for (int k = 0; k < kOutputs; ++k)
    w.output_index[k] = wrc_table_output_index(table, kOutputNames[k].data());
  return 0;
}

// Velocities the table has no axis for enter through the pose of equal creepage, as the
// creepages are what the contact sees: the lateral creepage vy/V − yaw − vroll·r0/V on the yaw
// axis, the yaw rate's longitudinal creepage −vyaw·y_c/V (y_c the wheel's lateral position,
// ±lever) on the spin axis. Both differ from the table's own velocities (fixed) only.
void FoldVelocities(const Wheel& w, int side, double (&value)[kQuantities]) {
  if (w.fold_lateral) {
    value[kYaw] -=
        (value[kVy] - w.fixed[kVy] - (value[kVroll] - w.fixed[kVroll]) * w.nominal_radius) /
        w.velocity;
    value[kVy] = w.fixed[kVy];
    value[kVroll] = w.fixed[kVroll];
  }
  if (w.fold_longitudinal) {
    const double y_c = side == WRC_RIGHT ? w.lever : -w.lever;
    value[kSpin] += (value[kVyaw] - w.fixed[kVyaw]) * y_c / w.velocity;
    value[kOmega] = -(w.velocity / w.nominal_radius) * (1.0 + value[kSpin]);
    value[kVyaw] = w.fixed[kVyaw];
  }
}

// The wheel's view of the state in the right-hand quantities of its table, before mirroring:
// velocities rescaled to the table's speed (creepages depend on velocity ratios only).
void StateQuantities(const wrc_wheelset_state& s, int side, const Wheel& w,
                     double (&value)[kQuantities]) {
  const double scale = w.velocity / s.velocity;
  value[kY] = s.y;
  value[kZ] = s.z;
  value[kFz] = s.fz[side];
  value[kRoll] = s.roll;
  value[kYaw] = s.yaw;
  value[kSpin] = -s.omega * w.nominal_radius / s.velocity - 1.0;
  value[kOmega] = s.omega * scale;
  value[kVy] = s.vy * scale;
  value[kVroll] = s.vroll * scale;
  value[kVyaw] = s.vyaw * scale;
  value[kMu] = s.mu[side];
  value[kYWheel] = s.y - w.nominal_radius * s.roll;
  FoldVelocities(w, side, value);
  for (int q = 0; q < kQuantities; ++q)
    value[q] *= w.mirror > 0.0 ? 1.0 : wrc::kStateQuantities[q].mirror;
}

// WRC_FLAG_FIXED when the state asks for a value the table fixes otherwise. A quantity the
// caller does not know (NaN fz, mu) asks for nothing.
int FixedFlag(const Wheel& w, const double (&value)[kQuantities]) {
  for (int i = 0; i < w.n_fixed; ++i) {
    const int q = w.fixed_quantity[i];
    if (std::isnan(value[q])) continue;
    const double tolerance = 1e-9 * (1.0 + std::fabs(w.fixed[q]) + std::fabs(value[q]));
    if (std::fabs(value[q] - w.fixed[q]) > tolerance) return WRC_FLAG_FIXED;
  }
  return 0;
}

double MirroredOutput(const Wheel& w, const double* out, int k) {
  const int index = w.output_index[k];
  if (index < 0) return NAN;
  return w.mirror > 0.0 ? out[index] : kOutputMirror[k] * out[index];
}

// A coordinate that lies outside its axis by rounding only (spin recomputed from omega at an
// end node, say) is taken at the end: it is not a pose the table cannot serve.
double SnapToRange(const Wheel& w, int a, double x) {
  const double slack = w.axis_slack[a];
  if (x < w.axis_first[a] && x >= w.axis_first[a] - slack) return w.axis_first[a];
  if (x > w.axis_last[a] && x <= w.axis_last[a] + slack) return w.axis_last[a];
  return x;
}

int EvalWheel(const Wheel& w, const wrc_wheelset_state& s, int side, wrc_wheel_contact& c) {
  double value[kQuantities];
  StateQuantities(s, side, w, value);
  double point[WRC_MAX_AXES];
  for (int a = 0; a < w.n_axes; ++a) {
    point[a] = SnapToRange(w, a, value[w.axis_quantity[a]]);
  }
  double out[kMaxOutputs];
  const int flags = wrc_table_eval(w.table, point, out);
  if (flags < 0) return flags;
  for (int i = 0; i < 3; ++i) {
    c.force[i] = MirroredOutput(w, out, kFx + i);
    c.moment[i] = MirroredOutput(w, out, kMx + i);
  }
  c.contact_y = MirroredOutput(w, out, kContactY);
  c.contact_angle = MirroredOutput(w, out, kContactAngle);
  c.t_gamma = MirroredOutput(w, out, kTGamma);
  c.flags = flags | FixedFlag(w, value);
  return c.flags;
}

// Forces and moments on the wheelset, the reactions of those on the rails; moments moved from
// each rail's origin o to the track origin: M + o × F with o = (0, o_y, o_z).
void Totals(const wrc_wheelset& ws, wrc_wheelset_result& r) {
  for (int i = 0; i < 3; ++i) {
    r.force[i] = -(r.wheel[0].force[i] + r.wheel[1].force[i]);
    r.moment[i] = 0.0;
  }
  for (int side = 0; side < 2; ++side) {
    const double* f = r.wheel[side].force;
    const double* m = r.wheel[side].moment;
    const double oy = ws.origin[side][0], oz = ws.origin[side][1];
    r.moment[0] -= m[0] + oy * f[2] - oz * f[1];
    r.moment[1] -= m[1] + oz * f[0];
    r.moment[2] -= m[2] - oy * f[0];
  }
}

// The pose must be finite (NaN: WRC_ERR_NAN_INPUT, ±inf: invalid); fz and mu may be NaN (not
// known) but not infinite. An infinite value would otherwise be clamped to the table or, for a
// quantity without an axis, compare equal to nothing and pass unflagged.
int CheckState(const wrc_wheelset_state& s) {
  const std::pair<const char*, double> pose[] = {
      {"y", s.y},       {"z", s.z},         {"roll", s.roll},
      {"yaw", s.yaw},   {"vy", s.vy},       {"vroll", s.vroll},
      {"vyaw", s.vyaw}, {"omega", s.omega}, {"velocity", s.velocity}};
  for (const auto& [name, v] : pose) {
    if (std::isnan(v)) {
      SetLastError("wrc_wheelset_eval: state.%s is NaN", name);
      return WRC_ERR_NAN_INPUT;
    }
    if (std::isinf(v)) {
      SetLastError("wrc_wheelset_eval: state.%s = %g, must be finite", name, v);
      return WRC_ERR_INVALID_ARGUMENT;
    }
  }
  const std::pair<const char*, double> per_wheel[] = {
      {"fz[0]", s.fz[0]}, {"fz[1]", s.fz[1]}, {"mu[0]", s.mu[0]}, {"mu[1]", s.mu[1]}};
  for (const auto& [name, v] : per_wheel) {
    if (std::isinf(v)) {
      SetLastError("wrc_wheelset_eval: state.%s = %g, must be finite (or NaN: not known)", name, v);
      return WRC_ERR_INVALID_ARGUMENT;
    }
  }
  // The case file's bounds (a running wheelset: 0 is not allowed here).
  if (!(s.velocity >= WRC_VELOCITY_MIN && s.velocity <= WRC_VELOCITY_MAX)) {
    SetLastError("wrc_wheelset_eval: velocity = %g mm/s, must lie within %g to %g mm/s", s.velocity,
                 WRC_VELOCITY_MIN, WRC_VELOCITY_MAX);
    return WRC_ERR_INVALID_ARGUMENT;
  }
  return 0;
}

}  // namespace

extern "C" {

void wrc_wheelset_state_init(wrc_wheelset_state* state) {
  if (state == nullptr) return;
  *state = wrc_wheelset_state{};
  state->fz[0] = state->fz[1] = state->mu[0] = state->mu[1] = NAN;
}

int wrc_wheelset_create(const wrc_table* left, const wrc_table* right, wrc_wheelset** out) {
  if (out == nullptr || (left == nullptr && right == nullptr)) {
    SetLastError("wrc_wheelset_create: %s is NULL", out == nullptr ? "out" : "both tables");
    return WRC_ERR_NULL_POINTER;
  }
  *out = nullptr;
  auto* ws = new (std::nothrow) wrc_wheelset;
  if (ws == nullptr) {
    SetLastError("wrc_wheelset_create: out of memory");
    return WRC_ERR_OUT_OF_MEMORY;
  }
  try {
    const wrc_table* tables[2] = {left ? left : right, right ? right : left};
    for (int side = 0; side < 2; ++side) {
      const int code = SetUpWheel(tables[side], side, ws->wheel[side]);
      if (code < 0) {
        delete ws;
        return code;
      }
    }
  } catch (const std::bad_alloc&) {
    delete ws;
    SetLastError("wrc_wheelset_create: out of memory");
    return WRC_ERR_OUT_OF_MEMORY;
  } catch (const std::exception& error) {
    delete ws;
    SetLastError("wrc_wheelset_create: %s", error.what());
    return WRC_ERR_INTERNAL;
  }
  *out = ws;
  return 0;
}

void wrc_wheelset_destroy(wrc_wheelset* wheelset) { delete wheelset; }

int wrc_wheelset_set_rail_origin(wrc_wheelset* wheelset, int side, double y, double z) {
  if (wheelset == nullptr) {
    SetLastError("wrc_wheelset_set_rail_origin: the wheelset is NULL");
    return WRC_ERR_NULL_POINTER;
  }
  if (side != WRC_LEFT && side != WRC_RIGHT) {
    SetLastError("wrc_wheelset_set_rail_origin: side %d is neither WRC_LEFT nor WRC_RIGHT", side);
    return WRC_ERR_INVALID_ARGUMENT;
  }
  wheelset->origin[side][0] = y;
  wheelset->origin[side][1] = z;
  return 0;
}

int wrc_wheelset_eval(const wrc_wheelset* wheelset, const wrc_wheelset_state* state,
                      wrc_wheelset_result* result) {
  if (wheelset == nullptr || state == nullptr || result == nullptr) {
    SetLastError("wrc_wheelset_eval: %s is NULL", wheelset == nullptr ? "the wheelset"
                                                  : state == nullptr  ? "state"
                                                                      : "result");
    return WRC_ERR_NULL_POINTER;
  }
  const int check = CheckState(*state);
  if (check < 0) return check;
  int flags = 0;
  for (int side = 0; side < 2; ++side) {
    const int wheel_flags = EvalWheel(wheelset->wheel[side], *state, side, result->wheel[side]);
    if (wheel_flags < 0) return wheel_flags;
    flags |= wheel_flags;
  }
  Totals(*wheelset, *result);
  return flags;
}

}  // extern "C"
