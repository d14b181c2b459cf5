// One small, valid material of every model kind (brdf::kAllModelKinds), for the export tests:
// a glossy orange sample as each kind would hold it.
#pragma once

#include <cmath>

#include "brdf/analytic.h"
#include "brdf/material_file.h"
#include "brdf/microfacet_terms.h"
#include "brdf/rusinkiewicz_table.h"

namespace brdfrig::testing {

inline brdf::Material ExampleMaterial(brdf::ModelKind kind) {
  brdf::Material m;
  m.kind = kind;
  if (brdf::IsSliceKind(kind)) {
    for (int k = 0; k < 4; ++k) {
      brdf::Slice s;
      s.theta_in = (15 + 20 * k) * M_PI / 180;
      for (int c = 0; c < 3; ++c) s.channel[c] = {4.0 + k, 0.1 / (1 + c), 0.04, 0.06};
      m.slices.push_back(s);
    }
    return m;
  }
  const brdf::MicrofacetParams ggx{brdf::Rgb(0.4, 0.15, 0.05), brdf::Rgb(0.05, 0.05, 0.05), 0.15};
  if (kind == brdf::ModelKind::kPrior) {
    m.table = brdf::TabulateBrdf(brdf::Ggx(ggx), m.table_grid);
    return m;
  }
  if (kind == brdf::ModelKind::kGltf) {
    brdf::GltfParams g;
    g.base_color = brdf::Rgb(0.6, 0.25, 0.08);
    g.metallic = 0.2;
    g.roughness = 0.4;
    g.ior = 1.6;
    g.specular = 0.9;
    g.specular_color = brdf::Rgb(1.0, 0.9, 0.8);
    m.gltf = g;
    return m;
  }
  brdf::MicrofacetModelParams& p = m.microfacet;
  p.diffuse = ggx.diffuse;
  p.f0 = ggx.f0;
  p.alpha = ggx.alpha;
  p.distribution = kind == brdf::ModelKind::kBeckmann ? brdf::Distribution::kBeckmann
                   : kind == brdf::ModelKind::kGgx    ? brdf::Distribution::kGgx
                                                      : brdf::Distribution::kTable;
  if (kind == brdf::ModelKind::kMicrofacet) {
    p.max_theta_h = 0.5;
    p.fresnel_knots = {0, 0.05, -0.05};
    for (int k = 0; k < 16; ++k) {
      p.log_d.push_back(brdf::microfacet::LogGgxD(
          std::cos(brdf::microfacet::TableKnotThetaH(k, 16, p.max_theta_h)), p.alpha));
    }
  }
  return m;
}

}  // namespace brdfrig::testing
