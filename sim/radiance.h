// Internal: the radiance synthesis behind Simulator::RenderRadiance.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "sim/scene.h"

namespace brdfrig::sim {

struct TrueGeometry;

// `sample_albedo`: the sample's directional albedo at cos(theta_v) = i / (size − 1); used only
// by the ambient effect (empty otherwise).
// `board`: the scene board's print (null without a board); `mask`: the rig's marker mask (null
// on a plain mask).
cv::Mat SynthesizeRadiance(const Scene& scene, const TrueGeometry& geometry,
                           const std::vector<brdf::Rgb>& sample_albedo, const SheetPrint* board,
                           const SheetPrint* mask, int threads);

}  // namespace brdfrig::sim
