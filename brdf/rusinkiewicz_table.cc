#include "brdf/rusinkiewicz_table.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::brdf {
namespace {

constexpr double kHalfPi = M_PI / 2;

// Lower node and fraction of a continuous index u in [0, n − 1].
void Split(double u, int n, int* i, double* t) {
  u = u > 0 ? std::min(u, n - 1.0) : 0.0;  // NaN (a degenerate direction) goes to node 0
  *i = std::min(static_cast<int>(u), n - 2);
  *t = u - *i;
}

// An orthonormal tangent frame about n (any one: the table is isotropic).
Vec3 ToLocal(const Vec3& x, const Vec3& n) {
  const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 t = n.cross(helper).normalized();
  const Vec3 b = n.cross(t);
  return {x.dot(t), x.dot(b), x.dot(n)};
}

}  // namespace

void RusinkiewiczGrid::Validate() const {
  CheckOption(theta_h >= 2 && theta_h <= 512, "RusinkiewiczGrid.theta_h", theta_h, "in [2, 512]");
  CheckOption(theta_d >= 2 && theta_d <= 512, "RusinkiewiczGrid.theta_d", theta_d, "in [2, 512]");
  CheckOption(phi_d >= 2 && phi_d <= 512, "RusinkiewiczGrid.phi_d", phi_d, "in [2, 512]");
  CheckOption(Cells() <= (1 << 22), "RusinkiewiczGrid cells", Cells(), "<= 4194304");
  CheckOption(std::isfinite(epsilon) && epsilon > 0 && epsilon < 1, "RusinkiewiczGrid.epsilon",
              epsilon, "in (0, 1)");
  CheckOption(std::isfinite(cos_floor) && cos_floor > 0 && cos_floor <= 1,
              "RusinkiewiczGrid.cos_floor", cos_floor, "in (0, 1]");
}

HalfDiffAngles ToHalfDiffAngles(const Vec3& l, const Vec3& v) {
  const Vec3 sum = l + v;
  const double norm = sum.norm();
  const Vec3 h = norm > 1e-300 ? Vec3(sum / norm) : Vec3::UnitZ();
  HalfDiffAngles a;
  // atan2, not acos: acos(1 − 1e-16) is already 1.5e-8 rad, and the sqrt-spaced θh index
  // magnifies a small θh's error (the shader computes the same way, in float).
  a.theta_h = std::atan2(std::hypot(h.x(), h.y()), h.z());
  const double phi_h = std::atan2(h.y(), h.x());
  // d = R_y(−θh) · R_z(−φh) · l
  const double cp = std::cos(phi_h), sp = std::sin(phi_h);
  const double x1 = cp * l.x() + sp * l.y(), y1 = -sp * l.x() + cp * l.y(), z1 = l.z();
  const double ct = std::cos(a.theta_h), st = std::sin(a.theta_h);
  const double dx = ct * x1 - st * z1, dz = st * x1 + ct * z1;
  // From both components, so that θd is a function of the directions only: acos(dz) of a
  // float-rounded l (|l| = 1 − 6e-8) puts θd at 3.5e-4 rad for l = v.
  a.theta_d = std::atan2(std::hypot(dx, y1), dz);
  double phi = std::abs(std::atan2(y1, dx));
  if (phi > kHalfPi) phi = M_PI - phi;
  a.phi_d = phi;
  return a;
}

void FromHalfDiffAngles(const HalfDiffAngles& a, Vec3* l, Vec3* v) {
  const Vec3 h(std::sin(a.theta_h), 0, std::cos(a.theta_h));
  const Vec3 d(std::sin(a.theta_d) * std::cos(a.phi_d), std::sin(a.theta_d) * std::sin(a.phi_d),
               std::cos(a.theta_d));
  const double ct = std::cos(a.theta_h), st = std::sin(a.theta_h);
  *l = Vec3(ct * d.x() + st * d.z(), d.y(), -st * d.x() + ct * d.z());
  *v = 2 * h.dot(*l) * h - *l;
}

HalfDiffAngles NodeAngles(const RusinkiewiczGrid& grid, int ih, int id, int ip) {
  const double u = static_cast<double>(ih) / (grid.theta_h - 1);
  return {kHalfPi * u * u, kHalfPi * id / (grid.theta_d - 1), kHalfPi * ip / (grid.phi_d - 1)};
}

