// `wrc plot profiles`: wheel and rail of a wheel–rail case in place (track frame, y lateral, z
// down) at the solved wheelset pose, the contact patches along the rail with their normals, and
// the gap between the undeformed profiles along the rail.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "tools/angles.h"
#include "tools/wrc/gnuplot.h"
#include "tools/wrc/output_text.h"
#include "tools/wrc/plot.h"
#include "wrc/core/case.h"
#include "wrc/core/errors.h"
#include "wrc/core/profile.h"
#include "wrc/core/profile_placement.h"
#include "wrc/core/wheelrail.h"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

// Points along each profile for the drawing: finer than any feature that matters at the
// picture's scale (about 0.1 mm per pixel).
constexpr double kDrawStep = 0.1;
// Length of the drawn contact normals, mm: long enough to be seen beside a 100 mm profile.
constexpr double kNormalLength = 12.0;

// What the drawing needs of a solve; everything in the right-side equivalent frame (a left case
// is solved, and drawn, as its mirror image, then mirrored back for the files).
struct Pose {
  WheelsetPlacement placement;
  double mirror = 1.0;
  bool solved = false;
  std::vector<PatchResult> patches;
};

// Solves the case for its wheelset height and patches. A case that does not solve (an fz that
// no height carries, a patch too large) is still drawn, at its prescribed z or at first
// contact, without patches: the picture then shows what is wrong with the placement.
Pose SolvePose(const Case& c) {
  Pose pose;
  pose.mirror = c.wheelset.side == WheelSide::kLeft ? -1.0 : 1.0;
  pose.placement.y = pose.mirror * c.state.y;
  pose.placement.roll = pose.mirror * c.state.roll;
  pose.placement.yaw = pose.mirror * c.state.yaw;
  try {
    WheelRailOptions options;
    options.keep_fields = true;
    WheelRailResult r = SolveWheelRail(c, options);
    pose.placement.z = r.z;
    pose.solved = true;
    pose.patches = std::move(r.patches);
  } catch (const InputError& e) {
    std::cerr << "wrc plot profiles: the case does not solve (" << e.what()
              << "); the profiles are drawn without contact patches\n";
    if (c.state.z) {
      pose.placement.z = *c.state.z;
    } else {
      pose.placement.z = FirstContactHeight(c, pose.placement, kDrawStep);
      if (!std::isfinite(pose.placement.z)) pose.placement.z = 0.0;
    }
  }
  return pose;
}

// One surface in the track frame: y z per line.
void WriteSurface(const fs::path& path, const char* header, const std::vector<double>& y,
                  const std::vector<double>& z, double mirror) {
  OutputText dat(path);
  dat << header;
  for (std::size_t k = 0; k < y.size(); ++k) dat << mirror * y[k] << ' ' << z[k] << '\n';
  dat.Commit();
}

// The gap along the rail at the contact locus (the smallest vertical distance between the
// undeformed surfaces over x at each rail point), at the drawn wheelset height; negative where
// they interpenetrate.
struct GapRange {
  double y_min = 1e300, y_max = -1e300, gap_min = 1e300;
};

GapRange WriteGap(const fs::path& path, const std::vector<GapSample>& gap, double mirror) {
  OutputText dat(path);
  dat << "# gap along the rail at the drawn wheelset height: y_mm (rail point, track frame) "
         "gap_mm (vertical, negative: interpenetration) x_mm (contact locus)\n";
  GapRange range;
  for (const GapSample& s : gap) {
    dat << mirror * s.y << ' ' << s.gap << ' ' << s.x << '\n';
    range.y_min = std::min(range.y_min, mirror * s.y);
    range.y_max = std::max(range.y_max, mirror * s.y);
    range.gap_min = std::min(range.gap_min, s.gap);
  }
  dat.Commit();
  return range;
}

// Rows j of a patch's grid that hold an element in contact: first and last, or nullopt.
std::optional<std::pair<int, int>> ContactRows(const PatchResult& p) {
  int first = -1, last = -1;
  for (int j = 0; j < p.grid.ny; ++j) {
    for (int i = 0; i < p.grid.nx; ++i) {
      if (p.pn[p.grid.index(i, j)] > 0.0) {
        if (first < 0) first = j;
        last = j;
        break;
      }
    }
  }
  if (first < 0) return std::nullopt;
  return std::make_pair(first, last);
}

// Track-frame point (y, z) of lateral position s (row j) of a patch in the case's frame. The
// curved reference's curve is stored in that frame; the planar one is a line through the
// reference along (cos δ, sin δ) in the right-side equivalent frame (s is not mirrored).
Eigen::Vector2d PatchPoint(const PatchResult& p, double mirror, int j, double s) {
  if (!p.curve_y.empty()) return {p.curve_y[j], p.curve_z[j]};
  const double angle = mirror * p.contact_angle;
  const Eigen::Vector2d right = Eigen::Vector2d(mirror * p.reference_T(1), p.reference_T(2)) +
                                s * Eigen::Vector2d(std::cos(angle), std::sin(angle));
  return {mirror * right(0), right(1)};
}

