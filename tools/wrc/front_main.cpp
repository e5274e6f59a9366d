// wrc: the front end of the command-line tool. `wrc solve` runs here, in a process that loads
// only the solver's libraries; every other command is handed to wrc-tables (see
// tools/CMakeLists.txt for why there are two executables).

#include <unistd.h>

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#endif

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

#include "tools/wrc/commands.h"

namespace {

// wrc-tables next to this executable (build tree and install tree alike).
std::filesystem::path TablesExecutable() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "wrc-tables";  // execvp then searches PATH
  return self.parent_path() / "wrc-tables";
}

// A solve is a short process that touches 5–20 MB of fresh memory (FFT spectra, grid fields,
// influence tables), and on a 4 KiB page each first touch is a page fault: ~5000 faults and
// ~10 % of a heavy-haul solve. Freed buffers stay in the heap for the next solve step (no
// mmap/munmap per large buffer), and the heap asks for transparent huge pages, so a 2 MiB
// stretch costs one fault. Only placement of memory changes, never results. Linux/glibc only.
void PrepareHeap() {
#if defined(__linux__) && defined(__GLIBC__)
  constexpr int kHeapChunk = 32 << 20;  // heap growth per sbrk
  constexpr std::size_t kHugePage = 2 << 20;
  mallopt(M_MMAP_THRESHOLD, 16 << 20);   // big buffers from the heap (glibc caps this at 32 MiB)
  mallopt(M_TRIM_THRESHOLD, 256 << 20);  // freed memory is kept, not returned
  mallopt(M_TOP_PAD, kHeapChunk);
  auto* before = static_cast<char*>(sbrk(0));
  // More than the heap has left, so it grows by kHeapChunk; volatile so that the compiler
  // cannot drop the malloc/free pair.
  void* volatile probe = std::malloc(1 << 20);
  auto* after = static_cast<char*>(sbrk(0));
  const auto first = (reinterpret_cast<std::uintptr_t>(before) + kHugePage - 1) & ~(kHugePage - 1);
  const auto last = reinterpret_cast<std::uintptr_t>(after) & ~(kHugePage - 1);
  if (before != reinterpret_cast<char*>(-1) && last > first) {
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);  // advice only
  }
  std::free(probe);
#endif
}

int RunSolve(int argc, char** argv) {
  PrepareHeap();
  CLI::App app{"wrc: wheel-rail contact solver, table generator and verifier"};
  app.require_subcommand(1);
  int exit_code = wrc::cli::kExitOk;
  wrc::cli::AddSolveCommand(app, &exit_code);
  return wrc::cli::RunCommandLine(app, argc, argv, exit_code);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "solve") return RunSolve(argc, argv);
  // Same pid, arguments and environment: an MPI launcher's rank variables reach wrc-tables.
  const std::string tables = TablesExecutable().string();
  // argv[0] stays "wrc" so that usage and error lines name the command the user typed.
  execvp(tables.c_str(), argv);
  std::cerr << "wrc: cannot start " << tables << " (needed for '" << (argc >= 2 ? argv[1] : "")
            << "'): " << std::strerror(errno) << "\n";
  return 1;
}
