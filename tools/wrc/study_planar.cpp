#include "tools/wrc/commands.h"
namespace wrc::cli {
void AddPlanarStudy(CLI::App&, int*) {}
}  // namespace wrc::cli
