// Tests of the checked GSL wrappers in core/gsl/: quadrature, Brent root finding, complete
// elliptic integrals and the conversion of GSL status codes into wrc::GslError.

#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

#include <gsl/gsl_errno.h>
#include <gtest/gtest.h>

#include "core/gsl/elliptic.h"
#include "core/gsl/error.h"
#include "core/gsl/integration.h"
#include "core/gsl/roots.h"
#include "core/gsl/spline.h"

namespace wrc::gsl {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Integrals are requested to rel 1e-10 (the IntegrationOptions default); a pass at 1e-9 also
// checks that GSL's error estimate is honest, which is what the quadrature-based tests rely on.
constexpr double kQuadratureCheck = 1e-9;

TEST(GslError, MessageNamesFunctionAndGslText) {
  const GslError error("gsl_example", GSL_EDOM);
  EXPECT_EQ(error.status(), GSL_EDOM);
  EXPECT_EQ(std::string(error.what()), std::string("gsl_example: ") + gsl_strerror(GSL_EDOM));
  EXPECT_NO_THROW(CheckStatus(GSL_SUCCESS, "gsl_example"));
  EXPECT_THROW(CheckStatus(GSL_EINVAL, "gsl_example"), GslError);
}

TEST(GslError, DisablingTheAbortHandlerTwiceIsHarmless) {
  DisableAbortOnError();
  DisableAbortOnError();
  // With GSL's default handler a domain error would abort the process here.
  EXPECT_THROW(CompleteEllipticK(2.0), GslError);
}

TEST(GslIntegration, QagsPolynomial) {
  const IntegrationResult r = IntegrateQags([](double x) { return x * x; }, 0.0, 1.0);
  EXPECT_NEAR(r.value, 1.0 / 3.0, kQuadratureCheck / 3.0);
  EXPECT_LE(r.abs_error, 1e-10);
}

TEST(GslIntegration, QagsEndPointSingularity) {
  // ∫_0^1 ln(x)/√x dx = −4 (the example of the GSL manual, §17.15).
  const IntegrationResult r =
      IntegrateQags([](double x) { return std::log(x) / std::sqrt(x); }, 0.0, 1.0);
  EXPECT_NEAR(r.value, -4.0, 4.0 * kQuadratureCheck);
}

TEST(GslIntegration, QagpInteriorSingularities) {
  // ∫_0^3 x³·ln|(x² − 1)(x² − 2)| dx = 61·ln 2 + (77/4)·ln 7 − 27, log singular at 1 and √2
  // (QUADPACK's QAGP example).
  const double expected = 61.0 * std::log(2.0) + 77.0 / 4.0 * std::log(7.0) - 27.0;
  const IntegrationResult r = IntegrateQagp(
      [](double x) { return x * x * x * std::log(std::fabs((x * x - 1.0) * (x * x - 2.0))); },
      {0.0, 1.0, std::sqrt(2.0), 3.0});
  EXPECT_NEAR(r.value, expected, std::fabs(expected) * kQuadratureCheck);
  EXPECT_THROW(IntegrateQagp([](double x) { return x; }, {0.0}), std::invalid_argument);
}

TEST(GslIntegration, CauchyPrincipalValue) {
  // PV ∫_{−1}^{5} dx / (x·(5x³ + 6)) = ln(125/631)/18, by partial fractions
  // 1/(x(5x³+6)) = (1/6)·(1/x − 5x²/(5x³ + 6)).
  const double expected = std::log(125.0 / 631.0) / 18.0;
  const IntegrationResult r =
      IntegrateCauchy([](double x) { return 1.0 / (5.0 * x * x * x + 6.0); }, -1.0, 5.0, 0.0);
  EXPECT_NEAR(r.value, expected, std::fabs(expected) * kQuadratureCheck);
}

TEST(GslIntegration, TwoDimensionalSmooth) {
  const IntegrationResult r =
      Integrate2d([](double x, double y) { return x * y * y; }, 0.0, 2.0, 0.0, 3.0);
  EXPECT_NEAR(r.value, 18.0, 18.0 * kQuadratureCheck);  // (2²/2)·(3³/3)
}

TEST(GslIntegration, TwoDimensionalPointSingularityOnBreakpoints) {
  // ∫∫ over [−h, h]² of 1/r = 8·h·ln(1 + √2): the 1/r singularity at the centre sits on a
  // corner of each of the four quarters after splitting at x = 0 and y = 0.
  const double h = 0.7;
  const double expected = 8.0 * h * std::log(1.0 + std::sqrt(2.0));
  const IntegrationResult r = Integrate2d([](double x, double y) { return 1.0 / std::hypot(x, y); },
                                          -h, h, -h, h, IntegrationOptions{}, {0.0}, {0.0});
  EXPECT_NEAR(r.value, expected, expected * kQuadratureCheck);
  EXPECT_GT(r.abs_error, 0.0);
  EXPECT_LT(r.abs_error, expected * 1e-8);
}

TEST(GslIntegration, ReversedLimitsChangeSign) {
  const IntegrationResult r =
      Integrate2d([](double x, double y) { return x + y; }, 1.0, 0.0, 0.0, 1.0, {}, {0.5}, {});
  EXPECT_NEAR(r.value, -1.0, kQuadratureCheck);
}

TEST(GslIntegration, DivergentIntegralThrows) {
  EXPECT_THROW(IntegrateQags([](double x) { return 1.0 / x; }, 0.0, 1.0), GslError);
}

TEST(GslIntegration, ImpossibleToleranceThrows) {
  IntegrationOptions options;
  options.rel_tolerance = 0.0;  // with abs_tolerance 0 too, GSL refuses: GSL_EBADTOL
  try {
    IntegrateQags([](double x) { return x; }, 0.0, 1.0, options);
    FAIL() << "expected GslError";
  } catch (const GslError& error) {
    EXPECT_EQ(error.status(), GSL_EBADTOL);
    EXPECT_NE(std::string(error.what()).find("gsl_integration_qags"), std::string::npos);
  }
}

TEST(GslIntegration, IntegrandExceptionIsRethrownUnchanged) {
  const auto failing = [](double x) -> double {
    if (x > 0.5) throw std::domain_error("integrand failed");
    return x;
  };
  EXPECT_THROW(IntegrateQags(failing, 0.0, 1.0), std::domain_error);
  // Also through both levels of the nested 2-D rule.
  EXPECT_THROW(Integrate2d([&](double x, double y) { return failing(x * y); }, 0.0, 1.0, 0.0, 1.0),
               std::domain_error);
}

TEST(GslRoots, CosineFixedPoint) {
  const RootResult r = FindRootBrent([](double x) { return std::cos(x) - x; }, 0.0, 1.0);
  EXPECT_TRUE(r.converged);
  EXPECT_GT(r.iterations, 0);
  // Bracket width goal is 1e-12 relative (RootOptions default); the root is within it.
  EXPECT_NEAR(r.root, 0.73908513321516064166, 1e-12);
}

TEST(GslRoots, SquareRootOfTwoToTightTolerance) {
  RootOptions options;
  options.rel_tolerance = 1e-14;
  const RootResult r = FindRootBrent([](double x) { return x * x - 2.0; }, 0.0, 2.0, options);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.root, std::sqrt(2.0), 2e-14 * std::sqrt(2.0));
}

