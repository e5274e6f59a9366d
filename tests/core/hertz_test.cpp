// Tests of the Hertz solution (include/wrc/core/hertz.h) against the Hertz values printed in the
// header comments of the reference half-space cases, and against closed-form special cases.

#include "wrc/core/hertz.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/gsl/elliptic.h"
#include "wrc/core/material.h"

namespace wrc {
namespace {

constexpr double kPi = 3.14159265358979323846;

// One printed number together with the half unit of its last printed digit.
struct PrintedValue {
  double value = 0.0;
  double half_unit = 0.0;
};

PrintedValue ParsePrinted(const std::string& text) {
  const std::size_t dot = text.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(text.size() - dot - 1);
  return PrintedValue{std::stod(text), 0.5 * std::pow(10.0, -decimals)};
}

// The Hertz line of a reference case and the inputs it was computed from.
struct ReferenceCase {
  std::string name;
  double a1 = 0.0, b1 = 0.0, shear_modulus = 0.0, poisson = 0.0, normal_force = 0.0;
  PrintedValue a, b, ratio, max_pressure, approach;
};

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The number of the first line "key = number" (top-level TOML keys, no quoting needed here).
double ParseTomlNumber(const std::vector<std::string>& lines, const std::string& key) {
  const std::string prefix = key + " = ";
  for (const std::string& line : lines) {
    if (line.rfind(prefix, 0) == 0) return std::stod(line.substr(prefix.size()));
  }
  throw std::runtime_error("no key " + key);
}

// The number after "key = " in a "key = value unit" item of the Hertz header line.
std::string HeaderField(const std::string& line, const std::string& key) {
  const std::string pattern = " " + key + " = ";
  const std::size_t at = line.find(pattern);
  if (at == std::string::npos) throw std::runtime_error("no field " + key + " in: " + line);
  const std::size_t begin = at + pattern.size();
  const std::size_t end = line.find_first_not_of("0123456789.", begin);
  return line.substr(begin, end - begin);
}

std::vector<ReferenceCase> LoadReferenceCases() {
  // Header line written by the reference generator, e.g.
  // "# Hertz (fn = 10 kN): a = 3.1173 mm, b = 3.1173 mm, a/b = 1.000, p0 = 491.4 N/mm2,
  //  approach = 0.021125 mm".
  const std::string hertz_prefix = "# Hertz (";
  std::vector<ReferenceCase> cases;
  const std::filesystem::path folder =
      std::filesystem::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / "halfspace";
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".toml") continue;
    std::ifstream in(entry.path());
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::vector<std::string> lines = Lines(buffer.str());
    const auto header = std::find_if(lines.begin(), lines.end(), [&](const std::string& line) {
      return line.rfind(hertz_prefix, 0) == 0;
    });
    if (header == lines.end()) continue;
    // Leading space so that " a = " does not also match inside "a/b = " or "approach = ".
    const std::string line = " " + header->substr(hertz_prefix.size());
    ReferenceCase c;
    c.name = entry.path().stem().string();
    if (line.find(" kN)") == std::string::npos) throw std::runtime_error("fn not in kN: " + line);
    c.normal_force = 1000.0 * std::stod(HeaderField(line, "fn"));
    c.a = ParsePrinted(HeaderField(line, "a"));
    c.b = ParsePrinted(HeaderField(line, "b"));
    c.ratio = ParsePrinted(HeaderField(line, "a/b"));
    c.max_pressure = ParsePrinted(HeaderField(line, "p0"));
    c.approach = ParsePrinted(HeaderField(line, "approach"));
    c.a1 = ParseTomlNumber(lines, "a1");
    c.b1 = ParseTomlNumber(lines, "b1");
    c.shear_modulus = ParseTomlNumber(lines, "shear_modulus");
    c.poisson = ParseTomlNumber(lines, "poisson");
    cases.push_back(c);
  }
  std::sort(cases.begin(), cases.end(),
            [](const ReferenceCase& x, const ReferenceCase& y) { return x.name < y.name; });
  return cases;
}

