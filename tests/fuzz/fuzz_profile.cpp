// libFuzzer target for the profile readers (include/wrc/core/profile.h): arbitrary bytes as a
// profile file of each format, read as a rail and as a wheel, repaired, and, when that succeeds,
// turned into a ProfileSpline that is evaluated at a few places.
//
// Input layout: byte 0 selects the file name extension (byte % 5: .prr .prw .ban .whl .csv) and
// two options ((byte / 5) bit 0: smoothing 2 mm, bit 1: mirror_y); the remaining bytes are the
// file. wrc::InputError is the expected answer to bad input; any other exception escapes and
// aborts, so that libFuzzer reports it together with the input.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "wrc/core/errors.h"
#include "wrc/core/profile.h"

namespace {

constexpr const char* kExtensions[] = {".prr", ".prw", ".ban", ".whl", ".csv"};
constexpr std::size_t kExtensionCount = sizeof kExtensions / sizeof kExtensions[0];

// One file per extension and process: libFuzzer's -fork/-jobs run several processes at once.
std::string TempProfilePath(std::size_t extension) {
  const char* dir = std::getenv("TMPDIR");
  std::string path = (dir != nullptr && *dir != '\0') ? dir : "/tmp";
  return path + "/wrc_fuzz_profile_" + std::to_string(::getpid()) + kExtensions[extension];
}

bool WriteFile(const std::string& path, const std::uint8_t* data, std::size_t size) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) return false;
  const bool written = size == 0 || std::fwrite(data, 1, size, file) == size;
  return std::fclose(file) == 0 && written;
}

// A broken invariant of an accepted profile is a bug like a crash: report it and abort.
void Check(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz_profile: invariant broken: %s\n", what);
  std::abort();
}

void ExerciseSpline(const wrc::Profile& profile) {
  Check(profile.size() >= 4, "a repaired profile has at least 4 points");
  for (std::size_t i = 0; i < profile.size(); ++i) {
    Check(std::isfinite(profile.y[i]) && std::isfinite(profile.z[i]), "finite profile points");
  }
  wrc::ProfileSpline spline(profile);
  const double length = spline.length();
  Check(std::isfinite(length) && length > 0.0, "finite positive spline length");
  for (const double fraction : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const wrc::ProfileVector point = spline.PositionAt(fraction * length);
    Check(std::isfinite(point.y) && std::isfinite(point.z), "finite PositionAt");
  }
  const double y_min = spline.YMin();
  const double y_max = spline.YMax();
  Check(y_min <= y_max, "YMin <= YMax");
  for (const double y : {y_min, 0.5 * (y_min + y_max), y_max, profile.y[profile.size() / 2],
                         y_max + 1.0, y_min - 1.0}) {
    const wrc::ProfileHeight height = spline.ZAtY(y);
    if (height.found()) {
      Check(std::isfinite(height.z) && std::isfinite(height.s), "finite ZAtY inside the profile");
    }
  }
}

void ReadAs(const std::string& path, wrc::ProfileKind kind, const wrc::ProfileOptions& options) {
  try {
    const wrc::Profile profile = wrc::ReadProfile(path, kind, options);
    ExerciseSpline(profile);
  } catch (const wrc::InputError&) {
    // Bad input, reported as documented.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t extension = data[0] % kExtensionCount;
  const unsigned option_bits = data[0] / kExtensionCount;
  wrc::ProfileOptions options;
  options.smoothing = (option_bits & 1u) != 0 ? 2.0 : 0.0;
  options.mirror_y = (option_bits & 2u) != 0;

  const std::string path = TempProfilePath(extension);
  if (!WriteFile(path, data + 1, size - 1)) {
    std::fprintf(stderr, "fuzz_profile: cannot write %s\n", path.c_str());
    std::abort();
  }
  try {
    const wrc::ProfilePoints points = wrc::ReadProfilePoints(path);
    Check(points.y.size() == points.z.size() && points.y.size() == points.lines.size(),
          "ReadProfilePoints gives equally long y, z and lines");
  } catch (const wrc::InputError&) {
  }
  ReadAs(path, wrc::ProfileKind::kRail, options);
  ReadAs(path, wrc::ProfileKind::kWheel, options);
  std::remove(path.c_str());
  return 0;
}
