#include "studies/studies.h"

#include "studies/study_commands.h"

namespace wrc::cli {

void AddStudyCommand(CLI::App& app, int* exit_code) {
  auto* study = app.add_subcommand("study", "Studies of accuracy, cost and stability");
  study->require_subcommand(1);
  AddCostStudies(*study, exit_code);
  AddStabilityStudy(*study, exit_code);
  AddDynamicsStudy(*study, exit_code);
  AddPaperStudy(*study, exit_code);
  AddPlanarStudy(*study, exit_code);
}

}  // namespace wrc::cli
