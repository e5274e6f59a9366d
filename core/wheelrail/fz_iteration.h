#pragma once
// The wheelset height that carries a prescribed vertical force FZ(TR) on the rail: a bracketed
// secant on normal-only solves, then Newton steps on full solves (core/wheelrail/solve.cpp asks
// for it when state.fz is given). Apart from the contact so that it can be read, changed and
// tested on its own: the contact enters only through VerticalForce.

#include <string>

namespace wrc::wr {

/// What the iteration solves: the vertical force on the rail at a wheelset height z (mm,
/// positive down into the rail). Both calls throw InputError for a height that cannot be
/// solved (the contact leaves the profiles, a patch too large to solve).
class VerticalForce {
 public:
  virtual ~VerticalForce() = default;
  /// FZ(TR) of the normal problem alone at z, solved to `tolerance` (0: the solver's own).
  virtual double Normal(double z, double tolerance) = 0;
  /// FZ(TR) with the tangential problem at z, its tractions solved to `tangential_tolerance`
  /// (0: the solver's own).
  virtual double Full(double z, double tangential_tolerance) = 0;
};

struct FzIterationOptions {
  double fz_tolerance = 1e-6;          ///< Relative: |F − fz| ≤ fz_tolerance·fz ends it.
  double normal_tolerance = 1e-8;      ///< The normal solver's own tolerance (the tightest).
  double tangential_tolerance = 1e-6;  ///< The tangential solver's own tolerance.
  int max_normal_steps = 100;          ///< Secant steps of the normal-only phase.
  bool tangential = true;              ///< Full solves follow (false: frictionless contact).
};

enum class FzOutcome {
  kMet,         ///< A solve at `z` carries fz within the tolerance.
  kNotMet,      ///< The steps ran out; `z` is the last height solved.
  kNoSupport,   ///< No height carries fz: the force stays below it as far down as searched.
  kUnsolvable,  ///< fz lies below heights that cannot be solved (`unsolvable` says why).
};

struct FzIterationSummary {
  FzOutcome outcome = FzOutcome::kNotMet;
  double z = 0.0;              ///< Height of the last solve that counts (the result's).
  int solves = 0;              ///< Normal-only and full solves of the iteration.
  bool last_was_full = false;  ///< Whether the result's solve is a full one.
  std::string unsolvable;      ///< Why the height above fz could not be solved.
};

/// The height where `force` carries `fz` (N, > 0), starting at `z_start` (> first_contact),
/// `first_contact` being the height of first touch (no force above it). The last call of
/// `force` that returned (of the kind `last_was_full` names) is the solve at the summary's z:
/// its result is the caller's. An InputError of the first full solve is passed on.
FzIterationSummary SolveForFz(VerticalForce& force, double fz, double first_contact, double z_start,
                              const FzIterationOptions& options);

}  // namespace wrc::wr
