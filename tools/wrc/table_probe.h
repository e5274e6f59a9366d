#pragma once
// A first read of a table in a child process, for tables whose HDF5 metadata has no checksums.

#include <string>

namespace wrc::cli {

/// Tables in HDF5's earliest format (superblock version 0 or 1, what tables were written in
/// before metadata checksums) are read once in a forked child first: every read a command makes
/// (the runtime's checks, what `wrc info` shows, the stored scene). HDF5 1.10 can crash on
/// damaged metadata it cannot check (found by fuzzing: SIGSEGV in H5Aexists on a damaged root
/// header), before wrc sees the damage; a crash of the child is then this error instead of a
/// crash of the command. Throws std::runtime_error naming the file. A file the child reads
/// without crashing, or whose reads fail with an error, is left to the command's own reads
/// (which give that error). Tables in the checksummed format are not probed: there HDF5 checks
/// every header before it uses it. Call before the process starts threads.
void ProbeUncheckedTable(const std::string& path);

}  // namespace wrc::cli
