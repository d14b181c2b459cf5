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

// A small valid scene (64x48 camera, two arms, GGX sample) written beside a fuzzed file that
// may name it (rig.yaml's `geometry:`, capture.json's `scene`) or that needs a rig to run
// against (the daemon's simulated devices).
inline constexpr const char* kSmallScene = R"(rig:
  camera: {resolution: [64, 48], focal_px: [80, 80], position: [0, 0, 0.5],
           look_at: [0, 0, 0], up: [0, 1, 0]}
  light: {position: [0, 0, 0.6], intensity: 2.0}
  axes:
    - {name: camera_arm, moves: camera, direction: [1, 0, 0], range_deg: [-80, 80]}
    - {name: light_arm, moves: light, direction: [1, 0, 0], range_deg: [-80, 80]}
  target: {cutout: [0.1, 0.08], paper: [0.3, 0.3], paper_albedo: 0.7}
sample:
  brdf: {model: ggx, alpha: 0.1, f0: 0.5, diffuse: 0.1}
  size: [0.2, 0.2]
background: {albedo: 0.05}
sensor: {gain: 10, shutter_speeds: [0.001, 0.01, 0.1]}
render: {seed: 7}
)";

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
