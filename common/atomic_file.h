// Writing files so that a crash at any instant leaves either the old file or the complete new
// one, never a torn file: write to a temporary name in the same directory, fsync, rename,
// fsync the directory. The temporary is created exclusively under a fresh unique name, so a
// file or symlink someone planted beside the target is never followed nor overwritten.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace brdfrig {

// Throws brdfrig::OutputError naming the path and the system error (e.g. "No space left on
// device"); so do the functions below that write.
void WriteFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes);
void WriteFileAtomically(const std::filesystem::path& path, std::string_view text);

// The two halves of WriteFileAtomically, for callers that act between them (e.g. record a
// checkpoint): create a new temporary beside `target` ("NAME.tmp-PID-RANDOM", O_CREAT|O_EXCL|
// O_NOFOLLOW), write `bytes`, fsync it and return its path (removed again on failure); rename
// `from` to `to` and fsync the directory (`from` removed on failure).
std::filesystem::path WriteTemporaryAndSync(const std::filesystem::path& target,
                                            std::span<const std::byte> bytes);
void RenameAndSync(const std::filesystem::path& from, const std::filesystem::path& to);

// A writer killed between the halves (SIGKILL, a crash, a power cut) leaves its temporary.
// Each new temporary of `target` first removes those of earlier writers: entries of the
// target's directory named "NAME.tmp-PID" or "NAME.tmp-PID-XXXXXXXX" (this file's patterns,
// for this NAME only) that are regular files of this user, not symlinks (never followed),
// whose PID runs no process here and which nobody wrote for kStaleTemporaryAgeS. Returns how
// many it removed; errors leave the entry alone.
inline constexpr long kStaleTemporaryAgeS = 600;
int RemoveStaleTemporaries(const std::filesystem::path& target);

// Inputs a user or client feeds are text files of modest size: the cap keeps a mistaken or
// hostile path (a disk image, /dev/zero) from eating the memory.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{64} << 20;  // 64 MiB

// Reads a whole regular file of at most `max_bytes`; throws FileError when it cannot, when the
// path is not a regular file (a FIFO, a device, a directory: refused at once, never waited on)
// or when the file is larger.
std::string ReadFileToString(const std::filesystem::path& path,
                             std::size_t max_bytes = kMaxInputFileBytes);

// std::filesystem::create_directories for an output: a component that is a file, or one that
// cannot be made, is an OutputError naming `dir` (not a std::filesystem::filesystem_error).
void CreateDirectories(const std::filesystem::path& dir);

// fsync of a directory, so that a rename inside it is durable.
void SyncDirectory(const std::filesystem::path& dir);

}  // namespace brdfrig
