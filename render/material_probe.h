// Evaluates a GPU material's GLSL BRDF at given directions (no mesh, no lighting): what the
// GPU/CPU agreement tests compare with the CPU model's Eval.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "render/gpu_material.h"

namespace brdfrig::render {

// `light` and `view` are CV_32FC3 images of directions (x, y, z), of one size; `normal` is the
// surface normal for all. Returns CV_32FC3 holding f in R, G, B order (1/sr). Needs a current
// GL context.
cv::Mat EvalMaterialOnGpu(const GpuMaterial& material, const cv::Mat& light, const cv::Mat& view,
                          const Eigen::Vector3f& normal);

}  // namespace brdfrig::render
