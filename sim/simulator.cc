#include "sim/simulator.h"

#include <cmath>

#include "brdf/metrics.h"
#include "sim/image_io.h"
#include "sim/radiance.h"
#include "sim/sensor.h"

namespace brdfrig::sim {
namespace {

nlohmann::json VecJson(const geometry::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Points of the directional-albedo table used by the ambient effect.
constexpr int kAlbedoTableSize = 33;

}  // namespace

nlohmann::json TrueGeometry::ToJson() const {
  nlohmann::json j;
  j["format"] = "brdfrig-sim-truth";
  j["version"] = 1;
  nlohmann::json axes = nlohmann::json::object();
  for (const auto& [name, angle] : positions) axes[name] = angle;
  j["axis_positions_rad"] = axes;
  const geometry::Intrinsics& k = intrinsics;
  j["intrinsics"] = {{"width", k.width}, {"height", k.height}, {"fx", k.fx}, {"fy", k.fy},
                     {"cx", k.cx},       {"cy", k.cy},         {"k1", k.k1}, {"k2", k.k2}};
  nlohmann::json matrix = nlohmann::json::array();
  const Eigen::Matrix4d m = camera.camera_from_world.matrix();
  for (int r = 0; r < 4; ++r) matrix.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  j["camera_from_world"] = matrix;
  j["camera_center_in_world"] = VecJson(camera.CenterInWorld());
  j["light"] = {{"position_in_world", VecJson(light_position)},
                {"intensity", light_intensity},
                {"radius", light_radius},
                {"on", light_on}};
  if (board_pose >= 0) {
    nlohmann::json page = nlohmann::json::array();
    const Eigen::Matrix4d b = world_from_page.matrix();
    for (int r = 0; r < 4; ++r) page.push_back({b(r, 0), b(r, 1), b(r, 2), b(r, 3)});
    j["board"] = {{"pose", board_pose},
                  {"world_from_page", page},
                  {"page", "metres from the page's top-left, x along, y down, z into the sheet"}};
  }
  j["pixel_convention"] = "pixel centres at integer coordinates (OpenCV)";
  return j;
}

Simulator::Simulator(Scene scene) : scene_(std::move(scene)) {
  if (scene_.board) board_print_ = std::make_shared<const SheetPrint>(PrintOfBoard(*scene_.board));
  if (scene_.rig.target.markers) {
    mask_print_ = std::make_shared<const SheetPrint>(PrintOfMask(scene_.rig.target));
  }
  if (scene_.effects.ambient) {
    // Reciprocity: the albedo for light from theta equals the albedo towards a viewer at theta.
    for (int i = 0; i < kAlbedoTableSize; ++i) {
      const double cos_v = static_cast<double>(i) / (kAlbedoTableSize - 1);
      sample_albedo_.push_back(brdf::DirectionalAlbedo(*scene_.sample.brdf, std::acos(cos_v)));
    }
  }
}

TrueGeometry Simulator::GeometryAt(const geometry::AxisPositions& positions, bool light_on,
                                   int board_pose) const {
  TrueGeometry g;
  g.positions = positions;
  g.intrinsics = scene_.rig.intrinsics;
  if (scene_.effects.radial_distortion) {
    g.intrinsics.k1 = scene_.effects.radial_distortion->k1;
    g.intrinsics.k2 = scene_.effects.radial_distortion->k2;
  }
  g.camera = scene_.rig.CameraAt(positions);
  g.light_position = scene_.rig.LightAt(positions);
  g.light_intensity = scene_.rig.light_intensity;
  g.light_radius = scene_.effects.area_light ? scene_.effects.area_light->radius : 0.0;
  g.light_on = light_on;
  if (scene_.board) {
    const int poses = static_cast<int>(scene_.board->world_from_page.size());
    if (board_pose < 0 || board_pose >= poses) {
      throw Error("board pose " + std::to_string(board_pose) + " of a board with " +
                  std::to_string(poses) + " poses");
    }
    g.board_pose = board_pose;
    g.world_from_page = scene_.board->world_from_page[board_pose];
  }
  return g;
}

cv::Mat Simulator::RenderRadiance(const geometry::AxisPositions& positions,
                                  const RenderOptions& options) const {
  return SynthesizeRadiance(scene_, GeometryAt(positions, options.light_on, options.board_pose),
                            sample_albedo_, board_print_.get(), mask_print_.get(), options.threads);
}

cv::Mat Simulator::Expose(const cv::Mat& radiance, double exposure_s, std::uint64_t frame,
                          int threads) const {
  if (!(exposure_s > 0) || !std::isfinite(exposure_s)) {
    throw Error("exposure must be a positive number of seconds, got " + std::to_string(exposure_s));
  }
  return ApplySensor(scene_, GeometryAt({}).intrinsics, radiance, exposure_s, frame, threads);
}

cv::Mat Simulator::RenderCameraImage(const geometry::AxisPositions& positions, double exposure_s,
                                     std::uint64_t frame, const RenderOptions& options) const {
  return Expose(RenderRadiance(positions, options), exposure_s, frame, options.threads);
}

std::vector<std::byte> Simulator::EncodePhoto(const cv::Mat& sensor_image) const {
  return sim::EncodePhoto(sensor_image, scene_.sensor);
}

}  // namespace brdfrig::sim
