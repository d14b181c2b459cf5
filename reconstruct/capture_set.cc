#include "reconstruct/capture_set.h"

#include <map>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_parse.h"
#include "common/yaml_reader.h"
#include "reconstruct/raw_photo.h"
#include "session/session_reader.h"

namespace brdfrig::reconstruct {

CaptureSet LoadSimulatedCapture(const std::filesystem::path& dir) {
  const std::filesystem::path photos =
      std::filesystem::exists(dir / "photos" / "capture.json") ? dir / "photos" : dir;
  const std::filesystem::path manifest = photos / "capture.json";
  if (!std::filesystem::exists(manifest)) {
    throw FileError(manifest.string(), "no capture.json: not a brdfrig simulate output directory");
  }
  const nlohmann::json doc = ParseJson(ReadFileToString(manifest), manifest.string());
  CaptureSet set;
  set.name = dir.string();
  try {
    // A relative scene lies beside capture.json, wherever the reader runs from.
    std::filesystem::path scene = doc.at("scene").get<std::string>();
    if (scene.is_relative()) scene = photos / scene;
    // Only the scene's rig section is read: the nominal geometry, never the truth.
    const YamlNode root = LoadYamlFile(scene.string());
    set.nominal = geometry::ParseRigGeometry(root.Required("rig"));
    std::map<int, CapturePosition> by_index;
    std::size_t frame_number = 0;
    for (const auto& frame : doc.at("frames")) {
      const std::size_t number = frame_number++;
      const int index = frame.at("position_index").get<int>();
      // A negative index would make a phantom slice (p-1) beside the real ones.
      if (index < 0) {
        throw FileError(manifest.string(), "frames[" + std::to_string(number) +
                                               "]: position_index " + std::to_string(index) +
                                               " is negative (positions count from 0)");
      }
      CapturePosition& p = by_index[index];
      p.index = index;
      p.validation = frame.value("validation", false);  // absent in older capture.json files
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

CaptureSet LoadSessionCapture(const std::filesystem::path& dir) {
  const session::SessionContents contents = session::ReadSession(dir);
  CaptureSet set;
  set.name = dir.string();
  set.nominal = contents.rig.geometry;
  set.calibration = contents.rig.calibration;
  if (contents.exit_status != "success") {
    set.warnings.push_back("session " + contents.name + " ended '" + contents.exit_status + "'" +
                           (contents.stop_reason.empty() ? "" : " (" + contents.stop_reason + ")") +
                           ": using its complete positions");
  }
  // One file per (position, bracket): RAW when the camera also wrote a JPEG.
  std::map<int, std::map<int, const session::RecordedFrame*>> shots;
  for (const session::RecordedFrame& frame : contents.frames) {
    const session::RecordedFrame*& kept = shots[frame.position_index][frame.bracket_index];
    if (kept == nullptr || (IsRawPhoto(frame.file) && !IsRawPhoto(kept->file))) kept = &frame;
  }
  for (const auto& [index, bracket] : shots) {
    const std::size_t planned =
        index < static_cast<int>(contents.planned_brackets.size())
            ? contents.planned_brackets[static_cast<std::size_t>(index)].size()
            : 0;
    if (bracket.size() < planned) {
      const std::string reason = std::to_string(bracket.size()) + " of " + std::to_string(planned) +
                                 " exposures recorded (the run stopped inside it)";
      set.warnings.push_back("position " + std::to_string(index) + " left out: " + reason);
      set.left_out.push_back({index, reason});
      continue;
    }
    CapturePosition position;
    position.index = index;
    position.validation = index < static_cast<int>(contents.planned_validation.size()) &&
                          contents.planned_validation[static_cast<std::size_t>(index)];
    position.axis_readings = bracket.begin()->second->axis_readings;
    for (const auto& [bracket_index, frame] : bracket) {
      position.frames.push_back({frame->file, frame->exposure_s, frame->sha256});
    }
    set.positions.push_back(std::move(position));
  }
  if (set.positions.empty()) {
    throw FileError((dir / "contents.sqlite").string(), "no complete position recorded");
  }
  return set;
}

}  // namespace brdfrig::reconstruct
