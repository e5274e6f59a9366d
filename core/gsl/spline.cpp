#include "core/gsl/spline.h"

#include <utility>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_spline.h>

#include "core/gsl/error.h"

namespace wrc::gsl {
namespace {

const gsl_interp_type* GslType(SplineType type) {
  switch (type) {
    case SplineType::kLinear:
      return gsl_interp_linear;
    case SplineType::kNaturalCubic:
      return gsl_interp_cspline;
    case SplineType::kAkima:
      return gsl_interp_akima;
    case SplineType::kSteffen:
      return gsl_interp_steffen;
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

Spline::Spline(const Spline& other) : x_(other.x_), f_(other.f_), type_(other.type_) { Build(); }

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
  const gsl_interp_type* gsl_type = GslType(type_);
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
