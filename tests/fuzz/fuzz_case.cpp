// libFuzzer target for the case parser (include/wrc/core/case.h): arbitrary bytes as case file
// text. wrc::InputError is the expected answer to bad input; any other exception escapes and
// aborts, so that libFuzzer reports it together with the input. An accepted case must hold the
// values that ParseCase promises to have validated.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "wrc/core/case.h"
#include "wrc/core/errors.h"

namespace {

void Check(bool condition, const char* what) {
  if (condition) return;
  std::fprintf(stderr, "fuzz_case: accepted case breaks: %s\n", what);
  std::abort();
}

void CheckValidated(const wrc::Case& parsed) {
  Check(parsed.grid.dx > 0.0 && std::isfinite(parsed.grid.dx), "grid.dx > 0");
  Check(!parsed.friction.mu.empty(), "friction.mu given");
  for (const double mu : parsed.friction.mu) Check(mu >= 0.0 && std::isfinite(mu), "mu >= 0");
  if (parsed.type == wrc::CaseType::kWheelRail) {
    Check(parsed.grid.ds > 0.0, "grid.ds > 0");
    Check(parsed.state.z.has_value() != parsed.state.fz.has_value(), "exactly one of z, fz");
    Check(parsed.wheelset.nominal_radius > 0.0, "wheelset.nominal_radius > 0");
    Check(std::isfinite(parsed.state.omega), "finite omega");
  } else {
    Check(parsed.grid.dy > 0.0, "grid.dy > 0");
    Check(parsed.halfspace_state.fn.has_value() != parsed.halfspace_state.approach.has_value(),
          "exactly one of fn, approach");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    CheckValidated(wrc::ParseCase(text, "/nonexistent/cases", "fuzz_case.toml"));
  } catch (const wrc::InputError&) {
    // Bad input, reported as documented.
  }
  return 0;
}