// |got − printed| must not exceed half a unit of the last printed digit (the printed value is
// the correctly rounded one), plus 1e-12 relative for the decimal conversion of the bound.
void ExpectMatchesPrinted(double got, const PrintedValue& printed, const std::string& what) {
  EXPECT_LE(std::fabs(got - printed.value), printed.half_unit * (1.0 + 1e-12))
      << what << ": got " << got << ", printed " << printed.value;
}

TEST(Hertz, MatchesReferenceCaseHeaders) {
  const std::vector<ReferenceCase> cases = LoadReferenceCases();
  // 22 half-space cases, each with a Hertz line (reference/README.md).
  ASSERT_EQ(cases.size(), 22u) << "reference cases not found under " << WRC_TEST_DATA_DIR;
  bool saw_long_x = false, saw_long_y = false, saw_circle = false;
  for (const ReferenceCase& c : cases) {
    SCOPED_TRACE(c.name);
    const ElasticMaterial steel{c.shear_modulus, c.poisson};
    const double effective_modulus = CombinedElasticity::Identical(steel).EffectiveModulus();
    const HertzSolution s = HertzContact(c.a1, c.b1, effective_modulus).ForForce(c.normal_force);
    ExpectMatchesPrinted(s.semi_axis_x, c.a, "a");
    ExpectMatchesPrinted(s.semi_axis_y, c.b, "b");
    ExpectMatchesPrinted(s.axis_ratio, c.ratio, "a/b");
    ExpectMatchesPrinted(s.max_pressure, c.max_pressure, "p0");
    ExpectMatchesPrinted(s.approach, c.approach, "approach");
    saw_long_x |= c.a1 < c.b1;
    saw_long_y |= c.a1 > c.b1;
    saw_circle |= c.a1 == c.b1;
  }
  EXPECT_TRUE(saw_long_x && saw_long_y && saw_circle);
}

// Reference values hard-coded from the header comments of
// tests/data/reference/cases/halfspace/{ab1,ab03,ab3}_normal.toml (G = 82000 N/mm², ν = 0.28,
// fn = 10 kN), so that this check does not depend on the parser above.
TEST(Hertz, HardCodedReferenceValues) {
  struct Expected {
    double a1, b1, a, b, p0, approach;
  };
  const Expected expected[] = {
      {0.001087, 0.001087, 3.1173, 3.1173, 491.4, 0.021125},  // ab1_normal
      {0.001087, 0.000174, 2.2191, 7.4023, 290.7, 0.014887},  // ab03_normal
      {0.001087, 0.00576, 3.9450, 1.3147, 920.6, 0.026874},   // ab3_normal
  };
  const double effective_modulus = 82000.0 / (1.0 - 0.28);
  for (const Expected& e : expected) {
    const HertzSolution s = HertzContact(e.a1, e.b1, effective_modulus).ForForce(10000.0);
    EXPECT_NEAR(s.semi_axis_x, e.a, 0.5e-4);  // printed to 4 decimals
    EXPECT_NEAR(s.semi_axis_y, e.b, 0.5e-4);
    EXPECT_NEAR(s.max_pressure, e.p0, 0.05);      // printed to 1 decimal
    EXPECT_NEAR(s.approach, e.approach, 0.5e-6);  // printed to 6 decimals
  }
}

