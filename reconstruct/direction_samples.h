// BRDF samples with their directions, for the fits that share structure across positions (the
// microfacet rungs): each sample is (l, v, f_rgb, weight) in the sample's local frame (z = the
// normal, the sample plane z = 0), with l and v unit vectors towards the light and the camera.
//
// Pixels are averaged in image blocks, not kept one by one: a position has 10^4–10^6 sample
// pixels, and the fits need a few thousand. A block is split (quadtree) until the half-vector
// angle theta_h varies across it by less than max(min_theta_h_span, relative_theta_h_span ·
// theta_h) and theta_d by less than max_theta_d_span. Why these spans: D changes fastest near
// its peak, where a GGX lobe of alpha 0.02 falls to half its peak at theta_h ≈ 0.73°, so
// 0.05° there is about a fifteenth of that half-width; away from the peak every lobe's ln D
// falls at most like −4 ln theta_h (GGX's tail), so a 10 % span of theta_h changes D by ~40 %
// across a block and biases the block's mean by under 1 % (second order: the block's mean
// directions are kept with its mean f). The count then follows the photo's angular extent,
// not its pixel count: ~1–3 thousand samples per position at any resolution.
#pragma once

#include <array>
#include <opencv2/core.hpp>
#include <vector>

#include "brdf/brdf.h"
#include "common/angles.h"
#include "geometry/rig_geometry.h"
#include "reconstruct/plane_view.h"
#include "reconstruct/radiometry.h"
#include "reconstruct/samples.h"

namespace brdfrig::reconstruct {

struct DirectionSampleOptions {
  int max_block_px = 16;                    // largest block side (pixels), a power of 2
  double min_theta_h_span = Radians(0.05);  // radians
  double relative_theta_h_span = 0.1;       // fraction of theta_h
  double max_theta_d_span = Radians(1.0);   // radians
  void Validate() const;
};

struct DirectionSample {
  brdf::Vec3 l = brdf::Vec3::UnitZ();  // towards the light (unit, local frame)
  brdf::Vec3 v = brdf::Vec3::UnitZ();  // towards the camera
  std::array<double, 3> f{};           // R, G, B (1/sr), mean over the block
  double weight = 1;                   // pixels averaged
};

struct DirectionSamples {
  int position = 0;  // capture position index
  std::vector<DirectionSample> samples;
  // Blocks below the noise floor, kept as upper bounds: f is the block's mean plus two standard
  // errors of its read noise (the floor's BRDF over sqrt(pixels)), and the material is darker
  // than that there. A black material seen away
  // from its highlight says only this, and it is still worth saying: without it the prior fills
  // those directions with what brighter training materials do.
  std::vector<DirectionSample> bounds;
  int pixels_used = 0;
  int pixels_below_noise_floor = 0;         // in blocks left out as darker than the noise floor
  double theta_h_min = 0, theta_h_max = 0;  // over the samples (radians)
  double theta_d_min = 0, theta_d_max = 0;
};

// The half-vector angles of one sample.
struct HalfAngles {
  double theta_h = 0, theta_d = 0;
};
HalfAngles HalfAnglesOf(const brdf::Vec3& l, const brdf::Vec3& v);

// Same sample region, validity and radiometry as ExtractSamples (sample_options.edge_margin).
// A block whose mean radiance, in its brightest channel, is below `noise_floor`
// (HdrImage::noise_floor; 0 keeps every block) is not a sample: what it holds is mostly clipped
// read noise, which reads as a material several times brighter than a dark one really is. It
// becomes a bound instead (DirectionSamples::bounds), which the prior rung uses; the other fits
// take that region from their form's shape. The floor is
// judged on blocks of at least 64 pixels (smaller ones take their enclosing block's verdict),
// so that it does not select a small block's upward noise.
DirectionSamples ExtractDirectionSamples(const cv::Mat& radiance, const cv::Mat& valid,
                                         double noise_floor, const PlaneView& view,
                                         const geometry::Vec3& light, const Radiometry& radiometry,
                                         const geometry::TargetGeometry& target,
                                         const SampleOptions& sample_options,
                                         const DirectionSampleOptions& options);

}  // namespace brdfrig::reconstruct