Stencil StencilAt(const RusinkiewiczGrid& grid, const HalfDiffAngles& a) {
  int ih, id, ip;
  double th, td, tp;
  Split(std::sqrt(std::clamp(a.theta_h / kHalfPi, 0.0, 1.0)) * (grid.theta_h - 1), grid.theta_h,
        &ih, &th);
  Split(a.theta_d / kHalfPi * (grid.theta_d - 1), grid.theta_d, &id, &td);
  Split(a.phi_d / kHalfPi * (grid.phi_d - 1), grid.phi_d, &ip, &tp);
  Stencil s;
  int k = 0;
  for (int bh = 0; bh < 2; ++bh) {
    for (int bd = 0; bd < 2; ++bd) {
      for (int bp = 0; bp < 2; ++bp, ++k) {
        s.node[k] = grid.Index(ih + bh, id + bd, ip + bp);
        s.weight[k] = (bh ? th : 1 - th) * (bd ? td : 1 - td) * (bp ? tp : 1 - tp);
      }
    }
  }
  return s;
}

std::vector<double> NodeMeasure(const RusinkiewiczGrid& grid) {
  grid.Validate();
  // Midpoint rule on the index coordinates, kSub points per interval along each axis: the
  // hats are piecewise linear there, the measure smooth.
  constexpr int kSub = 4;
  const int nh = (grid.theta_h - 1) * kSub, nd = (grid.theta_d - 1) * kSub,
            np = (grid.phi_d - 1) * kSub;
  const double dud = kHalfPi / nd, dup = kHalfPi / np;
  std::vector<double> w(grid.Cells(), 0.0);
  for (int i = 0; i < nh; ++i) {
    const double u = (i + 0.5) / nh;
    const double theta_h = kHalfPi * u * u, dtheta_h = M_PI * u / nh;
    for (int j = 0; j < nd; ++j) {
      const double theta_d = (j + 0.5) * dud;
      for (int k = 0; k < np; ++k) {
        const HalfDiffAngles a{theta_h, theta_d, (k + 0.5) * dup};
        Vec3 l, v;
        FromHalfDiffAngles(a, &l, &v);
        if (l.z() <= 0 || v.z() <= 0) continue;
        const double density =
            4 * std::cos(theta_d) * std::sin(theta_h) * std::sin(theta_d) * l.z() * v.z();
        const double mass = density * dtheta_h * dud * dup;
        const Stencil s = StencilAt(grid, a);
        for (int n = 0; n < 8; ++n) w[s.node[n]] += s.weight[n] * mass;
      }
    }
  }
  double total = 0;
  for (const double x : w) total += x;
  for (double& x : w) x *= grid.Cells() / total;
  return w;
}

double CosineProduct(const RusinkiewiczGrid& grid, const Vec3& l, const Vec3& v) {
  return std::max(l.z(), grid.cos_floor) * std::max(v.z(), grid.cos_floor);
}

double MapValue(const RusinkiewiczGrid& grid, double f, double c) {
  return std::log(std::max(f * c, 0.0) + grid.epsilon);
}

double UnmapValue(const RusinkiewiczGrid& grid, double q, double c) {
  return std::max(std::exp(q) - grid.epsilon, 0.0) / c;
}

RusinkiewiczTable::RusinkiewiczTable(RusinkiewiczGrid grid, TableValues q)
    : grid_(grid), q_(std::move(q)) {
  grid_.Validate();
  for (int c = 0; c < 3; ++c) {
    if (static_cast<int>(q_[c].size()) != grid_.Cells()) {
      throw Error("Rusinkiewicz table: channel " + std::to_string(c) + " has " +
                  std::to_string(q_[c].size()) + " values, the grid " +
                  std::to_string(grid_.Cells()));
    }
    for (const double x : q_[c]) {
      // q = ln(f·c + ε) >= ln ε; an upper bound keeps exp(q) finite in float32 on the GPU.
      if (!std::isfinite(x) || x < std::log(grid_.epsilon) - 1e-6 || x > 80) {
        throw Error("Rusinkiewicz table: a value of channel " + std::to_string(c) +
                    " is not finite or outside [ln epsilon, 80]");
      }
    }
  }
}

