// SHA-256 as lowercase hex: the one implementation for session frames, `session verify` and
// the reconstruction's up-to-date check (OpenSSL EVP underneath).
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>

namespace brdfrig {

// Incremental hashing for data that arrives in pieces (several files, a stream).
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  void Update(std::span<const std::byte> bytes);
  void Update(std::string_view text);
  // Adds a whole file's content; throws FileError when it cannot be read.
  void UpdateFile(const std::filesystem::path& path);
  // The digest as 64 lowercase hex digits. Call once.
  std::string HexDigest();

 private:
  struct Context;
  std::unique_ptr<Context> context_;
};

std::string Sha256Hex(std::span<const std::byte> bytes);
std::string Sha256Hex(std::string_view text);
// Throws FileError when the file cannot be read.
std::string Sha256FileHex(const std::filesystem::path& path);

}  // namespace brdfrig
