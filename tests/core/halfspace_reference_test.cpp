// The half-space cases of tests/data/reference against CONTACT's results.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "wrc/core/case.h"
#include "wrc/core/halfspace.h"

namespace wrc {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> HalfspaceCases() {
  std::vector<fs::path> cases;
  const fs::path dir = fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / "halfspace";
  if (!fs::exists(dir)) return cases;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".toml") cases.push_back(e.path());
  }
  std::sort(cases.begin(), cases.end());
  return cases;
}

TEST(HalfspaceReference, MatchesContact) {
  const auto cases = HalfspaceCases();
  ASSERT_EQ(cases.size(), 22u) << "reference cases missing under " << WRC_TEST_DATA_DIR;
  for (const fs::path& path : cases) {
    SCOPED_TRACE(path.filename().string());
    fs::path ref_path = path;
    ref_path.replace_extension(".contact.json");
    const nlohmann::json ref = nlohmann::json::parse(std::ifstream(ref_path))["patches"][0];
    const Case c = LoadCase(path);
    const HalfspaceResult r = SolveHalfspace(c);
    ASSERT_EQ(r.status, SolverStatus::kConverged);
    const double fn = ref["fn"].get<double>();
    // fn and approach to 0.5 %, n_contact ±2 elements; CONTACT prints 4 digits.
    EXPECT_NEAR(r.fn, fn, 0.005 * fn);
    EXPECT_NEAR(r.approach, ref["approach"].get<double>(), 0.005 * ref["approach"].get<double>());
    EXPECT_NEAR(r.n_contact, ref["n_contact"].get<int>(), 2);
    EXPECT_NEAR(r.pmax, ref["pmax"].get<double>(), 0.005 * ref["pmax"].get<double>());
    if (c.effects.tangential) {
      // fx, fs, mn within 0.5 % of μ·fn (mn per mm of the contact size, here taken
      // as 1 mm: all cases have semi-axes of 2-6 mm, so this is stricter), n_slip ±3.
      const double bound = 0.005 * c.friction.mu[0] * fn;
      EXPECT_NEAR(r.fx, ref["fx"].get<double>(), bound);
      EXPECT_NEAR(r.fy, ref["fs"].get<double>(), bound);
      EXPECT_NEAR(r.mz, ref["mn"].get<double>(), bound);
      EXPECT_NEAR(r.n_slip, ref["n_slip"].get<int>(), 3);
    }
  }
}

}  // namespace
}  // namespace wrc