Rgb RusinkiewiczTable::EvalLocal(const Vec3& l, const Vec3& v) const {
  if (l.z() <= 0 || v.z() <= 0) return Rgb::Zero();
  const Stencil s = StencilAt(grid_, ToHalfDiffAngles(l, v));
  const double c = CosineProduct(grid_, l, v);
  Rgb f;
  for (int ch = 0; ch < 3; ++ch) {
    double q = 0;
    for (int k = 0; k < 8; ++k) q += s.weight[k] * q_[ch][s.node[k]];
    f[ch] = UnmapValue(grid_, q, c);
  }
  return f;
}

Rgb RusinkiewiczTable::Eval(const Vec3& l, const Vec3& v, const Vec3& n) const {
  return EvalLocal(ToLocal(l, n), ToLocal(v, n));
}

std::string RusinkiewiczTable::Name() const {
  return "table(" + std::to_string(grid_.theta_h) + "x" + std::to_string(grid_.theta_d) + "x" +
         std::to_string(grid_.phi_d) + ")";
}

TableValues TabulateBrdf(const Brdf& brdf, const RusinkiewiczGrid& grid) {
  grid.Validate();
  TableValues q;
  for (auto& channel : q) channel.assign(grid.Cells(), 0.0);
  std::vector<char> valid(grid.Cells(), 0);
  for (int ih = 0; ih < grid.theta_h; ++ih) {
    for (int id = 0; id < grid.theta_d; ++id) {
      for (int ip = 0; ip < grid.phi_d; ++ip) {
        const HalfDiffAngles a = NodeAngles(grid, ih, id, ip);
        Vec3 l, v;
        FromHalfDiffAngles(a, &l, &v);
        if (l.z() <= 1e-9 || v.z() <= 1e-9) continue;  // below the horizon: filled below
        Rgb f = Rgb::Zero();
        for (const double phi : {a.phi_d, -a.phi_d, M_PI - a.phi_d, M_PI + a.phi_d}) {
          Vec3 lv, vv;
          FromHalfDiffAngles({a.theta_h, a.theta_d, phi}, &lv, &vv);
          f += brdf.Eval(lv, vv, Vec3::UnitZ());
        }
        f /= 4;
        const int node = grid.Index(ih, id, ip);
        const double c = CosineProduct(grid, l, v);
        for (int ch = 0; ch < 3; ++ch) q[ch][node] = MapValue(grid, f[ch], c);
        valid[node] = 1;
      }
    }
  }
  // At θh = 0 the half vector is the normal and φd is the light's azimuth, which an isotropic
  // BRDF cannot depend on: the row is averaged over φd (a measured fit need not be exactly
  // isotropic there, and a query at θh → 0 has no well-defined φd to pick a node by).
  for (auto& channel : q) {
    for (int id = 0; id < grid.theta_d; ++id) {
      if (!valid[grid.Index(0, id, 0)]) continue;
      double sum = 0;
      for (int ip = 0; ip < grid.phi_d; ++ip) sum += std::exp(channel[grid.Index(0, id, ip)]);
      const double mean = std::log(sum / grid.phi_d);
      for (int ip = 0; ip < grid.phi_d; ++ip) channel[grid.Index(0, id, ip)] = mean;
    }
  }
  // Nodes below the horizon are never looked up alone, only interpolated with valid
  // neighbours near it: continue each (θh, φd) line's last valid θd value, and a θh row with
  // none (θh = π/2) from the row before.
  for (int ih = 0; ih < grid.theta_h; ++ih) {
    for (int ip = 0; ip < grid.phi_d; ++ip) {
      int last = -1;
      for (int id = 0; id < grid.theta_d; ++id) {
        const int node = grid.Index(ih, id, ip);
        if (valid[node]) {
          last = node;
        } else {
          const int from = last >= 0 ? last : (ih > 0 ? grid.Index(ih - 1, id, ip) : -1);
          if (from < 0) continue;
          for (int ch = 0; ch < 3; ++ch) q[ch][node] = q[ch][from];
        }
      }
    }
  }
  return q;
}

}  // namespace brdfrig::brdf
