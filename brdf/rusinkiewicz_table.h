// A tabulated isotropic BRDF on a grid of Rusinkiewicz half/difference angles: the form the
// measured prior (prior/) reconstructs and the ladder's `prior` rung writes.
//
// Coordinates (Rusinkiewicz 1998): θh, the half vector's angle from the normal; θd and φd, the
// light's polar and azimuthal angles about the half vector. An isotropic, reciprocal and
// mirror-symmetric BRDF depends on φd only through |φd| folded into [0, π/2] (reciprocity maps
// φd to φd + π, mirror symmetry to −φd), so the table spans θh, θd ∈ [0, π/2], φd ∈ [0, π/2].
// Nodes: θh sqrt-spaced like MERL's tables (θh_i = π/2 · (i/(N−1))², the specular peak lives in
// the first degrees), θd and φd evenly spaced, both ends included.
//
// The tabulated quantity is q = ln(f · c + ε) with c = max(cos θi, floor) · max(cos θo, floor)
// (Nielsen et al. 2015's mapping, without their median offset, which a principal component
// analysis removes with the mean anyway): the logarithm makes a specular peak and a diffuse
// floor comparable, the cosines tame grazing values and ε the dark channels. q is interpolated
// trilinearly on the continuous index coordinates and f recovered with the query's own c, so
// the CPU and the shader compute the same function of the same node values.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "brdf/brdf.h"

namespace brdfrig::brdf {

struct RusinkiewiczGrid {
  int theta_h = 64;  // nodes, sqrt-spaced over [0, π/2]
  int theta_d = 32;  // nodes over [0, π/2]
  int phi_d = 8;     // nodes over [0, π/2]
  // ε of the mapping: below f·c ≈ ε the table stops resolving f, so it decides how much of a
  // dark channel's and a sharp peak's shape the prior and the fit see. 3e-5: on the 80
  // measured materials left out one at a time, from noise-free samples of six designed photos,
  // 1e-5 to 5e-5 reconstruct 0.4-0.7 dB better than 1e-4 (the worst material 4-6 dB), 1e-3
  // and 1e-6 lose 1.5 and 0.7 dB (docs/prior.md; captured: docs/results.md).
  double epsilon = 3e-5;
  double cos_floor = 0.05;  // floor of each cosine in c
  int Cells() const { return theta_h * theta_d * phi_d; }
  int Index(int ih, int id, int ip) const { return (ih * theta_d + id) * phi_d + ip; }
  void Validate() const;  // throws OptionsError naming the field
  bool operator==(const RusinkiewiczGrid&) const = default;
};

// The coordinates of a direction pair in the local frame (z = normal), φd folded to [0, π/2].
struct HalfDiffAngles {
  double theta_h = 0, theta_d = 0, phi_d = 0;
};
HalfDiffAngles ToHalfDiffAngles(const Vec3& l, const Vec3& v);
// A direction pair with the given coordinates (φh = 0): the inverse of ToHalfDiffAngles.
void FromHalfDiffAngles(const HalfDiffAngles& a, Vec3* l, Vec3* v);

// The node coordinates of index (ih, id, ip).
HalfDiffAngles NodeAngles(const RusinkiewiczGrid& grid, int ih, int id, int ip);

// How much of the space of direction pairs (light, view, both above the surface) each node
// stands for: the integral of its trilinear hat against the measure
// cos θi · cos θo · dωi dωo (= 4 cos θd dωh dωd, Rusinkiewicz 1998), normalised to mean 1 over
// the nodes. An error of q weighted by it is the error a rendering under uniform light would
// see: nodes below the horizon weigh nothing, grazing ones little, and the sqrt-spaced nodes of
// the specular peak by the small solid angle each covers.
std::vector<double> NodeMeasure(const RusinkiewiczGrid& grid);

// The eight nodes around a point and their trilinear weights (summing to 1).
struct Stencil {
  std::array<int, 8> node{};
  std::array<double, 8> weight{};
};
Stencil StencilAt(const RusinkiewiczGrid& grid, const HalfDiffAngles& a);

// c = max(cos θi, floor) · max(cos θo, floor) for local directions.
double CosineProduct(const RusinkiewiczGrid& grid, const Vec3& l, const Vec3& v);

// q = ln(f·c + ε), with f·c clamped at 0 from below (noise can make a measured f negative).
double MapValue(const RusinkiewiczGrid& grid, double f, double c);
// The inverse: f = max(exp(q) − ε, 0) / c.
double UnmapValue(const RusinkiewiczGrid& grid, double q, double c);

// q of every node of every channel: q[channel][node].
using TableValues = std::array<std::vector<double>, 3>;

class RusinkiewiczTable : public Brdf {
 public:
  // Throws brdfrig::Error when a channel does not have grid.Cells() finite values.
  RusinkiewiczTable(RusinkiewiczGrid grid, TableValues q);

  Rgb Eval(const Vec3& l, const Vec3& v, const Vec3& n) const override;
  Rgb EvalLocal(const Vec3& l, const Vec3& v) const;  // 0 below the surface
  std::string Name() const override;

  const RusinkiewiczGrid& grid() const { return grid_; }
  const TableValues& values() const { return q_; }

 private:
  RusinkiewiczGrid grid_;
  TableValues q_;
};

// The table of any BRDF: q at every node, f averaged over the four φd that the table folds
// together (a measured or fitted BRDF need not be exactly reciprocal or mirror-symmetric).
TableValues TabulateBrdf(const Brdf& brdf, const RusinkiewiczGrid& grid);

}  // namespace brdfrig::brdf
