// Writing files so that a crash at any instant leaves either the old file or the complete new
// one, never a torn file: write to a temporary name in the same directory, fsync, rename,
// fsync the directory.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace brdfrig {

// Throws brdfrig::Error naming the path and the system error (e.g. "No space left on device").
void WriteFileAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes);
void WriteFileAtomically(const std::filesystem::path& path, std::string_view text);

// The two halves of WriteFileAtomically, for callers that act between them (e.g. record a
// checkpoint): write `path` and fsync it (removed again on failure); rename `from` to `to` and
// fsync the directory (`from` removed on failure).
void WriteFileAndSync(const std::filesystem::path& path, std::span<const std::byte> bytes);
void RenameAndSync(const std::filesystem::path& from, const std::filesystem::path& to);

// Reads a whole file; throws FileError when it cannot.
std::string ReadFileToString(const std::filesystem::path& path);

// fsync of a directory, so that a rename inside it is durable.
void SyncDirectory(const std::filesystem::path& dir);

}  // namespace brdfrig
