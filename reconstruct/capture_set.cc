#include "reconstruct/capture_set.h"

#include <map>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/yaml_reader.h"

namespace brdfrig::reconstruct {

CaptureSet LoadSimulatedCapture(const std::filesystem::path& dir) {
  const std::filesystem::path photos =
      std::filesystem::exists(dir / "photos" / "capture.json") ? dir / "photos" : dir;
  const std::filesystem::path manifest = photos / "capture.json";
  if (!std::filesystem::exists(manifest)) {
    throw FileError(manifest.string(), "no capture.json: not a brdfrig simulate output directory");
  }
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(ReadFileToString(manifest));
  } catch (const nlohmann::json::exception& e) {
    throw FileError(manifest.string(), std::string("malformed JSON: ") + e.what());
  }
  CaptureSet set;
  set.name = dir.string();
  try {
    std::filesystem::path scene = doc.at("scene").get<std::string>();
    if (scene.is_relative() && !std::filesystem::exists(scene)) scene = photos / scene;
    // Only the scene's rig section is read: the nominal geometry, never the truth.
    const YamlNode root = LoadYamlFile(scene.string());
    set.nominal = rig::ParseRigGeometry(root.Required("rig"));
    std::map<int, CapturePosition> by_index;
    for (const auto& frame : doc.at("frames")) {
      const int index = frame.at("position_index").get<int>();
      CapturePosition& p = by_index[index];
      p.index = index;
      for (const auto& [axis, value] : frame.at("axis_readings_rad").items()) {
        p.axis_readings[axis] = value.get<double>();
      }
      p.frames.push_back(
          {photos / frame.at("file").get<std::string>(), frame.at("exposure_s").get<double>()});
    }
    for (auto& [index, position] : by_index) set.positions.push_back(std::move(position));
  } catch (const nlohmann::json::exception& e) {
    throw FileError(manifest.string(), std::string("unexpected content: ") + e.what());
  }
  if (set.positions.empty()) throw FileError(manifest.string(), "no frames recorded");
  return set;
}

}  // namespace brdfrig::reconstruct
