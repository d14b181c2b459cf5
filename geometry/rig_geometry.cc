#include "geometry/rig_geometry.h"

#include <cmath>
#include <sstream>
#include <tuple>

#include "common/angles.h"

namespace brdfrig::geometry {
namespace {

Vec3 ReadVec3(const YamlNode& node) {
  const std::vector<double> v = node.AsDoubles();
  if (v.size() != 3) node.Fail("expected [x, y, z], got " + std::to_string(v.size()) + " numbers");
  return {v[0], v[1], v[2]};
}

std::pair<double, double> ReadPair(const YamlNode& node) {
  const std::vector<double> v = node.AsDoubles();
  if (v.size() != 2) node.Fail("expected two numbers, got " + std::to_string(v.size()));
  return {v[0], v[1]};
}

Vec3 ReadDirection(const YamlNode& node) {
  const Vec3 v = ReadVec3(node);
  if (v.norm() < 1e-12) node.Fail("direction must not be zero");
  return v.normalized();
}

Intrinsics ParseIntrinsics(const YamlNode& camera) {
  Intrinsics k;
  const YamlNode resolution = camera.Required("resolution");
  const auto [w, h] = ReadPair(resolution);
  if (w < 1 || h < 1 || w != std::floor(w) || h != std::floor(h)) {
    resolution.Fail("expected two positive integers [width, height]");
  }
  // Larger than any sensor (150 MP is 14204 × 10652): a typo that would allocate gigabytes.
  if (w > 32768 || h > 32768) resolution.Fail("width and height must be at most 32768 pixels");
  k.width = static_cast<int>(w);
  k.height = static_cast<int>(h);
  if (auto focal_px = camera.Optional("focal_px")) {
    std::tie(k.fx, k.fy) = ReadPair(*focal_px);
    focal_px->Positive(std::min(k.fx, k.fy));
  } else {
    const YamlNode focal = camera.Required("focal_length_mm");
    const double f_mm = focal.Positive(focal.AsDouble());
    const YamlNode sensor = camera.Required("sensor_width_mm");
    const double sensor_mm = sensor.Positive(sensor.AsDouble());
    k.fx = k.fy = f_mm / sensor_mm * k.width;
  }
  k.cx = 0.5 * k.width;
  k.cy = 0.5 * k.height;
  if (auto pp = camera.Optional("principal_point")) std::tie(k.cx, k.cy) = ReadPair(*pp);
  if (auto distortion = camera.Optional("distortion")) {
    std::tie(k.k1, k.k2) = ReadPair(*distortion);
  }
  return k;
}

RotationAxis ParseAxis(const YamlNode& node) {
  RotationAxis axis;
  axis.name = node.Required("name").AsString();
  const YamlNode moves = node.Required("moves");
  const std::string what = moves.AsString();
  if (what == "camera") {
    axis.moves = RotationAxis::Moves::kCamera;
  } else if (what == "light") {
    axis.moves = RotationAxis::Moves::kLight;
  } else if (what == "sample") {
    axis.moves = RotationAxis::Moves::kSample;
  } else {
    moves.Fail("expected one of camera, light, sample; got '" + what + "'");
  }
  if (auto pivot = node.Optional("pivot")) axis.pivot = ReadVec3(*pivot);
  axis.direction = ReadDirection(node.Required("direction"));
  if (auto range = node.Optional("range_deg")) {
    const auto [lo, hi] = ReadPair(*range);
    if (!(lo < hi)) range->Fail("expected [min, max] with min < max");
    axis.min = Radians(lo);
    axis.max = Radians(hi);
  }
  node.Finish();
  return axis;
}

TargetGeometry ParseTarget(const YamlNode& node) {
  TargetGeometry t;
  const YamlNode cutout = node.Required("cutout");
  std::tie(t.cutout_width, t.cutout_height) = ReadPair(cutout);
  cutout.Positive(std::min(t.cutout_width, t.cutout_height));
  if (auto paper = node.Optional("paper")) {
    std::tie(t.paper_width, t.paper_height) = ReadPair(*paper);
    if (t.paper_width <= t.cutout_width || t.paper_height <= t.cutout_height) {
      paper->Fail("the paper must be larger than the cut-out");
    }
  }
  if (auto albedo = node.Optional("paper_albedo")) {
    t.paper_albedo = albedo->InRange(albedo->AsDouble(), 0.01, 1.0);
  }
  if (auto markers = node.Optional("markers")) {
    MaskMarkerRing ring;
    if (auto size = markers->Optional("size")) ring.marker = size->Positive(size->AsDouble());
    if (auto gap = markers->Optional("gap")) ring.gap = gap->Positive(gap->AsDouble());
    if (auto spacing = markers->Optional("spacing")) {
      ring.spacing = spacing->Positive(spacing->AsDouble());
    }
    if (auto dictionary = markers->Optional("dictionary")) ring.dictionary = dictionary->AsString();
    if (auto first = markers->Optional("first_id")) ring.first_id = first->AsInt();
    markers->Finish();
    t.markers = ring;
  }
  node.Finish();
  return t;
}

// Rotation by `angle` about the axis line through pivot with direction.
Eigen::Isometry3d AxisMotion(const RotationAxis& axis, double angle) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.translate(axis.pivot);
  motion.rotate(Eigen::AngleAxisd(angle, axis.direction));
  motion.translate(-axis.pivot);
  return motion;
}

double AngleOf(const RotationAxis& axis, const AxisPositions& positions) {
  const auto it = positions.find(axis.name);
  const double angle = it == positions.end() ? 0.0 : it->second;
  if (!std::isfinite(angle) || angle < axis.min - 1e-9 || angle > axis.max + 1e-9) {
    std::ostringstream msg;
    msg << "axis '" << axis.name << "': " << Degrees(angle) << "° is outside its range ["
        << Degrees(axis.min) << "°, " << Degrees(axis.max) << "°]";
    throw Error(msg.str());
  }
  return angle;
}

void CheckKnownAxes(const RigGeometry& rig, const AxisPositions& positions) {
  for (const auto& [name, angle] : positions) {
    if (!rig.FindAxis(name)) throw Error("unknown axis '" + name + "' in axis positions");
  }
}

// World motions applied to the camera and to the light for the given axis angles.
std::pair<Eigen::Isometry3d, Eigen::Isometry3d> Motions(const RigGeometry& rig,
                                                        const AxisPositions& positions) {
  CheckKnownAxes(rig, positions);
  Eigen::Isometry3d camera = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d light = Eigen::Isometry3d::Identity();
  for (const RotationAxis& axis : rig.axes) {
    const double angle = AngleOf(axis, positions);
    switch (axis.moves) {
      case RotationAxis::Moves::kCamera:
        camera = AxisMotion(axis, angle) * camera;
        break;
      case RotationAxis::Moves::kLight:
        light = AxisMotion(axis, angle) * light;
        break;
      case RotationAxis::Moves::kSample: {
        // Tilting the sample by +angle is seen as camera and light turning by -angle.
        const Eigen::Isometry3d inverse = AxisMotion(axis, -angle);
        camera = inverse * camera;
        light = inverse * light;
        break;
      }
    }
  }
  return {camera, light};
}

}  // namespace

