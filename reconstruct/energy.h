// Energy conservation of a fitted model: its directional albedo ∫ f cos(theta_o) dω_o must not
// exceed 1 at any incidence angle. The integral is taken over the half vector h (v = the mirror
// of l about h, dω_o = 4 (h·l) dω_h) with theta_h warped as u² (like the table's knots), so a
// lobe as sharp as GGX alpha 0.01 is resolved at every theta_in: a grid over v (as
// brdf::DirectionalAlbedo uses) needs ~10^6 directions for that.
#pragma once

#include <string>
#include <vector>

#include "brdf/brdf.h"
#include "brdf/microfacet_model.h"
#include "brdf/rusinkiewicz_table.h"

namespace brdfrig::reconstruct {

// Directional albedo per channel for light at theta_in (radians).
brdf::Rgb HalfVectorAlbedo(const brdf::Brdf& brdf, double theta_in, int theta_h_steps = 96,
                           int phi_steps = 96);

// Largest albedo over theta_in = 0°, 5°, …, 85° and channels, and the theta_in where it is.
struct AlbedoPeak {
  double albedo = 0;
  double theta_in = 0;
};
AlbedoPeak MaxAlbedo(const brdf::Brdf& brdf);

// Scales the specular term of a microfacet model (a constant added to its ln Fresnel
// correction knots) so that its albedo stays <= 1 − margin everywhere, and says so in `note`
// (empty when nothing was changed). Diffuse levels above 1 − margin are lowered to it first.
// Returns the scale applied (1 when none).
double LimitMicrofacetEnergy(brdf::MicrofacetModelParams* params, std::string* note,
                             double margin = 1e-3);

// Scales a table down where its albedo exceeds 1 − margin (the prior extrapolates towards
// grazing incidence, where neither the photos nor the training tables constrain it much): each
// node by the excess at its own incidence and exitance angles (the larger of the two, so the
// table stays reciprocal), interpolated over the albedo's 5° steps, every channel alike so the
// colour stays. Returns the largest scale applied (1: none).
//
// Measured and not adopted (docs/prior.md, stop 47): taking the excess only from the nodes no
// photo observed (the scales move by under 0.5 %: the observed nodes reflect next to nothing at
// the angles that exceed), and limiting each channel by its own excess (it shifts the colour
// towards grazing: paper_white_rgb −1.7 dB on the sphere).
double LimitTableEnergy(const brdf::RusinkiewiczGrid& grid, brdf::TableValues* table,
                        double margin = 1e-3);

}  // namespace brdfrig::reconstruct
