// Properties of the wheel–rail solver that need no reference: no contact, bad input,
// left/right mirror symmetry, only the requested effects.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "wrc/core/case.h"
#include "wrc/core/errors.h"
#include "wrc/core/wheelrail.h"

namespace wrc {
namespace {

namespace fs = std::filesystem;

Case Manchester(double y, ReferenceSurface reference) {
  Case c = LoadCase(fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" / "mbench_planar" /
                    "mbench_planar_y0.toml");
  c.state.y = y;
  c.method.reference = reference;
  return c;
}

TEST(WheelRail, WheelAboveTheRailIsNoContact) {
  Case c = Manchester(0.0, ReferenceSurface::kCurved);
  c.state.fz.reset();
  c.state.z = -1.0;  // 1 mm above the rail
  const WheelRailResult r = SolveWheelRail(c);
  EXPECT_EQ(r.status, SolverStatus::kNoContact);
  EXPECT_TRUE(r.patches.empty());
  EXPECT_EQ(r.force_T.norm(), 0.0);
}

TEST(WheelRail, PoseFarOffTheRailIsBadInput) {
  Case c = Manchester(0.0, ReferenceSurface::kPlanar);
  c.state.y = 500.0;
  EXPECT_THROW(SolveWheelRail(c), InputError);
  c.state.y = 0.0;
  c.state.yaw = 1.0;
  EXPECT_THROW(SolveWheelRail(c), InputError);
  c.state.yaw = std::nan("");
  EXPECT_THROW(SolveWheelRail(c), InputError);
}

// A wheel sunk millimetres into the rail is a pose or placement error, reported at once by the
// patch size it would need (left alone it would produce meganewton forces on grids whose
// tangential solve takes minutes); an fz that no solvable height carries names that reason.
TEST(WheelRail, WheelSunkIntoTheRailIsBadInput) {
  Case c = Manchester(0.0, ReferenceSurface::kCurved);
  c.state.fz.reset();
  c.state.z = 5.0;
  try {
    SolveWheelRail(c);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("contact patch needs"), std::string::npos) << e.what();
  }
  c.state.z.reset();
  c.state.fz = 1e10;
  try {
    SolveWheelRail(c);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is not reached before"), std::string::npos) << e.what();
  }
}

// Tread contact on the Manchester pair is well within the half-space model: no warning. The
// ball in a conforming groove (the rail turning by 0.8-1.5 rad across the contact) is solved and
// says that the half-space influence coefficients are strained there.
TEST(WheelRail, WarnsWhereTheHalfSpaceIsStrained) {
  const WheelRailResult tread = SolveWheelRail(Manchester(0.0, ReferenceSurface::kCurved));
  EXPECT_TRUE(tread.warnings.empty());
  const WheelRailResult groove = SolveWheelRail(LoadCase(fs::path(WRC_TEST_DATA_DIR) / "reference" /
                                                         "cases" / "groove" / "groove_r1025.toml"));
  EXPECT_EQ(groove.status, SolverStatus::kConverged);
  // The groove's rail profile also carries a reading warning (its z orientation), prefixed
  // "profile: "; exactly one warning is about the half-space.
  int half_space = 0;
  for (const std::string& w : groove.warnings) {
    if (w.rfind("profile: ", 0) != 0) {
      ++half_space;
      EXPECT_NE(w.find("half-space"), std::string::npos) << w;
    }
  }
  EXPECT_EQ(half_space, 1);
}

int CountContaining(const std::vector<std::string>& warnings, const std::string& text) {
  int n = 0;
  for (const std::string& w : warnings) n += w.find(text) != std::string::npos;
  return n;
}

// The measured MiniProf rail avg_HR.BAN runs from the field side to the gauge side and needs
// mirror_y = true. Without it the rail is placed with its field side as the gauge face and the
// S1002 wheel rests on its flange tip, 27 mm above the nominal position, with status ok and
// plausible-looking forces: the result must say so. Mirrored as it should be, the first contact
// at the nominal position is within 1 mm of z = 0 and nothing is said about the placement.
TEST(WheelRail, MisorientedRailIsRefusedAndTheOrientedOnePlacedNominally) {
  Case c = Manchester(0.0, ReferenceSurface::kCurved);
  c.rail.path = fs::path(WRC_TEST_DATA_DIR) / "profiles" / "avg_HR.BAN";
  c.rail.spline.reset();
  c.rail.mirror_y = false;
  // The orientation check refuses it before the placement check could warn about z = -27 mm.
  try {
    SolveWheelRail(c);
    ADD_FAILURE() << "a MiniProf rail read without mirror_y was solved";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("set mirror_y = true"), std::string::npos) << e.what();
  }
  c.rail.mirror_y = true;
  const WheelRailResult right = SolveWheelRail(c);
  EXPECT_GT(right.z, -1.0);
  EXPECT_LT(right.z, 1.0);
  EXPECT_EQ(CountContaining(right.warnings, "at the nominal position"), 0);
}

