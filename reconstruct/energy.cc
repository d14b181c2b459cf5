#include "reconstruct/energy.h"

#include <algorithm>
#include <cmath>

#include "common/angles.h"
#include "common/format.h"

namespace brdfrig::reconstruct {

brdf::Rgb HalfVectorAlbedo(const brdf::Brdf& brdf, double theta_in, int theta_h_steps,
                           int phi_steps) {
  const brdf::Vec3 n = brdf::Vec3::UnitZ();
  const brdf::Vec3 l(std::sin(theta_in), 0, std::cos(theta_in));
  brdf::Rgb sum = brdf::Rgb::Zero();
  // theta_h = u² · pi/2, midpoint rule in u and phi.
  for (int i = 0; i < theta_h_steps; ++i) {
    const double u = (i + 0.5) / theta_h_steps;
    const double theta_h = u * u * M_PI / 2;
    const double d_theta_h = 2 * u * (M_PI / 2) / theta_h_steps;
    const double sin_h = std::sin(theta_h), cos_h = std::cos(theta_h);
    for (int k = 0; k < phi_steps; ++k) {
      const double phi = (k + 0.5) * 2 * M_PI / phi_steps;
      const brdf::Vec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
      const double hl = h.dot(l);
      if (hl <= 0) continue;
      const brdf::Vec3 v = 2 * hl * h - l;
      if (v.z() <= 0) continue;
      // dω_o = 4 (h·l) dω_h, dω_h = sin dtheta_h dphi.
      sum += brdf.Eval(l, v, n) * (v.z() * 4 * hl * sin_h * d_theta_h * 2 * M_PI / phi_steps);
    }
  }
  return sum;
}

AlbedoPeak MaxAlbedo(const brdf::Brdf& brdf) {
  AlbedoPeak peak;
  for (int deg = 0; deg <= 85; deg += 5) {
    const double theta_in = Radians(deg);
    const double a = HalfVectorAlbedo(brdf, theta_in).maxCoeff();
    if (a > peak.albedo) peak = {a, theta_in};
  }
  return peak;
}

double LimitMicrofacetEnergy(brdf::MicrofacetModelParams* params, std::string* note,
                             double margin) {
  note->clear();
  const double limit = 1 - margin;
  bool lowered_diffuse = false;
  for (int c = 0; c < 3; ++c) {
    if (params->diffuse[c] > limit) {
      params->diffuse[c] = limit;
      lowered_diffuse = true;
    }
  }
  brdf::MicrofacetModelParams specular = *params;
  specular.diffuse = brdf::Rgb::Zero();
  const brdf::MicrofacetModel model(specular);
  double scale = 1;
  double worst_theta = 0;
  for (int deg = 0; deg <= 85; deg += 5) {
    const double theta_in = Radians(deg);
    const brdf::Rgb spec = HalfVectorAlbedo(model, theta_in);
    for (int c = 0; c < 3; ++c) {
      if (spec[c] <= 0) continue;
      const double s = (limit - params->diffuse[c]) / spec[c];
      if (s < scale) {
        scale = s;
        worst_theta = theta_in;
      }
    }
  }
  if (scale < 1) {
    scale = std::max(scale, 1e-6);
    if (params->fresnel_knots.empty()) params->fresnel_knots.assign(2, 0.0);
    for (double& k : params->fresnel_knots) k += std::log(scale);
    *note =
        "energy: the fitted specular term reflected more than the light it receives at "
        "theta_in " +
        Fixed(Degrees(worst_theta), 0) + "° (albedo " + Fixed(1 / scale, 3) +
        "× the allowed); scaled by " + Fixed(scale, 4) + " (a constant in the Fresnel correction)";
  }
  if (lowered_diffuse) {
    *note += std::string(note->empty() ? "" : "; ") + "energy: a diffuse albedo above " +
             Fixed(limit, 3) + " was lowered to it";
  }
  return scale;
}

double LimitTableEnergy(const brdf::RusinkiewiczGrid& grid, brdf::TableValues* table,
                        double margin) {
  double largest = 1;
  // Albedo at one angle integrates over others, so a few rounds.
  for (int round = 0; round < 4; ++round) {
    const brdf::RusinkiewiczTable whole(grid, *table);
    std::vector<double> excess(18, 1.0);
    bool over = false;
    for (int i = 0; i < 18; ++i) {
      const double a = HalfVectorAlbedo(whole, Radians(5.0 * i)).maxCoeff();
      excess[i] = std::max(1.0, a / (1 - margin));
      over = over || excess[i] > 1;
    }
    if (!over) break;
    const auto scale_at = [&](double theta) {
      const double u = std::clamp(Degrees(theta) / 5, 0.0, 17.0);
      const int i = std::min(static_cast<int>(u), 16);
      return excess[i] + (u - i) * (excess[i + 1] - excess[i]);
    };
    for (int ih = 0; ih < grid.theta_h; ++ih) {
      for (int id = 0; id < grid.theta_d; ++id) {
        for (int ip = 0; ip < grid.phi_d; ++ip) {
          brdf::Vec3 l, v;
          brdf::FromHalfDiffAngles(brdf::NodeAngles(grid, ih, id, ip), &l, &v);
          const double theta_i = std::acos(std::clamp(l.z(), 0.0, 1.0));
          const double theta_o = std::acos(std::clamp(v.z(), 0.0, 1.0));
          const double s = std::max(scale_at(theta_i), scale_at(theta_o));
          if (s <= 1) continue;
          const double f = 1.02 * s;  // 2 % more than the excess: the rounds converge from below
          largest = std::max(largest, f);
          for (auto& channel : *table) {
            double& q = channel[grid.Index(ih, id, ip)];
            q = std::log((std::exp(q) - grid.epsilon) / f + grid.epsilon);
          }
        }
      }
    }
  }
  return largest;
}

}  // namespace brdfrig::reconstruct