TEST(GslRoots, RootAtAnEndPointIsReturnedDirectly) {
  const RootResult r = FindRootBrent([](double x) { return x - 3.0; }, 3.0, 5.0);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.root, 3.0);
  EXPECT_EQ(r.iterations, 0);
}

TEST(GslRoots, BracketWithoutSignChangeThrows) {
  try {
    FindRootBrent([](double x) { return x * x - 2.0; }, 2.0, 3.0);
    FAIL() << "expected GslError";
  } catch (const GslError& error) {
    EXPECT_EQ(error.status(), GSL_EINVAL);
  }
  EXPECT_THROW(FindRootBrent([](double) { return std::nan(""); }, 0.0, 1.0), GslError);
}

TEST(GslRoots, IterationLimitReportsNotConverged) {
  RootOptions options;
  options.max_iterations = 1;
  const RootResult r = FindRootBrent([](double x) { return std::cos(x) - x; }, 0.0, 1.0, options);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_GT(r.root, 0.0);
  EXPECT_LT(r.root, 1.0);
}

TEST(GslRoots, ObjectiveExceptionIsRethrownUnchanged) {
  int calls = 0;
  const auto objective = [&calls](double x) {
    if (++calls > 3) throw std::logic_error("objective failed");
    return x - 0.3;
  };
  EXPECT_THROW(FindRootBrent(objective, 0.0, 1.0), std::logic_error);
}

TEST(GslElliptic, KnownValuesTakeTheModulus) {
  // Reference values to 17 digits (Abramowitz & Stegun Table 17.1 with m = k²): for k = 0.5,
  // m = 0.25; for k = 1/√2, m = 0.5, where K = Γ(1/4)²/(4√π). Passing m instead of k would
  // give K(0.5) = 1.8540746773... and fail.
  // GSL_PREC_DOUBLE is good to a few ulp: allow 4·DBL_EPSILON relative.
  const auto expect_close = [](double got, double expected) {
    EXPECT_NEAR(got, expected, 4.0 * DBL_EPSILON * expected);
  };
  EXPECT_DOUBLE_EQ(CompleteEllipticK(0.0), kPi / 2.0);
  EXPECT_DOUBLE_EQ(CompleteEllipticE(0.0), kPi / 2.0);
  expect_close(CompleteEllipticK(0.5), 1.6857503548125961);
  expect_close(CompleteEllipticE(0.5), 1.4674622093394272);
  expect_close(CompleteEllipticK(1.0 / std::sqrt(2.0)), 1.8540746773013719);
  expect_close(CompleteEllipticE(1.0 / std::sqrt(2.0)), 1.3506438810476755);
}

