// Renders what a capture position shows: the sample inside the cut-out, the Lambertian paper
// mask around it and the table beyond, lit by the rig's point light and seen through the
// capture's camera. The same geometry as sim::Simulator, so a rendering of a fitted material can
// stand in for a photo (evaluation), and a rendering of the true material must match the
// simulator's radiance (tests/render/capture_view_test).
#pragma once

#include <opencv2/core.hpp>

#include "brdf/brdf.h"
#include "geometry/rig_geometry.h"
#include "render/renderer.h"

namespace brdfrig::render {

// Any brdf::Brdf on the GPU: GpuMaterial::ForBrdf (the slice model, the microfacet rungs,
// Lambert and GGX have their own shaders; any other model goes through a MERL table).
std::unique_ptr<GpuMaterial> MakeGpuMaterial(const brdf::Brdf& brdf);

struct CaptureView {
  geometry::TargetGeometry target;  // cut-out and paper sizes, paper albedo
  brdf::Rgb background_albedo = brdf::Rgb::Constant(0.05);
  View view;  // camera intrinsics and pose
  PointLight light;
  // N×N samples per pixel, box-filtered: matches the simulator's anti-aliased edges (its
  // render.supersampling) so that edge pixels compare like for like.
  int supersampling = 1;
  // Slice models only: linear instead of spline interpolation across theta_in (the seed's).
  bool linear_interpolation = false;
};

// Radiance image (CV_32FC3, B, G, R; W/(m² sr)). Needs a current GL context.
cv::Mat RenderCaptureView(const CaptureView& capture, const brdf::Brdf& sample);

}  // namespace brdfrig::render
