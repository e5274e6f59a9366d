// libFuzzer target for the scene parser (include/wrc/core/scene.h): arbitrary bytes as scene file
// text; an accepted scene is also expanded at its first and last grid node. wrc::InputError is
// the expected answer to bad input; any other exception escapes and aborts, so that libFuzzer
// reports it together with the input.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "wrc/core/errors.h"
#include "wrc/core/scene.h"

namespace {

void Check(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz_scene: accepted scene breaks: %s\n", what);
  std::abort();
}

void ExerciseScene(const wrc::Scene& scene) {
  Check(!scene.axes.empty(), "at least one axis");
  Check(!scene.outputs.empty(), "at least one output");
  std::vector<std::size_t> first(scene.axes.size(), 0);
  std::vector<std::size_t> last;
  for (const wrc::SceneAxis& axis : scene.axes) {
    Check(!axis.values.empty(), "axis values given");
    for (std::size_t i = 0; i < axis.values.size(); ++i) {
      Check(std::isfinite(axis.values[i]), "finite axis values");
      if (i > 0) Check(axis.values[i] > axis.values[i - 1], "strictly ascending axis values");
    }
    last.push_back(axis.values.size() - 1);
  }
  Check(scene.PointCount() > 0, "PointCount() > 0");
  // Grid nodes passed the file's checks, so CaseAtIndex must accept them without an InputError.
  try {
    wrc::CaseAtIndex(scene, first);
    wrc::CaseAtIndex(scene, last);
  } catch (const wrc::InputError& error) {
    std::fprintf(stderr, "fuzz_scene: grid node refused: %s\n", error.what());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    ExerciseScene(wrc::ParseScene(text, "/nonexistent/scenes", "fuzz_scene.toml"));
  } catch (const wrc::InputError&) {
    // Bad input, reported as documented.
  }
  return 0;
}
