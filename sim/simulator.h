// The simulated world: synthesizes what the rig's camera would see for any axis positions.
//
// API summary (everything others need; details below and in docs/sim.md):
//
//   sim::Scene scene = sim::LoadScene("sim/scenes/default.yaml");   // strict, file:line errors
//   sim::Simulator simulator(scene);              // or Simulator(scene.Ideal()): no effects
//
//   sim::TrueGeometry g = simulator.GeometryAt(positions);   // camera pose, intrinsics, light
//   cv::Mat L = simulator.RenderRadiance(positions);         // CV_32FC3, W/(m² sr), B,G,R order
//   cv::Mat S = simulator.Expose(L, exposure_s, frame);      // sensor values, 1 = full scale
//   std::vector<std::byte> photo = simulator.EncodePhoto(S); // PNG16/TIFF16/JPEG8 bytes
//
//   sim::WriteRadianceExr(path, L); sim::WriteTrueGeometry(path, g);     (sim/image_io.h)
//
// Conventions. Positions are geometry::AxisPositions in radians (the true positions of the axes:
// mechanical error is applied by the simulated axes, sim/world.h). Pixel (u, v) is the image
// of the ray geometry::PixelRayInWorld(g.intrinsics, g.camera, {u, v}): pixel centres at integer
// coordinates (OpenCV). Images are cv::Mat in OpenCV's channel order (B, G, R), like
// cv::imread returns them; brdf::Rgb values are (R, G, B).
//
// Radiance per pixel: the ray from the camera hits the plane z = 0 on the sample (inside the
// cut-out), the paper (Lambertian, rig.target.paper_albedo) or the table (Lambertian,
// background.albedo); rays missing the plane see 0. L = f(l, v, n) · I · cos(theta_in) / d²
// for the point light (or each area-light emitter), plus ambient if listed. Pixels whose
// corners see different surfaces average render.supersampling² rays (anti-aliased edges).
//
// The ideal camera (no sensor effects listed): S = L · exposure · sensor.gain, float, no noise,
// no clipping. EncodePhoto clamps to [0, 1] and rounds to the file's bit depth.
// Everything is deterministic: same scene, seed, positions and frame → identical bytes,
// whatever the thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "geometry/rig_geometry.h"
#include "sim/scene.h"

namespace brdfrig::sim {

// Where everything truly is for one set of axis positions (for evaluation, never for the
// reconstruction).
struct TrueGeometry {
  geometry::AxisPositions positions;  // radians
  geometry::Intrinsics intrinsics;    // includes the radial_distortion effect's k1, k2
  geometry::CameraPose camera;
  geometry::Vec3 light_position = geometry::Vec3::Zero();  // world, metres
  double light_intensity = 0;  // W/sr (point light; total for an area light)
  double light_radius = 0;     // area_light radius, 0 for a point light
  bool light_on = true;
  // The printed board (scene `board:`): which pose, and where the page is; -1 without a board.
  int board_pose = -1;
  Eigen::Isometry3d world_from_page = Eigen::Isometry3d::Identity();

  nlohmann::json ToJson() const;
};

struct RenderOptions {
  int threads = 0;       // 0 = all hardware threads
  bool light_on = true;  // false: only ambient light (if listed) reaches the scene
  int board_pose = 0;    // which of the scene board's poses (ignored without a board)
};

class Simulator {
 public:
  explicit Simulator(Scene scene);

  const Scene& scene() const { return scene_; }

  TrueGeometry GeometryAt(const geometry::AxisPositions& positions, bool light_on = true,
                          int board_pose = 0) const;

  // Radiance reaching each pixel (world effects area_light, ambient, radial_distortion
  // included when listed). CV_32FC3, B,G,R.
  cv::Mat RenderRadiance(const geometry::AxisPositions& positions,
                         const RenderOptions& options = {}) const;

  // The sensor pipeline on a radiance image: exposure × gain, then vignetting, shot and read
  // noise (seeded by render.seed and `frame`), saturation, quantization, response curve, as
  // listed. CV_32FC3, B,G,R, 1 = full scale.
  cv::Mat Expose(const cv::Mat& radiance, double exposure_s, std::uint64_t frame,
                 int threads = 0) const;

  // RenderRadiance + Expose.
  cv::Mat RenderCameraImage(const geometry::AxisPositions& positions, double exposure_s,
                            std::uint64_t frame, const RenderOptions& options = {}) const;

  // The photo file the scene's sensor writes (sensor.format), from a sensor image.
  std::vector<std::byte> EncodePhoto(const cv::Mat& sensor_image) const;

 private:
  Scene scene_;
  std::vector<brdf::Rgb> sample_albedo_;  // directional albedo by cos(theta_v); ambient only
  std::shared_ptr<const SheetPrint> board_print_;  // the scene's board, rasterized once
  std::shared_ptr<const SheetPrint> mask_print_;   // the rig's marker mask, rasterized once
};

}  // namespace brdfrig::sim
