// The rig's nominal geometry: where the camera and the light are for a given set of axis
// positions, the camera intrinsics, and the target (paper mask with its cut-out). The world has
// the sample plane at z = 0 with normal +z and the cut-out centred at the origin.
//
// One description serves the simulator (scene.yaml's `rig:` section), the plan check and the
// reconstruction's starting values (rig.yaml's `geometry:` section): parsed by
// ParseRigGeometry. A sample tilt is modelled as the inverse rotation of camera and light about
// the same pivot, so the sample plane stays z = 0.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/yaml_reader.h"
#include "geometry/camera.h"
#include "geometry/rig_calibration.h"

namespace brdfrig::geometry {

using AxisPositions = std::map<std::string, double>;  // axis name -> angle (radians)

struct RotationAxis {
  std::string name;
  Vec3 pivot = Vec3::Zero();       // a point on the axis (metres, world)
  Vec3 direction = Vec3::UnitY();  // unit axis direction; positive angle = right-hand rule
  double min = -M_PI, max = M_PI;  // travel limits (radians)
  enum class Moves { kCamera, kLight, kSample } moves = Moves::kLight;
};

// A marker mask's ring of ArUco markers printed around the cut-out (calibrate/marker_mask.h lays
// them out; `brdfrig target print` prints them). Metres.
struct MaskMarkerRing {
  double marker = 0.02;   // side of a marker, black border included
  double gap = 0.01;      // from the cut-out's edge to the ring
  double spacing = 0.01;  // least white between neighbouring markers
  std::string dictionary = "DICT_4X4_100";
  int first_id = 0;
};

// The paper mask: a near-Lambertian reference of known albedo with a rectangular cut-out.
struct TargetGeometry {
  double cutout_width = 0.1;   // metres, along world x
  double cutout_height = 0.1;  // metres, along world y
  double paper_width = 0.3;    // metres (outer size of the paper)
  double paper_height = 0.3;
  double paper_albedo = 0.8;  // diffuse reflectance of the paper (grey)
  // A marker mask: the pose comes from its markers (reconstruct/marker_pose.h) and the paper's
  // radiometry from the bare paper between the cut-out and the ring. None: a plain mask.
  std::optional<MaskMarkerRing> markers;
};

struct RigGeometry {
  Intrinsics intrinsics;
  // Camera at rest (every axis at 0): its centre and the point it looks at (world), and the
  // world direction that appears "up" in the image.
  Vec3 camera_position = {0, -0.35, 0.35};
  Vec3 camera_look_at = Vec3::Zero();
  Vec3 camera_up = Vec3::UnitZ();
  Vec3 light_position = {0, 0.35, 0.35};  // light at rest (world, metres)
  double light_intensity = 1.0;           // radiant intensity (W/sr, or relative units)
  std::vector<RotationAxis> axes;         // applied in list order
  TargetGeometry target;

  const RotationAxis* FindAxis(const std::string& name) const;

  // Pose of the camera and position of the light for the given axis angles. Axes not named in
  // `positions` are at 0. Throws brdfrig::Error for an unknown axis or one outside its limits.
  CameraPose CameraAt(const AxisPositions& positions) const;
  Vec3 LightAt(const AxisPositions& positions) const;
  // The motion that carries the light from its rest position to where the axes put it
  // (LightAt(p) = LightMotion(p) * light_position): a light calibration solves for the rest
  // position through it.
  Eigen::Isometry3d LightMotion(const AxisPositions& positions) const;
};

// A rig file read without opening any device (rig::ReadRigDescription, or a session's snapshot):
// enough to check a plan or to reconstruct.
struct RigDescription {
  std::filesystem::path file;
  RigGeometry geometry;
  // Files a session must copy to be reprocessable on its own: the rig file itself and, when
  // the geometry lives in another file, that file.
  std::vector<std::filesystem::path> source_files;
  // The calibrations rig.yaml references (`calibration:`), already applied to `geometry`
  // (geometry/rig_calibration.h); each empty where the values are the nominal ones.
  RigCalibrationFiles calibration;
  // When the lab last changed the rig (rig.yaml `changed:`, ISO 8601): a calibration made
  // before it no longer describes the rig (`brdfrig rig calibrate status`). "" = not said.
  std::string changed;
};

// Parses the geometry section (keys: docs/rig_geometry.md). Angles in the file are
// in degrees (the only place degrees are accepted); they are radians everywhere in code.
RigGeometry ParseRigGeometry(const YamlNode& node);

}  // namespace brdfrig::geometry
