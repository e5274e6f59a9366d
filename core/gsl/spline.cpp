#include "core/gsl/spline.h"

#include <algorithm>
#include <cstddef>
#include <new>
#include <utility>
#include <vector>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_spline.h>
#include <gsl/gsl_vector.h>

#include "core/gsl/error.h"

namespace wrc::gsl {
namespace {

// ---------------------------------------------------------------------------------------------
// SplineType::kCubic as a gsl_interp_type, so that gsl_spline does the bookkeeping (copies of
// the knots, the check that x increases, the domain checks, the knot search) as for its own
// types. On knot interval i, with h = x_{i+1} − x_i, t = x − x_i, the slope of the chord
// Δ_i = (f_{i+1} − f_i)/h and the second derivatives M_i at the knots:
//   f(x) = f_i + b_i t + M_i t²/2 + (M_{i+1} − M_i) t³/(6h),  b_i = Δ_i − h (2M_i + M_{i+1})/6.
// C2 continuity gives, at each interior knot,
//   h_{i−1} M_{i−1} + 2 (h_{i−1} + h_i) M_i + h_i M_{i+1} = 6 (Δ_i − Δ_{i−1}),
// and each end adds M = 0 (natural) or the not-a-knot condition (third derivative equal on both
// sides of the knot next to the end): h_1 M_0 − (h_0 + h_1) M_1 + h_0 M_2 = 0 at the start,
// likewise at the end. Eliminating M_0 (M_{n−1}) from the first (last) interior equation keeps
// the system tridiagonal and strictly diagonally dominant (|h_1 − h_0| < h_0 + 2 h_1), so
// elimination without pivoting, as gsl_linalg_solve_tridiag does, is stable.

struct CubicState {
  std::vector<double> second;  ///< M_i, the second derivative at each knot.
};

void* AllocateCubic(std::size_t size) {
  try {
    auto* state = new CubicState;
    state->second.resize(size);
    return state;
  } catch (const std::bad_alloc&) {
    return nullptr;  // gsl_interp_alloc reports GSL_ENOMEM.
  }
}

void FreeCubic(void* state) { delete static_cast<CubicState*>(state); }

int InitCubic(void* raw_state, const double x[], const double f[], std::size_t n,
              CubicEnd first_end, CubicEnd last_end) {
  std::vector<double>& m = static_cast<CubicState*>(raw_state)->second;
  std::vector<double> h(n - 1);
  std::vector<double> slope(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x[i + 1] - x[i];
    slope[i] = (f[i + 1] - f[i]) / h[i];
  }
  const bool first_free = first_end == CubicEnd::kNotAKnot;
  const bool last_free = last_end == CubicEnd::kNotAKnot;
  const std::size_t unknowns = n - 2;  // M_1 .. M_{n−2}; n >= 3 (min_size).
  if (unknowns == 1 && first_free && last_free) {
    // One cubic through three points is underdetermined; the parabola is the usual choice.
    m.assign(3, 2.0 * (slope[1] - slope[0]) / (h[0] + h[1]));
    return GSL_SUCCESS;
  }
  std::vector<double> diagonal(unknowns);
  std::vector<double> above(std::max<std::size_t>(unknowns - 1, 1), 0.0);  // Never empty.
  std::vector<double> below(above.size(), 0.0);
  std::vector<double> rhs(unknowns);
  for (std::size_t k = 0; k < unknowns; ++k) {
    diagonal[k] = 2.0 * (h[k] + h[k + 1]);
    rhs[k] = 6.0 * (slope[k + 1] - slope[k]);
    if (k + 1 < unknowns) {
      above[k] = h[k + 1];
      below[k] = h[k + 1];
    }
  }
  if (first_free) {  // M_0 = ((h_0 + h_1) M_1 − h_0 M_2) / h_1 substituted.
    diagonal[0] = (h[0] + h[1]) * (h[0] + 2.0 * h[1]) / h[1];
    if (unknowns > 1) above[0] = (h[1] - h[0]) * (h[1] + h[0]) / h[1];
  }
  if (last_free) {  // M_{n−1} = ((a + b) M_{n−2} − b M_{n−3}) / a, a = h_{n−3}, b = h_{n−2}.
    const double a = h[n - 3];
    const double b = h[n - 2];
    diagonal[unknowns - 1] = (a + b) * (2.0 * a + b) / a;
    if (unknowns > 1) below[unknowns - 2] = (a - b) * (a + b) / a;
  }
  std::vector<double> interior(unknowns);
  if (unknowns == 1) {
    interior[0] = rhs[0] / diagonal[0];
  } else {
    gsl_vector_view diagonal_view = gsl_vector_view_array(diagonal.data(), unknowns);
    gsl_vector_view above_view = gsl_vector_view_array(above.data(), unknowns - 1);
    gsl_vector_view below_view = gsl_vector_view_array(below.data(), unknowns - 1);
    gsl_vector_view rhs_view = gsl_vector_view_array(rhs.data(), unknowns);
    gsl_vector_view interior_view = gsl_vector_view_array(interior.data(), unknowns);
    const int status =
        gsl_linalg_solve_tridiag(&diagonal_view.vector, &above_view.vector, &below_view.vector,
                                 &rhs_view.vector, &interior_view.vector);
    if (status != GSL_SUCCESS) return status;
  }
  for (std::size_t k = 0; k < unknowns; ++k) m[k + 1] = interior[k];
  m[0] = first_free ? ((h[0] + h[1]) * m[1] - h[0] * m[2]) / h[1] : 0.0;
  m[n - 1] = last_free ? ((h[n - 3] + h[n - 2]) * m[n - 2] - h[n - 2] * m[n - 3]) / h[n - 3] : 0.0;
  return GSL_SUCCESS;
}

template <CubicEnd kFirst, CubicEnd kLast>
int InitCubicWithEnds(void* state, const double x[], const double f[], std::size_t n) {
  return InitCubic(state, x, f, n, kFirst, kLast);
}

std::size_t KnotInterval(const double x[], std::size_t n, double at, gsl_interp_accel* accel) {
  return accel != nullptr ? gsl_interp_accel_find(accel, x, n, at)
                          : gsl_interp_bsearch(x, at, 0, n - 1);
}

/// The cubic on knot interval i in powers of t = x − x_i: a + b t + c t² + d t³.
struct CubicPiece {
  double a, b, c, d;
};

CubicPiece PieceOn(const void* state, const double x[], const double f[], std::size_t i) {
  const std::vector<double>& m = static_cast<const CubicState*>(state)->second;
  const double h = x[i + 1] - x[i];
  const double slope = (f[i + 1] - f[i]) / h;
  return CubicPiece{f[i], slope - h * (2.0 * m[i] + m[i + 1]) / 6.0, 0.5 * m[i],
                    (m[i + 1] - m[i]) / (6.0 * h)};
}

int EvalCubic(const void* state, const double x[], const double f[], std::size_t n, double at,
              gsl_interp_accel* accel, double* result) {
  const std::size_t i = KnotInterval(x, n, at, accel);
  const CubicPiece p = PieceOn(state, x, f, i);
  const double t = at - x[i];
  *result = p.a + t * (p.b + t * (p.c + t * p.d));
  return GSL_SUCCESS;
}

int EvalCubicDerivative(const void* state, const double x[], const double f[], std::size_t n,
                        double at, gsl_interp_accel* accel, double* result) {
  const std::size_t i = KnotInterval(x, n, at, accel);
  const CubicPiece p = PieceOn(state, x, f, i);
  const double t = at - x[i];
  *result = p.b + t * (2.0 * p.c + t * 3.0 * p.d);
  return GSL_SUCCESS;
}

int EvalCubicSecondDerivative(const void* state, const double x[], const double f[], std::size_t n,
                              double at, gsl_interp_accel* accel, double* result) {
  const std::size_t i = KnotInterval(x, n, at, accel);
  const CubicPiece p = PieceOn(state, x, f, i);
  *result = 2.0 * p.c + 6.0 * p.d * (at - x[i]);
  return GSL_SUCCESS;
}

int EvalCubicIntegral(const void* state, const double x[], const double f[], std::size_t n,
                      gsl_interp_accel* accel, double from, double to, double* result) {
  // gsl_interp_eval_integ_e has checked that from <= to lie in [x_0, x_{n−1}].
  const std::size_t first = KnotInterval(x, n, from, accel);
  const std::size_t last = KnotInterval(x, n, to, accel);
  const auto antiderivative = [](const CubicPiece& p, double t) {
    return t * (p.a + t * (p.b / 2.0 + t * (p.c / 3.0 + t * p.d / 4.0)));
  };
  double sum = 0.0;
  for (std::size_t i = first; i <= last; ++i) {
    const CubicPiece p = PieceOn(state, x, f, i);
    const double lo = (i == first ? from : x[i]) - x[i];
    const double hi = (i == last ? to : x[i + 1]) - x[i];
    sum += antiderivative(p, hi) - antiderivative(p, lo);
  }
  *result = sum;
  return GSL_SUCCESS;
}

template <CubicEnd kFirst, CubicEnd kLast>
const gsl_interp_type* CubicType() {
  static const gsl_interp_type type = {"wrc_cubic",
                                       3,
                                       AllocateCubic,
                                       InitCubicWithEnds<kFirst, kLast>,
                                       EvalCubic,
                                       EvalCubicDerivative,
                                       EvalCubicSecondDerivative,
                                       EvalCubicIntegral,
                                       FreeCubic};
  return &type;
}

const gsl_interp_type* GslType(SplineType type, CubicEnd first_end, CubicEnd last_end) {
  using E = CubicEnd;
  switch (type) {
    case SplineType::kLinear:
      return gsl_interp_linear;
    case SplineType::kNaturalCubic:
      return gsl_interp_cspline;
    case SplineType::kAkima:
      return gsl_interp_akima;
    case SplineType::kSteffen:
      return gsl_interp_steffen;
    case SplineType::kCubic:
      if (first_end == E::kNatural) {
        return last_end == E::kNatural ? CubicType<E::kNatural, E::kNatural>()
                                       : CubicType<E::kNatural, E::kNotAKnot>();
      }
      return last_end == E::kNatural ? CubicType<E::kNotAKnot, E::kNatural>()
                                     : CubicType<E::kNotAKnot, E::kNotAKnot>();
  }
  return gsl_interp_cspline;
}

}  // namespace

struct Spline::State {
  struct Deleter {
    void operator()(gsl_spline* s) const { gsl_spline_free(s); }
  };
  std::unique_ptr<gsl_spline, Deleter> spline;
};

Spline::Spline(std::vector<double> x, std::vector<double> f, SplineType type)
    : x_(std::move(x)), f_(std::move(f)), type_(type) {
  Build();
}

Spline::~Spline() = default;

Spline::Spline(std::vector<double> x, std::vector<double> f, CubicEnd first_end, CubicEnd last_end)
    : x_(std::move(x)),
      f_(std::move(f)),
      type_(SplineType::kCubic),
      first_end_(first_end),
      last_end_(last_end) {
  Build();
}

Spline::Spline(const Spline& other)
    : x_(other.x_),
      f_(other.f_),
      type_(other.type_),
      first_end_(other.first_end_),
      last_end_(other.last_end_) {
  Build();
}

Spline& Spline::operator=(const Spline& other) {
  if (this != &other) {
    Spline copy(other);
    *this = std::move(copy);
  }
  return *this;
}

Spline::Spline(Spline&& other) noexcept = default;
Spline& Spline::operator=(Spline&& other) noexcept = default;

void Spline::Build() {
  DisableAbortOnError();
  const gsl_interp_type* gsl_type = GslType(type_, first_end_, last_end_);
  // Checked here because gsl_spline_alloc would only return null without saying why.
  if (x_.size() != f_.size() || x_.size() < gsl_interp_type_min_size(gsl_type)) {
    throw GslError("gsl_spline_alloc", GSL_EINVAL);
  }
  state_ = std::make_unique<State>();
  state_->spline.reset(gsl_spline_alloc(gsl_type, x_.size()));
  if (!state_->spline) throw GslError("gsl_spline_alloc", GSL_ENOMEM);
  // gsl_spline_init copies the knots into the spline and rejects x that does not increase.
  CheckStatus(gsl_spline_init(state_->spline.get(), x_.data(), f_.data(), x_.size()),
              "gsl_spline_init");
}

double Spline::Value(double x) const {
  double result = 0.0;
  CheckStatus(gsl_spline_eval_e(state_->spline.get(), x, nullptr, &result), "gsl_spline_eval_e");
  return result;
}

double Spline::Derivative(double x) const {
  double result = 0.0;
  CheckStatus(gsl_spline_eval_deriv_e(state_->spline.get(), x, nullptr, &result),
              "gsl_spline_eval_deriv_e");
  return result;
}

double Spline::DerivativeOn(std::size_t interval, double x) const {
  // An accelerator that already points at the interval: GSL's lookup then checks it and takes
  // it, instead of a binary search (the derivative itself is GSL's, for every spline type).
  gsl_interp_accel accel{};
  accel.cache = std::min(interval, x_.size() - 2);
  double result = 0.0;
  CheckStatus(gsl_spline_eval_deriv_e(state_->spline.get(), x, &accel, &result),
              "gsl_spline_eval_deriv_e");
  return result;
}

double Spline::ValueOn(std::size_t interval, double x) const {
  gsl_interp_accel accel{};
  accel.cache = std::min(interval, x_.size() - 2);
  double result = 0.0;
  CheckStatus(gsl_spline_eval_e(state_->spline.get(), x, &accel, &result), "gsl_spline_eval_e");
  return result;
}

void Spline::DerivativesOn(std::size_t interval, const double* x, std::size_t count,
                           double* out) const {
  if (type_ != SplineType::kCubic) {
    for (std::size_t k = 0; k < count; ++k) out[k] = DerivativeOn(interval, x[k]);
    return;
  }
  // EvalCubicDerivative's arithmetic on the piece it would find for these points.
  const gsl_spline* spline = state_->spline.get();
  const std::size_t i = std::min(interval, x_.size() - 2);
  const CubicPiece p = PieceOn(spline->interp->state, spline->x, spline->y, i);
  for (std::size_t k = 0; k < count; ++k) {
    if (!(x[k] >= spline->x[i] && x[k] <= spline->x[i + 1])) {
      throw GslError("Spline::DerivativesOn", GSL_EDOM);
    }
    const double t = x[k] - spline->x[i];
    out[k] = p.b + t * (2.0 * p.c + t * 3.0 * p.d);
  }
}

double Spline::SecondDerivative(double x) const {
  double result = 0.0;
  CheckStatus(gsl_spline_eval_deriv2_e(state_->spline.get(), x, nullptr, &result),
              "gsl_spline_eval_deriv2_e");
  return result;
}

double Spline::Integral(double a, double b) const {
  double result = 0.0;
  CheckStatus(gsl_spline_eval_integ_e(state_->spline.get(), a, b, nullptr, &result),
              "gsl_spline_eval_integ_e");
  return result;
}

}  // namespace wrc::gsl
