#pragma once
/// @file output_file.h
/// Writing outputs safely: regular files only (a device, FIFO or directory at the output name is
/// refused, never replaced), temporary files created exclusively without following symlinks,
/// every write, sync and close checked, and a failed write leaves nothing under the final name.

#include <filesystem>
#include <string_view>
#include <vector>

namespace wrc {

/// Throws InputError when something that is not a regular file (a device, FIFO, socket,
/// directory, or a symlink to one of those) exists at path. A missing path is fine.
void RequireRegularOutput(const std::filesystem::path& path);

/// Throws InputError when output is the same file as one of inputs (by device and inode where
/// both exist, else by their normalised paths): a command must not overwrite what it reads.
void RequireNotAnInput(const std::filesystem::path& output,
                       const std::vector<std::filesystem::path>& inputs);

/// Creates path as a new, empty regular file: O_CREAT | O_EXCL | O_NOFOLLOW, so a symlink
/// planted at that name is never followed. A regular file already there (left over by an
/// interrupted run) is removed first; anything else there is refused with InputError.
void CreateExclusively(const std::filesystem::path& path);

/// Writes text to path through path + ".tmp", created exclusively, checked at every write, then
/// synced, closed and renamed into place. Throws InputError naming the file on any failure,
/// after removing the temporary file: path then still holds what it held before.
void WriteFileAtomically(const std::filesystem::path& path, std::string_view text);

/// Flushes std::cout and checks that everything written to it arrived (a full disk or
/// `> /dev/full` fails here); throws InputError when not.
void FinishStandardOutput();

}  // namespace wrc