const RotationAxis* RigGeometry::FindAxis(const std::string& name) const {
  for (const RotationAxis& axis : axes) {
    if (axis.name == name) return &axis;
  }
  return nullptr;
}

CameraPose RigGeometry::CameraAt(const AxisPositions& positions) const {
  const Eigen::Isometry3d world_from_camera =
      Motions(*this, positions).first *
      WorldFromCameraLookingAt(camera_position, camera_look_at, camera_up);
  CameraPose pose;
  pose.camera_from_world = world_from_camera.inverse();
  return pose;
}

Vec3 RigGeometry::LightAt(const AxisPositions& positions) const {
  return LightMotion(positions) * light_position;
}

Eigen::Isometry3d RigGeometry::LightMotion(const AxisPositions& positions) const {
  return Motions(*this, positions).second;
}

RigGeometry ParseRigGeometry(const YamlNode& node) {
  RigGeometry rig;
  const YamlNode camera = node.Required("camera");
  rig.intrinsics = ParseIntrinsics(camera);
  rig.camera_position = ReadVec3(camera.Required("position"));
  if (auto look_at = camera.Optional("look_at")) rig.camera_look_at = ReadVec3(*look_at);
  if (auto up = camera.Optional("up")) rig.camera_up = ReadDirection(*up);
  const Vec3 forward = rig.camera_look_at - rig.camera_position;
  if (forward.norm() < 1e-9 || forward.normalized().cross(rig.camera_up).norm() < 1e-6) {
    camera.Fail("position, look_at and up must define a view (up not along the view direction)");
  }
  camera.Finish();

  const YamlNode light = node.Required("light");
  rig.light_position = ReadVec3(light.Required("position"));
  if (auto intensity = light.Optional("intensity")) {
    rig.light_intensity = intensity->Positive(intensity->AsDouble());
  }
  light.Finish();

  if (auto axes = node.Optional("axes")) {
    for (const YamlNode& item : axes->Elements()) {
      RotationAxis axis = ParseAxis(item);
      if (rig.FindAxis(axis.name)) item.Fail("duplicate axis name '" + axis.name + "'");
      rig.axes.push_back(std::move(axis));
    }
  }
  if (auto target = node.Optional("target")) rig.target = ParseTarget(*target);
  node.Finish();
  return rig;
}

}  // namespace brdfrig::geometry
