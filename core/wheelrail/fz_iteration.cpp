#include "core/wheelrail/fz_iteration.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "wrc/core/errors.h"

namespace wrc::wr {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// The upper end of the bracket before any height above fz is known.
constexpr double kOpen = 1e300;

// The normal-only phase ends within kNormalPhase·fz when a full solve follows: the first full
// solve moves the force by the tangential part (1e-4 to 1e-3 of fz in the Manchester cases), so
// a Newton step on the full force is needed anyway and a closer start saves no full solve.
// Without friction the normal phase gives the result itself.
constexpr double kNormalPhase = 1e-5;
// With friction the normal-only phase hands over early: once a normal solve is within
// kHandOver·fz, the secant's next z is within ~1e-6·fz of the normal-only target (the secant on
// F^(2/3) converges about quadratically from there), and the full solves that follow correct
// the tangential part, 1e-4 to a few 1e-2 of fz, by Newton steps anyway. So the first full solve
// goes to that z directly, without a last normal-only solve there (measured: one solve fewer on
// y0, y8 and y10, the same passes elsewhere).
constexpr double kHandOver = 1e-3;
// The first full solve only serves to measure the tangential part for the next Newton step, so
// its tangential problem is solved to kFirstPassTangential instead of the solver's tolerance:
// the part is 1e-4 to 1e-3 of fz, so an error of 1e-4 of the tractions moves that step by 1e-7
// of fz or less, below fz_tolerance. The next solve starts from these tractions and is solved
// fully; only a full-tolerance solve can end the iteration.
constexpr double kFirstPassTangential = 1e-4;
constexpr int kMaxFullPasses = 20;
// The loosest tolerance of a normal solve far from fz (see FzIteration::last_error_).
constexpr double kLoosestNormal = 1e-5;

// Secant on G(z) = F(z)^(2/3): for Hertzian contact F ∝ δ^1.5 with δ = z − z_c, so G is close
// to linear in z and the secant converges in a few steps.
double G(double f) { return std::cbrt(std::max(f, 0.0) * std::max(f, 0.0)); }

// Where the normal-only phase left off: the height for the full solves (or the result's, without
// friction), the normal force expected there and dF/dz near it.
struct NormalPhaseEnd {
  double z = kNaN;
  double f_normal = 0.0;
  double stiffness = 0.0;
};

class FzIteration {
 public:
  FzIteration(VerticalForce& force, double fz, double first_contact,
              const FzIterationOptions& options)
      : force_(force), fz_(fz), first_contact_(first_contact), options_(options) {}

  FzIterationSummary Run(double z_start);

 private:
  double NormalForce(double z);
  void Record(double z, double f);
  double Deeper() const { return lo_ + 2.0 * (lo_ - first_contact_) + 1e-3; }
  bool NormalPhase(double z_start, NormalPhaseEnd& end);
  void FinishFrictionless(const NormalPhaseEnd& end);
  void NewtonOnFullSolves(const NormalPhaseEnd& end);