TEST(GslElliptic, OutOfDomainThrows) {
  for (double k : {1.0, -1.0, 1.5, std::nan("")}) {
    try {
      CompleteEllipticK(k);
      FAIL() << "expected GslError for K(" << k << ")";
    } catch (const GslError& error) {
      EXPECT_EQ(error.status(), GSL_EDOM);
      EXPECT_NE(std::string(error.what()).find("gsl_sf_ellint_Kcomp_e"), std::string::npos);
    }
    EXPECT_THROW(CompleteEllipticE(k), GslError) << "k = " << k;
  }
  EXPECT_THROW(CarlsonRD(-1.0, 1.0, 1.0), GslError);
  EXPECT_THROW(CarlsonRD(0.0, 0.0, 1.0), GslError);
  EXPECT_THROW(CarlsonRD(0.0, 1.0, std::nan("")), GslError);
}

TEST(GslElliptic, CarlsonRdValuesAndIdentity) {
  // Test values of B.C. Carlson, "Numerical computation of real or complex elliptic
  // integrals", Numer. Algorithms 10 (1995), §3, printed to 14 digits.
  EXPECT_NEAR(CarlsonRD(0.0, 2.0, 1.0), 1.7972103521034, 1e-13);
  EXPECT_NEAR(CarlsonRD(2.0, 3.0, 4.0), 0.16510527294261, 1e-14);
  // DLMF 19.25.1: K − E = (k²/3)·R_D(0, 1 − k², 1). At k = 0.5 the difference loses no
  // digits, so 1e-15 covers the few ulp of each function.
  const double k = 0.5;
  EXPECT_NEAR(CompleteEllipticK(k) - CompleteEllipticE(k), k * k / 3.0 * CarlsonRD(0.0, 0.75, 1.0),
              1e-15);
}

}  // namespace

TEST(GslSpline, DerivativeOnAnIntervalMatchesTheSearchedOne) {
  // DerivativeOn skips the search for the knot interval; on every interval, at its ends and
  // inside, it must give Derivative's value (the same arithmetic, so to round-off) for every
  // spline type.
  const std::vector<double> x{0.0, 0.3, 1.1, 1.5, 2.9, 3.0, 4.4};
  const std::vector<double> f{1.0, 0.2, -0.7, 0.4, 2.5, 2.4, -1.0};
  std::vector<wrc::gsl::Spline> splines;
  for (auto type : {wrc::gsl::SplineType::kLinear, wrc::gsl::SplineType::kNaturalCubic,
                    wrc::gsl::SplineType::kAkima, wrc::gsl::SplineType::kSteffen}) {
    splines.emplace_back(x, f, type);
  }
  splines.emplace_back(x, f, wrc::gsl::CubicEnd::kNotAKnot, wrc::gsl::CubicEnd::kNatural);
  for (const wrc::gsl::Spline& spline : splines) {
    for (std::size_t i = 0; i + 1 < x.size(); ++i) {
      for (double t : {0.0, 0.25, 0.5, 0.999}) {
        const double at = x[i] + t * (x[i + 1] - x[i]);
        EXPECT_NEAR(spline.DerivativeOn(i, at), spline.Derivative(at),
                    1e-13 * (1.0 + std::fabs(spline.Derivative(at))))
            << "type " << static_cast<int>(spline.type()) << " interval " << i << " t " << t;
      }
    }
  }
}

TEST(GslSpline, DerivativesOnAnIntervalEqualDerivativeOn) {
  // Several points of one interval at once: the same values as DerivativeOn, to the last bit
  // (the cubic type takes its piece once; the others ask GSL per point); points outside the
  // interval are a domain error.
  const std::vector<double> x{0.0, 0.3, 1.1, 1.5, 2.9, 3.0, 4.4};
  const std::vector<double> f{1.0, 0.2, -0.7, 0.4, 2.5, 2.4, -1.0};
  std::vector<wrc::gsl::Spline> splines;
  splines.emplace_back(x, f, wrc::gsl::SplineType::kNaturalCubic);
  splines.emplace_back(x, f, wrc::gsl::CubicEnd::kNatural, wrc::gsl::CubicEnd::kNatural);
  splines.emplace_back(x, f, wrc::gsl::CubicEnd::kNotAKnot, wrc::gsl::CubicEnd::kNatural);
  for (const wrc::gsl::Spline& spline : splines) {
    for (std::size_t i = 0; i + 1 < x.size(); ++i) {
      std::vector<double> at, out(4);
      for (double t : {0.0, 0.2, 0.7, 0.999}) at.push_back(x[i] + t * (x[i + 1] - x[i]));
      spline.DerivativesOn(i, at.data(), at.size(), out.data());
      for (std::size_t k = 0; k < at.size(); ++k) {
        EXPECT_EQ(out[k], spline.DerivativeOn(i, at[k]))
            << "type " << static_cast<int>(spline.type()) << " interval " << i << " k " << k;
      }
    }
  }
  const double outside = 2.0;
  double out = 0.0;
  EXPECT_THROW(splines[1].DerivativesOn(0, &outside, 1, &out), GslError);
}

}  // namespace wrc::gsl
