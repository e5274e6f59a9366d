// `wrc export TABLE.h5 -o TABLE.wrct`: the table as a flat file (runtime/format/flat_table.h)
// for a runtime built without HDF5. The table is read by the runtime's own reader, so a table
// the runtime would refuse is refused here, for the same reason, and the flat file holds
// exactly what the runtime would have loaded.

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "runtime/format/flat_table.h"
#include "tools/wrc/commands.h"
#include "wrc/core/output_file.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

void Export(const std::string& input, const std::string& output) {
  RequireRegularOutput(output);
  RequireNotAnInput(output, {input});
  const format::TableContent content = format::ReadTableContent(input);
  if (!content.warning.empty()) std::cerr << "wrc export: warning: " << content.warning << '\n';
  format::WriteFlatTable(content, output);
  std::cout << "wrc export: wrote " << output << ": " << content.axes.size() << " axes, "
            << content.outputs.size() << " outputs, " << content.num_nodes() << " nodes, "
            << fs::file_size(output) << " bytes\n";
}

}  // namespace

void AddExportCommand(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand(
      "export", "Write a table as a flat file (.wrct) for a runtime built without HDF5");
  auto input = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  cmd->add_option("TABLE", *input, "Table file (HDF5, or a flat table to copy)")->required();
  cmd->add_option("-o,--output", *output, "The flat table to write (replaced if it exists)")
      ->required();
  cmd->callback([=]() {
    try {
      Export(*input, *output);
      FinishStandardOutput();
      *exit_code = kExitOk;
    } catch (...) {
      *exit_code = ReportFailure("wrc export");
    }
  });
}

}  // namespace wrc::cli