// Per patch: its extent along the profile (the rows in contact, one data block) and its normal
// at the reference (one segment in the second file), labelled with the contact angle.
void WritePatches(const fs::path& extents, const fs::path& normals, const Pose& pose,
                  std::string* labels) {
  OutputText ext(extents), nor(normals);
  ext << "# per patch (blocks): y_mm z_mm of the elements in contact along s, track frame\n";
  nor << "# per patch: y_mm z_mm dy_mm dz_mm (the contact normal into the rail, from "
         "above the reference point) contact_angle_deg\n";
  for (std::size_t n = 0; n < pose.patches.size(); ++n) {
    const PatchResult& p = pose.patches[n];
    const auto rows = ContactRows(p);
    if (!rows) continue;
    // The rows' centres, and half an element beyond the outer ones: the contact's edges.
    const double half = 0.5 * p.grid.dy;
    auto edge = [&](int j, int inward) {
      const Eigen::Vector2d c = PatchPoint(p, pose.mirror, j, p.grid.y(j));
      const int k = std::clamp(j + inward, 0, p.grid.ny - 1);
      if (k == j) return c;
      const Eigen::Vector2d d = PatchPoint(p, pose.mirror, k, p.grid.y(k)) - c;
      return Eigen::Vector2d(c - half * d / d.norm());
    };
    std::vector<Eigen::Vector2d> points{edge(rows->first, 1)};
    for (int j = rows->first; j <= rows->second; ++j) {
      points.push_back(PatchPoint(p, pose.mirror, j, p.grid.y(j)));
    }
    points.push_back(edge(rows->second, -1));
    for (const Eigen::Vector2d& q : points) ext << q(0) << ' ' << q(1) << '\n';
    ext << "\n\n";
    // In the case's frame the normal into the rail is (−sin δ, cos δ) with δ the contact angle.
    const double angle = p.contact_angle;
    const Eigen::Vector2d normal(-std::sin(angle), std::cos(angle));
    const Eigen::Vector2d ref(p.reference_T(1), p.reference_T(2));
    const Eigen::Vector2d tail = ref - kNormalLength * normal;
    nor << tail(0) << ' ' << tail(1) << ' ' << kNormalLength * normal(0) << ' '
        << kNormalLength * normal(1) << ' ' << tools::Degrees(angle) << '\n';
    *labels += "set label " + std::to_string(n + 1) + " 'patch " + std::to_string(n + 1) + ": " +
               Short(tools::Degrees(angle), 3) + "°, Fn " + Short(p.fn, 3) + " N' at " +
               Short(tail(0), 6) + "," + Short(tail(1), 6) + " offset char 1,0.5 front\n";
  }
  ext.Commit();
  nor.Commit();
}

// The drawing's y range: where wheel and rail overlap laterally, with a margin.
struct View {
  double y0 = 0.0, y1 = 0.0, z0 = 0.0, z1 = 0.0;
};

View ViewOf(const fs::path& rail, const fs::path& wheel, const fs::path& normals) {
  double ry0 = 1e300, ry1 = -1e300, wy0 = 1e300, wy1 = -1e300, z0 = 1e300, z1 = -1e300;
  auto scan = [&](const fs::path& path, double& y0, double& y1) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream cells(line);
      double y, z;
      cells >> y >> z;
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
      z0 = std::min(z0, z);
      z1 = std::max(z1, z);
    }
  };
  scan(rail, ry0, ry1);
  scan(wheel, wy0, wy1);
  scan(normals, wy0, wy1);  // the normals' tails, above the contact
  View v;
  const double margin = 5.0;  // mm
  v.y0 = std::min(ry0, wy0) - margin;
  v.y1 = std::max(ry1, wy1) + margin;
  v.z0 = z0 - margin;
  v.z1 = z1 + margin;
  return v;
}

