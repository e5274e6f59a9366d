#include <stdexcept>

#include "core/wheelrail/patch.h"
#include "wrc/errors.h"

namespace wrc::wr {

PatchResult SolveCurvedPatch(const PatchContext&, const PatchExtent&) {
  throw InputError("method.reference = \"curved\" is not available yet");
}

}  // namespace wrc::wr
