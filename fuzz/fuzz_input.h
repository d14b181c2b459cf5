// Shared by the fuzz targets (one per parser, see docs/fuzzing.md): parsers that only take a
// path get the input as a file in this process's scratch directory. libFuzzer runs one input
// at a time per process, so fixed file names inside that directory cannot collide.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace brdfrig::fuzz {

inline std::string AsString(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// $TMPDIR/brdfrig-fuzz-PID, created on first use and removed when the fuzzer exits normally
// (a crash leaves it for the post-mortem).
inline const std::filesystem::path& ScratchDir() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("brdfrig-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(ScratchDir(), ignored);
    });
    return d;
  }();
  return dir;
}

// Writes `text` to ScratchDir()/name (replacing it) and returns the file's path.
inline std::filesystem::path WriteScratchFile(const std::string& name, std::string_view text) {
  const std::filesystem::path path = ScratchDir() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(text.data(), static_cast<std::streamsize>(text.size()));
  return path;
}

inline std::filesystem::path WriteScratchFile(const std::string& name, const std::uint8_t* data,
                                              std::size_t size) {
  return WriteScratchFile(name, AsString(data, size));
}

}  // namespace brdfrig::fuzz