TEST(Hertz, CircularContactIsExact) {
  // a³ = 3·fn·R/(4E*), δ = a²/R, p0 = 3fn/(2πa²) with R = 1/(2·a1) (Johnson ch. 4).
  const double a1 = 0.001087, e_star = 113888.0, fn = 12345.0;
  const double radius = 0.5 / a1;
  const double a = std::cbrt(3.0 * fn * radius / (4.0 * e_star));
  const HertzContact contact(a1, a1, e_star);
  const HertzSolution s = contact.ForForce(fn);
  // Same formula, evaluated in a different order: only rounding differs (a few ulp).
  constexpr double kRounding = 1e-14;
  EXPECT_EQ(contact.eccentricity(), 0.0);
  EXPECT_EQ(s.axis_ratio, 1.0);
  EXPECT_NEAR(s.semi_axis_x, a, kRounding * a);
  EXPECT_EQ(s.semi_axis_x, s.semi_axis_y);
  EXPECT_NEAR(s.approach, a * a / radius, kRounding * s.approach);
  EXPECT_NEAR(s.max_pressure, 3.0 * fn / (2.0 * kPi * a * a), kRounding * s.max_pressure);
  EXPECT_NEAR(s.area, kPi * a * a, kRounding * s.area);
  EXPECT_EQ(s.normal_force, fn);
}

TEST(Hertz, EllipseSatisfiesHertzConditionsWithKAndE) {
  // Independent check of the R_D-based eccentricity: the displacement under the Hertz pressure
  // must reproduce both curvatures (Johnson ch. 3), written with K(e) and E(e) directly:
  //   A = p0·S·(K − E)/(E*·L²·e²),   B = p0·S·((L/S)²·E − K)/(E*·L²·e²),   δ = p0·S·K/E*.
  // At e ≈ 0.94 the differences lose < 1 digit, so 1e-12 is far above the rounding.
  const double a1 = 0.001087, b1 = 0.00576, e_star = 82000.0 / 0.72, fn = 10000.0;
  const HertzContact contact(a1, b1, e_star);
  const HertzSolution s = contact.ForForce(fn);
  const double e = contact.eccentricity();
  const double k = gsl::CompleteEllipticK(e), big_e = gsl::CompleteEllipticE(e);
  const double long_axis = s.semi_axis_x, short_axis = s.semi_axis_y;  // a1 < b1: long in x
  ASSERT_GT(long_axis, short_axis);
  EXPECT_NEAR(e * e, 1.0 - std::pow(short_axis / long_axis, 2), 1e-14);
  const double common = s.max_pressure * short_axis / (e_star * long_axis * long_axis * e * e);
  EXPECT_NEAR(common * (k - big_e), a1, 1e-12 * a1);
  EXPECT_NEAR(common * (std::pow(long_axis / short_axis, 2) * big_e - k), b1, 1e-12 * b1);
  EXPECT_NEAR(s.max_pressure * short_axis * k / e_star, s.approach, 1e-12 * s.approach);
  EXPECT_NEAR(s.max_pressure, 3.0 * fn / (2.0 * kPi * s.semi_axis_x * s.semi_axis_y),
              1e-14 * s.max_pressure);
  EXPECT_NEAR(s.area, kPi * s.semi_axis_x * s.semi_axis_y, 1e-14 * s.area);
}

TEST(Hertz, SwappingCurvaturesSwapsAxes) {
  const double e_star = 113888.0, fn = 10000.0;
  const HertzSolution long_x = HertzContact(0.001, 0.004, e_star).ForForce(fn);
  const HertzSolution long_y = HertzContact(0.004, 0.001, e_star).ForForce(fn);
  EXPECT_GT(long_x.semi_axis_x, long_x.semi_axis_y);
  // Identical arithmetic on the same sorted curvatures: equal to the last bit.
  EXPECT_EQ(long_x.semi_axis_x, long_y.semi_axis_y);
  EXPECT_EQ(long_x.semi_axis_y, long_y.semi_axis_x);
  EXPECT_EQ(long_x.max_pressure, long_y.max_pressure);
  EXPECT_EQ(long_x.approach, long_y.approach);
  EXPECT_DOUBLE_EQ(long_x.axis_ratio, 1.0 / long_y.axis_ratio);
}

