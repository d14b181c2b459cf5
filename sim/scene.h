// scene.yaml: everything the simulator needs to know about the simulated world. The full key
// reference with an example is docs/sim_scene.md; sim/scenes/default.yaml is the shipped scene.
//
//   rig:        geometry::ParseRigGeometry (camera, light, axes, target = paper mask with cut-out)
//   sample:     {brdf: {model: ggx|cook_torrance|ward|blinn_phong|lambert|slices|merl|nbrdf, ...},
//                size: [w, h]}
//   background: {albedo: grey or [r, g, b]}       the table around the paper (Lambertian)
//   sensor:     {format: png16|tiff16|jpeg8, gain, jpeg_quality, shutter_speeds, model}
//   render:     {supersampling: N, seed: S}
//   timing:     axis speed/acceleration, camera overhead/download, real_time_factor
//   capture:    {exposures: [s, ...], positions: [{axis: degrees, ..., validation: bool}, ...]
//                or positions: {design: {count: 6, validation: 1, ...}} (coverage/designer.h)}
//   effects:    see sim/effects.h
//   faults:     scheduled device faults (see SimFault)
//   board:      a printed ChArUco board at one or more poses (sim/scene_board.h)
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "brdf/brdf.h"
#include "common/angles.h"
#include "common/yaml_reader.h"
#include "geometry/rig_geometry.h"
#include "sim/effects.h"
#include "sim/scene_board.h"

namespace brdfrig::sim {

struct SampleDescription {
  std::shared_ptr<const brdf::Brdf> brdf;  // never null after parsing
  double width = 0.2, height = 0.2;        // metres, centred at the origin
};

enum class PhotoFormat { kPng16, kTiff16, kJpeg8 };

// The sensor format named as in scene files (png16, tiff16, jpeg8); nullopt for another name.
std::optional<PhotoFormat> PhotoFormatNamed(const std::string& name);

struct SensorDescription {
  PhotoFormat format = PhotoFormat::kPng16;
  // Sensor signal (1 = full scale) per unit of radiance (W/(m² sr)) and second of exposure.
  double gain = 1.0;
  int jpeg_quality = 95;
  std::vector<double> shutter_speeds;  // offered exposure times (s); empty = any in range
  double min_exposure_s = 1e-5, max_exposure_s = 60;
  std::string model = "brdfrig simulated camera";
  std::string Extension() const;  // ".png", ".tif", ".jpg"
};

struct RenderSettings {
  int supersampling = 1;  // N×N samples in pixels that straddle an edge; 1 = centre only
  std::uint64_t seed = 1;
};

struct AxisTiming {
  double speed = Radians(30);         // rad/s
  double acceleration = Radians(60);  // rad/s²
};

struct TimingDescription {
  AxisTiming default_axis;
  std::map<std::string, AxisTiming> axes;  // overrides by axis name
  double shot_overhead_s = 0.2;            // shutter lag, mirror, write-out beyond the exposure
  double download_s = 0.8;                 // per frame
  double reopen_s = 2.0;                   // a successful Reopen
  // 0: virtual time only (durations are reported, nobody waits). r > 0: each operation also
  // sleeps r × its duration (1 = real time).
  double real_time_factor = 0;
  const AxisTiming& For(const std::string& axis) const;
};

// A fault scheduled by the scene. Shots and moves are counted from 1.
struct SimFault {
  enum class Type { kCameraDisconnect, kCameraBusy, kSlowDownload, kAxisAlarm } type;
  int at = 1;             // disconnect: after this many shots; others: at this shot / move
  int count = 1;          // busy: failed attempts; slow_download: shots affected;
                          // disconnect: failed Reopen() calls before the camera is back
  double duration_s = 0;  // slow_download: download time of each affected frame
  std::string axis;       // axis_alarm
  int alarm_code = 0x30;  // axis_alarm
};

struct CapturePlan {
  std::vector<double> exposures;                   // seconds
  std::vector<geometry::AxisPositions> positions;  // radians
  // Per position: a validation position (captured, never fitted). Same length as positions.
  std::vector<bool> validation;
  // For `positions: {design: {...}}`: the designer's explanation (the positions are resolved
  // when the scene is read, from the scene's own rig).
  std::string design;
};

struct Scene {
  std::filesystem::path source;  // the file it came from ("" for strings), for messages
  geometry::RigGeometry rig;
  SampleDescription sample;
  brdf::Rgb background_albedo = brdf::Rgb::Constant(0.05);
  SensorDescription sensor;
  RenderSettings render;
  TimingDescription timing;
  CapturePlan capture;
  Effects effects;
  std::vector<SimFault> faults;
  // A printed calibration board in front of the rig, photographed at each of its poses.
  std::optional<SceneBoard> board;

  // The same world seen by an ideal camera: no effects, no faults.
  Scene Ideal() const;
  // One line: resolution, sample BRDF, active effects.
  std::string Summary() const;
};

// Reads and validates a scene; relative file names inside resolve against `base_dir`.
Scene ParseScene(const YamlNode& root, const std::filesystem::path& base_dir);
Scene LoadScene(const std::filesystem::path& path);
Scene LoadSceneString(const std::string& yaml, const std::string& source_name,
                      const std::filesystem::path& base_dir = ".");

// Axis positions written as "axis=degrees,axis=degrees" (the command line's --positions).
geometry::AxisPositions ParsePositionsDegrees(const std::string& text);

}  // namespace brdfrig::sim