  VerticalForce& force_;
  const double fz_, first_contact_;
  const FzIterationOptions& options_;
  FzIterationSummary summary_;
  // Normal solves far from fz need not be exact: their tolerance is 1 % of the force error
  // expected of this step, between the solver's own tolerance and 1e-5. The secant converges
  // faster than linearly, so that is the last error times the last contraction, not the last
  // error itself: a solve whose force is off by more than the step still to go misleads the
  // secant and the bracket (seen: a loose 1e-5 solve 1.6e-6 of fz off, after which the bracket
  // closed on the wrong side of fz and the iteration stalled 1.1e-6 away).
  double last_error_ = 1.0, previous_error_ = 1.0;
  double last_normal_z_ = kNaN;
  // The bracket [lo, hi] with F(lo) < fz < F(hi) guards every step (regula falsi or bisection
  // when the secant leaves it), so the iteration cannot diverge where patches appear or merge.
  // A height that cannot be solved lies below every height that carries fz, as the force grows
  // with z: it bounds the bracket from above like a force of +inf.
  double lo_ = 0.0, g_lo_ = 0.0, hi_ = kOpen, g_hi_ = 0.0;
  bool hi_unsolvable_ = false;
};

// One normal-only solve, +inf where the height cannot be solved (its reason kept for the
// outcome, should fz lie beyond it).
double FzIteration::NormalForce(double z) {
  ++summary_.solves;
  double f = 0.0;
  try {
    const double expected_error = last_error_ * std::min(1.0, last_error_ / previous_error_);
    const double tolerance =
        std::clamp(1e-2 * expected_error, options_.normal_tolerance, kLoosestNormal);
    f = force_.Normal(z, tolerance);
  } catch (const InputError& e) {
    summary_.unsolvable = e.what();
    return kInf;
  }
  last_normal_z_ = z;
  previous_error_ = last_error_;
  last_error_ = std::fabs(f - fz_) / fz_;
  return f;
}

void FzIteration::Record(double z, double f) {
  if (f < fz_) {
    if (z > lo_) {
      lo_ = z;
      g_lo_ = G(f);
    }
  } else if (z < hi_) {
    hi_ = z;
    g_hi_ = G(f);
    hi_unsolvable_ = !std::isfinite(f);
  }
}

// The secant on normal-only solves; false when fz cannot be reached (the outcome set).
bool FzIteration::NormalPhase(double z_start, NormalPhaseEnd& end) {
  const double tolerance = options_.fz_tolerance * fz_;
  const double phase_tolerance =
      options_.tangential ? std::max(0.25 * tolerance, kNormalPhase * fz_) : 0.25 * tolerance;
  const double g_target = G(fz_);
  lo_ = first_contact_;
  double z0 = z_start, f0 = NormalForce(z0);
  double z1 = z0, f1 = f0;
  Record(z0, f0);
  const double hand_over = options_.tangential ? kHandOver : 0.0;
  if (std::fabs(f0 - fz_) > phase_tolerance) {
    // Second point from the Hertz scaling of the first.
    z1 = f0 > 0.0 ? first_contact_ + (z0 - first_contact_) * g_target / G(f0)
                  : first_contact_ + 2.0 * (z0 - first_contact_);
    for (int it = 0; it < options_.max_normal_steps; ++it) {
      // Without a height above fz yet, the next guess goes deeper by doubling the approach below
      // first contact: bisecting towards the open end would ask for absurd heights whose failure
      // then ends the iteration.
      if (hi_ < kOpen && !(z1 > lo_ && z1 < hi_)) z1 = 0.5 * (lo_ + hi_);
      if (hi_ == kOpen && !(z1 > lo_ && std::isfinite(z1))) z1 = Deeper();
      f1 = NormalForce(z1);
      Record(z1, f1);
      if (hi_ < kOpen && hi_ - lo_ < 1e-13) break;
      if (!std::isfinite(f1)) {
        // Unsolvable: bisection towards the solved heights; the secant pair stays.
        z1 = 0.5 * (lo_ + hi_);
        continue;
      }
      const bool secant_pair = z1 != z0 && std::isfinite(f0);
      if (secant_pair) end.stiffness = (f1 - f0) / (z1 - z0);
      if (std::fabs(f1 - fz_) <= phase_tolerance) break;
      const double ga = G(f0), gb = G(f1);
      // Two heights without contact (a first-contact estimate above the true one) give no
      // secant: then bisection, or deeper while no height above fz is known.
      double z2 = secant_pair && gb != ga ? z1 + (g_target - gb) * (z1 - z0) / (gb - ga)
                  : hi_ < kOpen           ? 0.5 * (lo_ + hi_)
                                          : Deeper();
      if (hi_ < kOpen && std::isfinite(g_hi_) && g_hi_ > g_lo_ && (z2 <= lo_ || z2 >= hi_)) {
        z2 = lo_ + (g_target - g_lo_) * (hi_ - lo_) / (g_hi_ - g_lo_);
      }
      if (std::fabs(f1 - fz_) <= hand_over * fz_ && z2 > lo_ && (hi_ == kOpen || z2 < hi_) &&
          secant_pair) {
        end.z = z2;
        end.f_normal = f1 + (f1 - f0) / (z1 - z0) * (z2 - z1);
        break;
      }
      z0 = z1;
      f0 = f1;
      z1 = z2;
    }
    const bool short_of_fz = std::isnan(end.z) && !(std::fabs(f1 - fz_) <= phase_tolerance);
    if (short_of_fz && hi_ == kOpen) {
      summary_.outcome = FzOutcome::kNoSupport;
      return false;
    }
    if (short_of_fz && hi_unsolvable_) {
      summary_.outcome = FzOutcome::kUnsolvable;
      return false;
    }
  }
  if (!(end.stiffness > 0.0)) {
    // Met at the first evaluation: estimate dF/dz from the Hertz law, F ∝ δ^1.5.
    end.stiffness = 1.5 * std::max(f1, 1e-9) / std::max(z1 - first_contact_, 1e-9);
  }
  if (std::isnan(end.z)) {
    end.z = z1;
    end.f_normal = f1;
  }
  return true;
}

// Without friction: the last normal solve is the result, unless it was a loose one or at
// another height (then solved again at the solver's tolerance).
void FzIteration::FinishFrictionless(const NormalPhaseEnd& end) {
  double f = end.f_normal;
  if (!(end.z == last_normal_z_ && last_error_ <= 0.25 * options_.fz_tolerance)) {
    f = force_.Normal(end.z, 0.0);
  }
  summary_.z = end.z;
  summary_.outcome =
      std::fabs(f - fz_) <= options_.fz_tolerance * fz_ ? FzOutcome::kMet : FzOutcome::kNotMet;
}

// Newton steps on the full force: the first with the normal-only stiffness, then with the
// secant stiffness of the full solves (at flange contact fs·sin δ changes with z as much as the
// normal part, and the normal stiffness alone converges only linearly there).
void FzIteration::NewtonOnFullSolves(const NormalPhaseEnd& end) {
  const bool loose_first = options_.tangential_tolerance < kFirstPassTangential;
  double z = end.z, stiffness = end.stiffness, z_last = 0.0, f_last = 0.0;
  summary_.last_was_full = true;
  for (int pass = 0; pass < kMaxFullPasses; ++pass) {
    ++summary_.solves;
    const bool loose = pass == 0 && loose_first;
    double f = 0.0;
    try {
      f = force_.Full(z, loose ? kFirstPassTangential : 0.0);
    } catch (const InputError&) {
      // A Newton step to a height that cannot be solved: half of it.
      if (pass == 0) throw;
      z = 0.5 * (z + z_last);
      continue;
    }
    summary_.z = z;
    if (!loose && std::fabs(f - fz_) <= options_.fz_tolerance * fz_) {
      summary_.outcome = FzOutcome::kMet;
      return;
    }
    if (pass > 0 && z != z_last) {
      const double secant = (f - f_last) / (z - z_last);
      if (secant > 0.0) stiffness = secant;
    } else if (pass == 0 && end.f_normal > 0.0 && f > 0.0) {
      // The tangential part of FZ(TR), fs·sin δ, follows the normal load (in full slip fs = μ·fn
      // exactly), so dF/dz scales like F itself: the normal stiffness times F_full/F_normal at
      // this z. At flange contact, where that part is a few % of FZ, this saves the pass that the
      // secant needed to learn it; on the tread it changes the stiffness by 1e-4 or less.
      stiffness *= f / end.f_normal;
    }
    z_last = z;
    f_last = f;
    z -= (f - fz_) / stiffness;
  }
  summary_.outcome = FzOutcome::kNotMet;
}

FzIterationSummary FzIteration::Run(double z_start) {
  NormalPhaseEnd end;
  if (!NormalPhase(z_start, end)) return summary_;
  if (options_.tangential) {
    NewtonOnFullSolves(end);
  } else {
    FinishFrictionless(end);
  }
  return summary_;
}

}  // namespace

FzIterationSummary SolveForFz(VerticalForce& force, double fz, double first_contact, double z_start,
                              const FzIterationOptions& options) {
  return FzIteration(force, fz, first_contact, options).Run(z_start);
}

}  // namespace wrc::wr
