#include "fmu/variables.h"

#include <stdexcept>
#include <utility>

namespace wrc::fmu {
namespace {

constexpr Type F = Type::kFloat64;
constexpr Causality P = Causality::kParameter;
constexpr Causality In = Causality::kInput;
constexpr Causality Out = Causality::kOutput;

class Builder {
 public:
  void Add(Type type, Causality causality, std::string name, const char* unit, double scale,
           std::string description) {
    const auto vr = static_cast<std::uint32_t>(list_.size());
    list_.push_back({vr, std::move(name), type, causality, unit, scale, std::move(description)});
  }
  std::vector<Variable> Take() { return std::move(list_); }

 private:
  std::vector<Variable> list_;
};

void AddParameters(Builder& b) {
  b.Add(Type::kString, P, "right_table", "", 1.0,
        "Flat table (.wrct) of the right wheel: a path relative to the FMU's resources, or "
        "absolute");
  b.Add(Type::kString, P, "left_table", "", 1.0,
        "Flat table of the left wheel; empty: the right wheel's table, mirrored");
  b.Add(Type::kEnumeration, P, "interpolation", "", 1.0,
        "Table interpolation: 1 multilinear, 2 cubic");
  for (const std::string side : {"left", "right"}) {
    b.Add(F, P, side + ".rail_origin_y", "m", 1000.0,
          "Lateral position of the " + side + " rail profile's origin, track frame (+ right)");
    b.Add(F, P, side + ".rail_origin_z", "m", 1000.0,
          "Vertical position of the " + side + " rail profile's origin (+ down)");
  }
}

void AddInputs(Builder& b) {
  b.Add(F, In, "y", "m", 1000.0, "Lateral displacement of the wheelset (+ right)");
  b.Add(F, In, "z", "m", 1000.0, "Vertical displacement of the wheelset (+ down), 0 nominal");
  b.Add(F, In, "roll", "rad", 1.0, "Roll angle of the wheelset about x");
  b.Add(F, In, "yaw", "rad", 1.0, "Yaw angle of the wheelset about z");
  b.Add(F, In, "vy", "m/s", 1000.0, "Lateral velocity");
  b.Add(F, In, "vroll", "rad/s", 1.0, "Roll rate");
  b.Add(F, In, "vyaw", "rad/s", 1.0, "Yaw rate");
  b.Add(F, In, "omega", "rad/s", 1.0, "Rotation about the axle, negative when rolling forward");
  b.Add(F, In, "velocity", "m/s", 1000.0, "Forward speed, > 0");
  for (const std::string side : {"left", "right"}) {
    b.Add(
        F, In, side + ".wheel_load", "N", 1.0,
        "Vertical force on the " + side + " rail, read on tables with an fz axis; NaN: not known");
  }
  for (const std::string side : {"left", "right"}) {
    b.Add(F, In, side + ".mu", "", 1.0,
          "Friction coefficient at the " + side +
              " wheel, read on tables with a mu axis; NaN: not known");
  }
}

// In the order of wrc_wheel_contact; the moments are about the rail's origin.
void AddWheelOutputs(Builder& b, const std::string& side) {
  const std::string rail = " on the " + side + " rail";
  b.Add(F, Out, side + ".fx", "N", 1.0, "Longitudinal force" + rail);
  b.Add(F, Out, side + ".fy", "N", 1.0, "Lateral force" + rail + " (+ right)");
  b.Add(F, Out, side + ".fz", "N", 1.0, "Vertical force" + rail + " (+ down)");
  for (const char* axis : {"x", "y", "z"}) {
    b.Add(F, Out, side + ".m" + axis, "N.m", 1000.0,
          std::string("Moment") + rail + " about " + axis + ", about the rail's origin");
  }
  b.Add(F, Out, side + ".contact_y", "m", 1000.0,
        "Lateral position of the force resultant on the " + side + " rail's profile");
  b.Add(F, Out, side + ".contact_angle", "rad", 1.0,
        "Surface inclination at the " + side + " contact, track frame");
  b.Add(F, Out, side + ".t_gamma", "N", 1.0,
        "Frictional power per distance rolled at the " + side +
            " wheel, T-gamma (NaN when the table has no t_gamma output)");
  b.Add(Type::kInt32, Out, side + ".flags", "", 1.0,
        "1: clamped to the table's range, 2: a failed node entered, 4: the state differs from "
        "a value the table fixes");
}

void AddWheelsetOutputs(Builder& b) {
  for (const char* axis : {"x", "y", "z"}) {
    b.Add(F, Out, std::string("wheelset.f") + axis, "N", 1.0,
          std::string("Force on the wheelset along ") + axis + ", track frame");
  }
  for (const char* axis : {"x", "y", "z"}) {
    b.Add(F, Out, std::string("wheelset.m") + axis, "N.m", 1000.0,
          std::string("Moment on the wheelset about the track's ") + axis + " axis");
  }
  b.Add(Type::kInt32, Out, "status", "", 1.0,
        "The flags of both wheels or'ed; negative: the lookup failed and the outputs are NaN");
}

std::vector<Variable> Build() {
  Builder b;
  b.Add(F, Causality::kIndependent, "time", "s", 1.0, "Simulation time");
  AddParameters(b);
  AddInputs(b);
  AddWheelOutputs(b, "left");
  AddWheelOutputs(b, "right");
  AddWheelsetOutputs(b);
  std::vector<Variable> list = b.Take();
  if (list.size() != kNumVariables || list[kY].name != "y" || list[kRightFx].name != "right.fx" ||
      list[kStatus].name != "status") {
    throw std::logic_error("wrc::fmu::Variables: the list is out of step with Vr");
  }
  return list;
}

}  // namespace

const char* TypeName(Type type) {
  switch (type) {
    case Type::kFloat64:
      return "Float64";
    case Type::kInt32:
      return "Int32";
    case Type::kString:
      return "String";
    case Type::kEnumeration:
      return "Enumeration";
  }
  return "";
}

const std::vector<Variable>& Variables() {
  static const std::vector<Variable> list = Build();
  return list;
}

}  // namespace wrc::fmu