std::string ProfilesScript(const View& v, const GapRange& gap, const std::string& title,
                           const std::string& labels) {
  // The upper panel has equal scales on y and z: its height follows from the width.
  const double width_px = 1100.0, left = 90.0, right = 30.0, top = 50.0, gap_px = 260.0;
  const double plot_w = width_px - left - right;
  const double upper_h = std::clamp(plot_w * (v.z1 - v.z0) / (v.y1 - v.y0), 150.0, 1100.0);
  const double height_px = top + upper_h + 60.0 + gap_px + 50.0;
  auto sx = [&](double px) { return Short(px / width_px, 5); };
  auto sy = [&](double px) { return Short(1.0 - px / height_px, 5); };
  // The gap panel shows the interpenetration and the first 2 mm of clearance: enough to see
  // where a second contact is near (the flange) without flattening the contact itself.
  const double gap_top = 2.0;
  std::ostringstream gp;
  gp << "set terminal pngcairo noenhanced size " << width_px << ',' << static_cast<int>(height_px)
     << " font ',10'\nset output 'profiles.png'\nset multiplot title \"" << title << "\"\n"
     << "set lmargin at screen " << sx(left) << "\nset rmargin at screen " << sx(width_px - right)
     << "\nset tmargin at screen " << sy(top) << "\nset bmargin at screen " << sy(top + upper_h)
     << "\n"
     << "set xrange [" << v.y0 << ':' << v.y1 << "]\nset yrange [" << v.z1 << ':' << v.z0
     << "]\nset size ratio -1\n"
     << "set grid\nset format x ''\nset ylabel 'z, mm (down)'\nset key top left box opaque\n"
     << labels
     << "plot 'profiles_rail.dat' with lines lw 2 lc rgb '#404040' title 'rail', "
        "'profiles_wheel.dat' with lines lw 2 lc rgb '#2166ac' title 'wheel (principal plane)', "
        "'profiles_patches.dat' with lines lw 6 lc rgb '#d6604d' title 'contact patch (extent "
        "along s)', 'profiles_normals.dat' using 1:2:3:4 with vectors head filled lw 1.5 "
        "lc rgb '#b2182b' title 'contact normal'\n"
     << "unset label\nset size noratio\nset tmargin at screen " << sy(top + upper_h + 60.0)
     << "\nset bmargin at screen " << sy(top + upper_h + 60.0 + gap_px) << "\n"
     << "set format x '%g'\nset xlabel 'y, mm (track frame, lateral)'\n"
     << "set ylabel 'gap, mm'\nset yrange [" << std::min(-0.05, 1.2 * gap.gap_min) << ':' << gap_top
     << "]\nset key top right box opaque\n"
     << "plot 'profiles_gap.dat' using 1:2 with lines lw 2 lc rgb '#1b7837' title 'gap between "
        "the undeformed profiles (negative: interpenetration)', 0 with lines dt 2 lc rgb "
        "'#000000' notitle\n"
     << "unset multiplot\n";
  return gp.str();
}

std::string ProfilesTitle(const Case& c, const Pose& pose) {
  std::string title = fs::path(c.source_name).filename().string() + ": " +
                      (c.wheelset.side == WheelSide::kLeft ? "left" : "right") + " wheel, y " +
                      Short(c.state.y) + " mm, z " + Short(pose.placement.z) + " mm, roll " +
                      Short(c.state.roll, 3) + " rad, yaw " + Short(c.state.yaw, 3) + " rad";
  title += pose.solved ? ", " + std::to_string(pose.patches.size()) + " patch(es)"
                       : " (not solved: no patches)";
  return title;
}

}  // namespace

WrittenFiles PlotProfiles(const fs::path& case_path, const fs::path& out) {
  const Case c = LoadCase(case_path);
  if (c.type != CaseType::kWheelRail) {
    throw InputError(case_path.string() +
                     ": a half-space case has no profiles; `wrc plot profiles` needs a "
                     "wheel-rail case");
  }
  const Pose pose = SolvePose(c);
  const PlacedProfiles placed = PlaceProfiles(c, pose.placement, kDrawStep);
  fs::create_directories(out);
  WrittenFiles written;
  for (const char* name : {"profiles_rail.dat", "profiles_wheel.dat", "profiles_gap.dat",
                           "profiles_patches.dat", "profiles_normals.dat"}) {
    written.push_back(out / name);
  }
  WriteSurface(written[0], "# rail surface, track frame: y_mm z_mm (z down)\n", placed.rail_y,
               placed.rail_z, pose.mirror);
  WriteSurface(written[1],
               "# wheel profile in the wheelset's principal plane, track frame: y_mm z_mm "
               "(z down)\n",
               placed.wheel_y, placed.wheel_z, pose.mirror);
  const GapRange gap = WriteGap(written[2], placed.gap, pose.mirror);
  std::string labels;
  WritePatches(written[3], written[4], pose, &labels);
  const std::string script = ProfilesScript(ViewOf(written[0], written[1], written[4]), gap,
                                            ProfilesTitle(c, pose), labels);
  if (!RunGnuplot(out, "profiles.gp", script)) {
    std::cerr << "wrc plot profiles: gnuplot is not installed (Debian: gnuplot-nox): "
              << "no picture, the data is written\n";
    return written;
  }
  written.push_back(out / "profiles.gp");
  written.push_back(out / "profiles.png");
  return written;
}

}  // namespace wrc::cli
