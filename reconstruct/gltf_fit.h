// The glTF version of a material (docs/gltf.md): the `gltf` kind's parameters (brdf/gltf_model.h)
// fitted with Ceres to one of two sources, in the ladder's loss (reconstruct/log_loss.h,
// Huber-robust):
//   rung     the chosen rung itself, evaluated on a fixed grid over the whole hemisphere pair
//            (theta_h sqrt-spaced, theta_d, phi_d; each node weighted by its measure in
//            (l, v) times cos_i cos_o): the export reproduces what brdfrig renders and reports.
//            Needs no samples, so any material.json can be exported. The default.
//   samples  the capture's direction samples (every position weighing the same, as the rungs
//            are fitted): only where the photos saw the material.
// docs/gltf.md has the measurement that chose the default. The parameters fitted are
// baseColor, metallic, roughness, specular and a dielectric f0 per channel; f0 is written as
// KHR_materials_ior's ior (from f0's largest channel) and KHR_materials_specular's
// specularColor (f0 over that channel, so its largest channel is 1), which reproduces f0
// exactly and gives consumers without KHR_materials_specular the right ior.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "brdf/gltf_model.h"
#include "brdf/material_file.h"
#include "brdf/sphere_figure.h"
#include "reconstruct/direction_samples.h"
#include "reconstruct/seed_fit.h"

namespace brdfrig::reconstruct {

struct GltfFitOptions {
  std::string source = "rung";  // "rung" or "samples" (see above)
  int theta_h_steps = 24;       // the hemisphere grid of the `rung` source
  int theta_d_steps = 12;
  int phi_d_steps = 8;
  double epsilon_fraction = 0.01;  // of the 10th percentile of f·cos_i (log_loss.h)
  double loss_scale = 0.25;        // Huber scale in ln units (0 = plain least squares)
  int max_iterations = 60;
  brdf::SphereFigureOptions sphere;  // the figure of the export's loss against the rung
  void Validate() const;             // throws OptionsError
};

struct GltfFit {
  brdf::GltfParams params;
  std::string source;    // "rung" or "samples"
  double residual = 0;   // weighted RMS of the log residual over the fitted samples
  int sample_count = 0;  // directions fitted
  double seconds = 0;
};

// The `rung` source's samples: `model` on the hemisphere grid.
std::vector<DirectionSample> HemisphereSamples(const brdf::Brdf& model,
                                               const GltfFitOptions& options);

// The fit itself (any source). Throws brdfrig::Error with fewer than 10 samples.
GltfFit FitGltf(const std::vector<DirectionSample>& samples, const GltfFitOptions& options);

// Every position's direction samples, each position weighing the same (the ladder's pooling).
std::vector<DirectionSample> PoolDirectionSamples(const std::vector<PositionSamples>& positions);

// Fits the material's glTF version and stores it in material->gltf, with material->gltf_fit
// saying how (source, residual, seconds) and what it costs: the sphere PSNR of the glTF
// version against the material's own model ("sphere_vs_model"). `samples` are needed by the
// `samples` source only. A material of kind gltf is its own glTF version (figure: inf).
void AddGltfVersion(brdf::Material* material, const GltfFitOptions& options,
                    const std::vector<DirectionSample>& samples = {});

}  // namespace brdfrig::reconstruct