// A wheel prescribed 1.2 mm into the rail (first contact at 0.27 mm): an interpenetration of
// about 0.9 mm at the deepest point is under the bound of 1 mm and is solved silently; 1.6 mm
// (1.3 mm deep) carries some 0.5 MN on a coarse grid and is flagged. pmax there stays below
// 1e4 N/mm² (tread radii), so only the depth warns.
TEST(WheelRail, DeepInterpenetrationIsAWarning) {
  Case c = Manchester(0.0, ReferenceSurface::kPlanar);
  c.effects.tangential = false;
  c.grid.dx = c.grid.ds = 1.0;
  c.state.fz.reset();
  c.state.z = 1.2;
  const WheelRailResult shallow = SolveWheelRail(c);
  ASSERT_EQ(shallow.patches.size(), 1u);
  EXPECT_LT(shallow.patches[0].approach, 1.0);
  EXPECT_EQ(CountContaining(shallow.warnings, "interpenetrate"), 0);
  c.state.z = 1.6;
  const WheelRailResult deep = SolveWheelRail(c);
  ASSERT_EQ(deep.patches.size(), 1u);
  EXPECT_GT(deep.patches[0].approach, 1.0);
  EXPECT_EQ(CountContaining(deep.warnings, "mm (more than 1 mm, far beyond any wheel load)"), 1);
  EXPECT_EQ(CountContaining(deep.warnings, "peak pressure"), 0);
}

// Mirror symmetry: a left wheel at −y, −yaw equals the right wheel at +y, +yaw mirrored (the
// same profiles serve both sides, as in CONTACT).
TEST(WheelRail, LeftSideMirrorsRightSide) {
  for (ReferenceSurface ref : {ReferenceSurface::kPlanar, ReferenceSurface::kCurved}) {
    Case right = Manchester(4.0, ref);
    right.state.yaw = 0.004;
    Case left = right;
    left.wheelset.side = WheelSide::kLeft;
    left.state.y = -4.0;
    left.state.yaw = -0.004;
    WheelRailOptions fields;
    fields.keep_fields = true;
    const WheelRailResult a = SolveWheelRail(right, fields);
    const WheelRailResult b = SolveWheelRail(left, fields);
    ASSERT_EQ(a.patches.size(), b.patches.size());
    // Lateral slips, total and rigid alike, change sign with the mirror; longitudinal ones not.
    const PatchResult &pa = a.patches[0], &pb = b.patches[0];
    ASSERT_EQ(pa.ws.size(), pb.ws.size());
    for (std::size_t k = 0; k < pa.ws.size(); ++k) {
      EXPECT_NEAR(pb.ws[k], -pa.ws[k], 1e-12);  // slips ~1e-3: round-off far below
      EXPECT_NEAR(pb.ss[k], -pa.ss[k], 1e-12);
      EXPECT_NEAR(pb.wx[k], pa.wx[k], 1e-12);
    }
    // Identical arithmetic up to the order of operations: 1e-9 of the load.
    const double tol = 1e-9 * a.force_T(2);
    EXPECT_NEAR(b.force_T(0), a.force_T(0), tol);
    EXPECT_NEAR(b.force_T(1), -a.force_T(1), tol);
    EXPECT_NEAR(b.force_T(2), a.force_T(2), tol);
    EXPECT_NEAR(b.z, a.z, 1e-9);
    EXPECT_NEAR(b.patches[0].reference_T(1), -a.patches[0].reference_T(1), 1e-9);
  }
}

// A frictionless scene solves no tangential problem: no tangential iterations, zero longitudinal
// force, and in the planar method zero lateral force. (With the curved reference, fs in the
// reference frame also holds the normal pressure acting on the inclined parts of the surface.)
TEST(WheelRail, FrictionlessSceneSkipsTangentialSolve) {
  for (ReferenceSurface ref : {ReferenceSurface::kPlanar, ReferenceSurface::kCurved}) {
    Case c = Manchester(2.0, ref);
    c.effects.tangential = false;
    const WheelRailResult r = SolveWheelRail(c);
    ASSERT_FALSE(r.patches.empty());
    for (const PatchResult& p : r.patches) {
      EXPECT_EQ(p.fx, 0.0);
      if (ref == ReferenceSurface::kPlanar) {
        EXPECT_EQ(p.fs, 0.0);
      }
      EXPECT_EQ(p.tangential_iterations, 0);
    }
    EXPECT_NEAR(r.force_T(2), 10000.0, 1e-6 * 10000.0);
  }
}

