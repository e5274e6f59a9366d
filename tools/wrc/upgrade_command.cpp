// `wrc upgrade OLD.h5 -o NEW.h5`: a table written before tables were sealed, or before they
// stored their fixed state typed, rewritten in the checksummed format with a seal and that state.
// The old file is read in a child process: in HDF5's earliest format its metadata carries no
// checksums, and HDF5 1.10 can crash on a damaged byte of it.

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "runtime/hdf5/hdf5.h"
#include "runtime/hdf5/seal.h"
#include "runtime/hdf5/table_schema.h"
#include "tools/wrc/commands.h"
#include "wrc/core/errors.h"
#include "wrc/core/output_file.h"
#include "wrc/core/scene.h"
#include "wrc/generator/generator.h"
#include "wrc/runtime.hpp"

namespace wrc::cli {
namespace {

namespace fs = std::filesystem;

// A table written before tables stored their fixed state typed gets it from its own scene text,
// parsed as the generator parses a scene (the profiles are not needed for it), so that the
// wheelset API and `wrc info` read the upgraded table as a new one. A scene this build no longer
// parses keeps the table as it was: the runtime then reads the text, as before.
void AddFixedState(h5::File& target, const std::string& old) {
  if (target.HasAttribute(schema::kWheelsetVelocity) || !target.HasAttribute(schema::kScene)) {
    return;
  }
  try {
    const Scene scene = ParseScene(target.ReadStringAttribute(schema::kScene),
                                   fs::path(old).parent_path(), old + ":/scene");
    WriteFixedStateAttributes(target, scene);
  } catch (const InputError& e) {
    std::cerr << "wrc upgrade: warning: the fixed state stays in the scene text only: " << e.what()
              << '\n';
  }
}

// In the child: every member and root attribute of `old` into `copy`, sealed and read back.
// The child's failure message goes to `report` (a pipe) and its class to the exit code
// (FailureOf): exceptions cannot cross the fork.
[[noreturn]] void CopyInChild(const std::string& old, const std::string& copy, int report) {
  int code = 0;
  try {
    const h5::File source =
        h5::File::Open(old, h5::File::Mode::kReadOnly, h5::File::Earliest::kAllow);
    {
      h5::File target = h5::File::Create(copy, true, h5::FileFormat::kChecksummed, true);
      h5::CopyContents(source, &target);
      AddFixedState(target, old);
      target.Flush();
    }
    h5::SealFile(copy);
    // Every check and read a command makes, still in the child: HDF5 copies damaged content
    // it can parse faithfully, and the copy may crash HDF5 where the original did.
    const Table checked(copy);
    (void)ReadTableInfo(copy);
  } catch (...) {
    const Failure failure = FailureOf(std::current_exception());
    const std::string& text = failure.message;
    code = ::write(report, text.data(), text.size()) < 0 ? kExitBadInput : failure.exit_code;
  }
  _exit(code);  // _exit: neither the parent's buffered output nor its atexit handlers run twice
}

std::string ReadAll(int fd) {
  std::string text;
  char buffer[512];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return text;
    text.append(buffer, static_cast<std::size_t>(got));
  }
}

// Runs CopyInChild and turns its end into an exception naming the old table.
void CopyContained(const std::string& old, const std::string& copy) {
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0)
    throw InputError(std::string("cannot make a pipe: ") + std::strerror(errno));
  std::cout.flush();
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    throw InputError(std::string("cannot start a process: ") + std::strerror(errno));
  }
  if (child == 0) {
    ::close(pipe_fds[0]);
    CopyInChild(old, copy, pipe_fds[1]);
  }
  ::close(pipe_fds[1]);
  const std::string message = ReadAll(pipe_fds[0]);
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0) {
    if (errno != EINTR)
      throw InputError(std::string("lost the copying process: ") + std::strerror(errno));
  }
  if (WIFSIGNALED(status)) {
    throw InputError(old + ": damaged: reading it crashed the HDF5 library (signal " +
                     std::to_string(WTERMSIG(status)) + "); it cannot be upgraded, regenerate it");
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == kExitBug) throw std::logic_error(message);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw InputError(message.empty() ? old + ": cannot be copied" : message);
  }
}

void Upgrade(const fs::path& old, const fs::path& output) {
  if (!fs::is_regular_file(old)) throw InputError(old.string() + ": not a regular file");
  RequireRegularOutput(output);
  RequireNotAnInput(output, {old});
  const fs::path temporary = output.string() + ".tmp";
  CreateExclusively(temporary);
  try {
    CopyContained(old.string(), temporary.string());
    RequireRegularOutput(temporary);
    fs::rename(temporary, output);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

}  // namespace

void AddUpgradeCommand(CLI::App& app, int* exit_code) {
  auto* cmd = app.add_subcommand(
      "upgrade", "Rewrite a table written before tables were sealed: checksummed and sealed");
  auto old = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  cmd->add_option("TABLE", *old, "Table file (HDF5) written by an earlier wrc generate")
      ->required();
  cmd->add_option("-o,--output", *output, "The upgraded table (a new file)")->required();
  cmd->callback([=]() {
    try {
      Upgrade(*old, *output);
      std::cout << "wrc upgrade: wrote " << *output << " (sealed)\n";
      FinishStandardOutput();
      *exit_code = kExitOk;
    } catch (...) {
      *exit_code = ReportFailure("wrc upgrade");
    }
  });
}

}  // namespace wrc::cli