TEST(Hertz, NearlyCircularContactIsContinuous) {
  // For B/A = 1 + ε, 1 − b/a is proportional to ε for small ε. Computed from K and E the ratio
  // would lose about log10(1/ε) digits; the R_D form keeps it linear down to ε = 1e-10.
  const double a1 = 0.001, e_star = 113888.0, fn = 10000.0;
  const HertzSolution circle = HertzContact(a1, a1, e_star).ForForce(fn);
  const auto flattening = [&](double epsilon) {
    return 1.0 - 1.0 / HertzContact(a1, a1 * (1.0 + epsilon), e_star).axis_ratio();
  };
  const double slope = flattening(1e-6) / 1e-6;
  EXPECT_GT(slope, 0.0);
  // Linear with O(ε) corrections; 1e-5 covers that at ε = 1e-6 and the 1e-13 root tolerance
  // relative to a flattening of 1e-10 (1e-3 at ε = 1e-10, hence the looser check there).
  EXPECT_NEAR(flattening(1e-8) / 1e-8, slope, 1e-5 * slope);
  EXPECT_NEAR(flattening(1e-10) / 1e-10, slope, 2e-3 * slope);
  const HertzSolution near = HertzContact(a1, a1 * (1.0 + 1e-10), e_star).ForForce(fn);
  EXPECT_NEAR(near.semi_axis_x, circle.semi_axis_x, 1e-9 * circle.semi_axis_x);
  EXPECT_NEAR(near.approach, circle.approach, 1e-9 * circle.approach);
}

TEST(Hertz, ForceApproachRelation) {
  const HertzContact contact(0.001087, 0.000174, 113888.0);
  const double fn = 7500.0;
  const double approach = contact.ApproachForForce(fn);
  EXPECT_DOUBLE_EQ(approach, contact.ForForce(fn).approach);
  // fn ∝ δ^{3/2}: doubling δ multiplies fn by 2√2. Round trips lose only rounding.
  EXPECT_NEAR(contact.ForceForApproach(2.0 * approach), 2.0 * std::sqrt(2.0) * fn, 1e-12 * fn);
  const HertzSolution by_approach = contact.ForApproach(approach);
  EXPECT_EQ(by_approach.approach, approach);
  EXPECT_NEAR(by_approach.normal_force, fn, 1e-12 * fn);
  EXPECT_NEAR(by_approach.semi_axis_y, contact.ForForce(fn).semi_axis_y, 1e-12 * 7.4);
  // The reference case ab1_approach0.02 prescribes δ = 0.02 mm for the ab1 geometry: below the
  // 0.021125 mm of 10 kN, so the force is (0.02/0.021125)^{3/2}·10 kN to the printed digits.
  const HertzContact ab1(0.001087, 0.001087, 82000.0 / 0.72);
  EXPECT_NEAR(ab1.ForceForApproach(0.02), 1e4 * std::pow(0.02 / 0.021125, 1.5),
              1e4 * 1.5 * 0.5e-6 / 0.021125);  // δ printed to 6 decimals: fn to 3.5e-5 relative
  const HertzSolution unloaded = contact.ForForce(0.0);
  EXPECT_EQ(unloaded.semi_axis_x, 0.0);
  EXPECT_EQ(unloaded.approach, 0.0);
  EXPECT_EQ(contact.ForceForApproach(0.0), 0.0);
}

TEST(Hertz, InvalidInputThrows) {
  EXPECT_THROW(HertzContact(0.0, 0.001, 1e5), std::invalid_argument);
  EXPECT_THROW(HertzContact(0.001, -0.001, 1e5), std::invalid_argument);
  EXPECT_THROW(HertzContact(0.001, 0.001, std::nan("")), std::invalid_argument);
  EXPECT_THROW(HertzContact(0.001, 1e30, 1e5), std::invalid_argument);  // absurd elongation
  const HertzContact contact(0.001, 0.002, 1e5);
  EXPECT_THROW(contact.ForForce(-1.0), std::invalid_argument);
  EXPECT_THROW(contact.ForApproach(std::nan("")), std::invalid_argument);
  EXPECT_THROW(contact.ForceForApproach(-0.01), std::invalid_argument);
}

}  // namespace
}  // namespace wrc