// The resultant's location (paper Eq. 25–27) lies on the rail surface, and about it the
// moment of the tractions is parallel to the force (its perpendicular part vanishes).
TEST(WheelRail, ForceLocationLeavesOnlyAParallelMoment) {
  const WheelRailResult r = SolveWheelRail(Manchester(6.0, ReferenceSurface::kCurved));
  ASSERT_TRUE(r.has_force_location);
  const Eigen::Vector3d& f = r.force_T;
  const Eigen::Vector3d m_loc = r.moment_T - (r.force_location_T - r.rail_origin_T).cross(f);
  // |M⊥| relative to |M|: round-off of sums over ~1000 elements, 1e-9.
  EXPECT_LT(m_loc.cross(f).norm() / f.norm(), 1e-9 * r.moment_T.norm());
  // The location lies between the outer patches.
  EXPECT_GT(r.force_location_T(1), r.patches.back().reference_T(1));
  EXPECT_LT(r.force_location_T(1), r.patches.front().reference_T(1));
  // For three vertical-ish patch forces the lateral location is their fn-weighted mean to
  // within the lever of the small lateral forces (z differences of a few mm × fy/fz ≈ 0.1 mm).
  double sum = 0.0, weighted = 0.0;
  for (const PatchResult& p : r.patches) {
    sum += p.force_T(2);
    weighted += p.force_T(2) * p.reference_T(1);
  }
  EXPECT_NEAR(r.force_location_T(1), weighted / sum, 0.5);
}

// The solve box (the bounding box of the interpenetration) gives the solution of the whole
// potential contact area: contact needs h < 0 for identical bodies. Three patches at y = 6 mm,
// a two-patch flange contact with yaw on the heavy-haul pair.
TEST(WheelRail, SolveBoxGivesTheSolutionOfTheWholeArea) {
  std::vector<Case> cases = {Manchester(6.0, ReferenceSurface::kCurved),
                             LoadCase(fs::path(WRC_TEST_DATA_DIR) / "reference" / "cases" /
                                      "heavy_haul" / "heavy_haul_z1.162.toml")};
  for (const Case& c : cases) {
    WheelRailOptions whole;
    whole.solve_box = false;
    const WheelRailResult a = SolveWheelRail(c);
    const WheelRailResult b = SolveWheelRail(c, whole);
    ASSERT_EQ(a.status, SolverStatus::kConverged) << c.source_name;
    ASSERT_EQ(b.status, SolverStatus::kConverged) << c.source_name;
    ASSERT_EQ(a.patches.size(), b.patches.size()) << c.source_name;
    // Both are converged to the solvers' tolerances (1e-8 normal, 1e-7 tangential relative),
    // from different starting points: 1e-6 of the load leaves room for that and nothing else.
    const double load = b.force_T.norm();
    EXPECT_LT((a.force_T - b.force_T).norm(), 1e-6 * load) << c.source_name;
    for (std::size_t k = 0; k < a.patches.size(); ++k) {
      EXPECT_EQ(a.patches[k].n_contact, b.patches[k].n_contact) << c.source_name;
      EXPECT_EQ(a.patches[k].n_slip, b.patches[k].n_slip) << c.source_name;
      EXPECT_EQ(a.patches[k].n_pot, b.patches[k].n_pot) << c.source_name;
    }
  }
}

// Dissimilar bodies (K != 0) are solved with the normal–tangential coupling. Swapping the two
// materials keeps the combined stiffness and flips the sign of K: both solves converge and meet
// fz, and their creep forces differ (by the coupling) but only slightly.
TEST(WheelRail, DissimilarBodiesAreCoupled) {
  Case soft_wheel = Manchester(2.0, ReferenceSurface::kCurved);
  soft_wheel.wheel_material = {60000.0, 0.33};
  Case soft_rail = soft_wheel;
  std::swap(soft_rail.rail_material, soft_rail.wheel_material);
  const WheelRailResult a = SolveWheelRail(soft_wheel);
  const WheelRailResult b = SolveWheelRail(soft_rail);
  for (const WheelRailResult* r : {&a, &b}) {
    ASSERT_EQ(r->status, SolverStatus::kConverged);
    EXPECT_NEAR(r->force_T(2), 10000.0, 1e-6 * 10000.0);
  }
  const double difference = std::fabs(a.force_T(0) - b.force_T(0));
  EXPECT_GT(difference, 1e-4 * std::fabs(a.force_T(0)));
  EXPECT_LT(difference, 0.1 * std::fabs(a.force_T(0)));
}

// LoadCase reads the profiles once and the solver uses them; a case built in code (no spline)
// is read by the solver itself, with the same result to the last bit.
TEST(WheelRail, ProfilesReadByLoadCaseAreReused) {
  const Case loaded = Manchester(4.0, ReferenceSurface::kCurved);
  ASSERT_TRUE(loaded.rail.spline);
  ASSERT_TRUE(loaded.wheel.spline);
  Case from_files = loaded;
  from_files.rail.spline.reset();
  from_files.wheel.spline.reset();
  const WheelRailResult a = SolveWheelRail(loaded);
  const WheelRailResult b = SolveWheelRail(from_files);
  EXPECT_EQ(a.force_T, b.force_T);
  EXPECT_EQ(a.moment_T, b.moment_T);
}

}  // namespace
}  // namespace wrc
