#include "reconstruct/gltf_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include "brdf/gltf_terms.h"
#include "common/error.h"
#include "common/median.h"
#include "common/option_check.h"
#include "common/parallel.h"
#include "reconstruct/log_loss.h"

namespace brdfrig::reconstruct {
namespace {

namespace gltf = brdf::gltf;

// f0 of the dielectric at most that of ior 10 (what brdf::GltfParams accepts); roughness at
// least GltfParams' floor.
constexpr double kMaxDielectricF0 = (9.0 / 11.0) * (9.0 / 11.0);
constexpr double kMinRoughness = 0.01;

struct Prepared {
  double cos_i, cos_o, cos_h, v_dot_h;
  double f[3];
  double sqrt_w;
};

// The fit works on a dielectric f0 per channel; the terms take ior and specularColor. ior 1.5
// (f0 0.04) and specularColor = f0 / 0.04 give exactly that f0 (f0 <= 0.67, never clamped).
template <typename T>
gltf::Params<T> ParamsOf(const T* base, const T* metallic, const T* roughness, const T* f0,
                         const T* specular) {
  gltf::Params<T> p;
  for (int c = 0; c < 3; ++c) {
    p.base_color[c] = base[c];
    p.specular_color[c] = f0[c] / 0.04;
  }
  p.metallic = metallic[0];
  p.roughness = roughness[0];
  p.ior = T(1.5);
  p.specular = specular[0];
  return p;
}

struct Residual {
  const Prepared* s;
  const Epsilon* eps;
  template <typename T>
  bool operator()(const T* base, const T* metallic, const T* roughness, const T* f0,
                  const T* specular, T* r) const {
    using std::log;
    T f[3];
    gltf::Eval(ParamsOf(base, metallic, roughness, f0, specular), s->cos_i, s->cos_o, s->cos_h,
               s->v_dot_h, f);
    for (int c = 0; c < 3; ++c) {
      r[c] =
          s->sqrt_w * (log((*eps)[c] + f[c] * s->cos_i) - std::log((*eps)[c] + s->f[c] * s->cos_i));
    }
    return true;
  }
};

struct Start {
  double base[3], metallic, roughness, f0[3], specular;
};

double Cost(const std::vector<Prepared>& samples, const Epsilon& eps, const Start& x) {
  double sum = 0;
  const auto p = ParamsOf(x.base, &x.metallic, &x.roughness, x.f0, &x.specular);
  for (const Prepared& s : samples) {
    double f[3];
    gltf::Eval(p, s.cos_i, s.cos_o, s.cos_h, s.v_dot_h, f);
    for (int c = 0; c < 3; ++c) {
      const double r = std::log(eps[c] + f[c] * s.cos_i) - std::log(eps[c] + s.f[c] * s.cos_i);
      sum += s.sqrt_w * s.sqrt_w * r * r;
    }
  }
  return sum;
}

// The best start on a roughness grid for a dielectric (metallic 0) or a metal (metallic 1):
// the diffuse level from the darkest tenth of the data (by measure), f0 from where the
// specular lobe dominates, for each roughness.
Start BestStart(const std::vector<Prepared>& samples, const Epsilon& eps, bool metal) {
  double rho[3];
  for (int c = 0; c < 3; ++c) {
    std::vector<std::pair<double, double>> f;
    for (const Prepared& s : samples) f.emplace_back(s.f[c], s.sqrt_w * s.sqrt_w);
    rho[c] = std::clamp(M_PI * WeightedQuantile(std::move(f), 0.1), 0.01, 0.95);
    if (!std::isfinite(rho[c])) rho[c] = 0.1;
  }
  Start best{};
  double best_cost = std::numeric_limits<double>::infinity();
  for (double roughness : {0.08, 0.15, 0.25, 0.35, 0.5, 0.7, 0.9}) {
    const double alpha = roughness * roughness;
    Start x{};
    x.metallic = metal ? 1 : 0;
    x.roughness = roughness;
    x.specular = 1;
    for (int c = 0; c < 3; ++c) {
      std::vector<double> ratios;
      for (const Prepared& s : samples) {
        const double spec = s.f[c] - (metal ? 0 : rho[c] / M_PI);
        const double unit = gltf::V(s.cos_i, s.cos_o, alpha) * gltf::D(s.cos_h, alpha);
        if (spec > rho[c] / M_PI && unit > 0) ratios.push_back(std::log(spec / unit));
      }
      const double f0 = ratios.empty() ? 0.04 : std::exp(Median(ratios));
      x.base[c] = metal ? std::clamp(f0, 0.0, 1.0) : rho[c];
      x.f0[c] = std::clamp(f0, 0.0, kMaxDielectricF0);
    }
    const double cost = Cost(samples, eps, x);
    if (cost < best_cost) best_cost = cost, best = x;
  }
  return best;
}

}  // namespace

void GltfFitOptions::Validate() const {
  if (source != "rung" && source != "samples") {
    throw OptionsError("GltfFitOptions.source = " + source + "; must be rung or samples");
  }
  CheckOption(theta_h_steps >= 4 && theta_h_steps <= 256, "GltfFitOptions.theta_h_steps",
              theta_h_steps, "must be in [4, 256]");
  CheckOption(theta_d_steps >= 2 && theta_d_steps <= 256, "GltfFitOptions.theta_d_steps",
              theta_d_steps, "must be in [2, 256]");
  CheckOption(phi_d_steps >= 1 && phi_d_steps <= 256, "GltfFitOptions.phi_d_steps", phi_d_steps,
              "must be in [1, 256]");
  CheckOption(epsilon_fraction > 0 && epsilon_fraction <= 1, "GltfFitOptions.epsilon_fraction",
              epsilon_fraction, "must be in (0, 1]");
  CheckOption(loss_scale >= 0, "GltfFitOptions.loss_scale", loss_scale, "must be >= 0");
  CheckOption(max_iterations >= 1, "GltfFitOptions.max_iterations", max_iterations, "must be >= 1");
  sphere.Validate();
}

std::vector<DirectionSample> HemisphereSamples(const brdf::Brdf& model,
                                               const GltfFitOptions& options) {
  options.Validate();
  std::vector<DirectionSample> out;
  const int nh = options.theta_h_steps, nd = options.theta_d_steps, np = options.phi_d_steps;
  const double d_theta_d = (M_PI / 2) / nd, d_phi = M_PI / np;
  for (int ih = 0; ih < nh; ++ih) {
    // theta_h = u² · pi/2 at cell midpoints in u: dense near the peak, like MERL's axis.
    const double u = (ih + 0.5) / nh;
    const double theta_h = u * u * M_PI / 2, d_theta_h = 2 * u * (M_PI / 2) / nh;
    const brdf::Vec3 h(std::sin(theta_h), 0, std::cos(theta_h));
    for (int id = 0; id < nd; ++id) {
      const double theta_d = (id + 0.5) * d_theta_d;
      for (int ip = 0; ip < np; ++ip) {
        // phi_d over [0, pi): an isotropic BRDF repeats with period pi in phi_d.
        const double phi_d = (ip + 0.5) * d_phi;
        const brdf::Vec3 d(std::sin(theta_d) * std::cos(phi_d), std::sin(theta_d) * std::sin(phi_d),
                           std::cos(theta_d));
        // d is l in the half vector's frame; rotate that frame about y by theta_h.
        const brdf::Vec3 l(std::cos(theta_h) * d.x() + std::sin(theta_h) * d.z(), d.y(),
                           -std::sin(theta_h) * d.x() + std::cos(theta_h) * d.z());
        const brdf::Vec3 v = 2 * l.dot(h) * h - l;
        if (l.z() < 1e-3 || v.z() < 1e-3) continue;
        DirectionSample s;
        s.l = l.normalized();
        s.v = v.normalized();
        const brdf::Rgb f = model.Eval(s.l, s.v, brdf::Vec3::UnitZ());
        for (int c = 0; c < 3; ++c) s.f[c] = f[c];
        // dω_i dω_o = 4 cos θd dω_h dω_d (LossWeight adds cos_i cos_o).
        s.weight = 4 * std::cos(theta_d) * std::sin(theta_h) * d_theta_h * std::sin(theta_d) *
                   d_theta_d * d_phi;
        out.push_back(s);
      }
    }
  }
  return out;
}

std::vector<DirectionSample> PoolDirectionSamples(const std::vector<PositionSamples>& positions) {
  std::vector<DirectionSample> all;
  for (const PositionSamples& p : positions) {
    double total = 0;
    for (const DirectionSample& s : p.directions.samples) total += s.weight;
    if (!(total > 0)) continue;
    for (DirectionSample s : p.directions.samples) {
      s.weight *= 1000.0 / total;
      all.push_back(s);
    }
  }
  return all;
}

GltfFit FitGltf(const std::vector<DirectionSample>& input, const GltfFitOptions& options) {
  options.Validate();
  const auto start_time = std::chrono::steady_clock::now();
  std::vector<Prepared> samples;
  double total_weight = 0;
  for (const DirectionSample& s : input) {
    if (!(s.l.z() > 0 && s.v.z() > 0 && LossWeight(s) > 0)) continue;
    if (!(std::isfinite(s.f[0]) && std::isfinite(s.f[1]) && std::isfinite(s.f[2]))) continue;
    const brdf::Vec3 h = (s.l + s.v).normalized();
    samples.push_back(
        {s.l.z(), s.v.z(), h.z(), s.v.dot(h), {s.f[0], s.f[1], s.f[2]}, LossWeight(s)});
    total_weight += LossWeight(s);
  }
  if (samples.size() < 10) {
    throw Error("the glTF fit needs at least 10 directions, got " + std::to_string(samples.size()));
  }
  // Weights summing to the sample count: the solver's tolerances then mean the same for any
  // source.
  for (Prepared& s : samples) {
    s.sqrt_w = std::sqrt(s.sqrt_w * static_cast<double>(samples.size()) / total_weight);
  }
  const Epsilon eps = LossEpsilon(input, options.epsilon_fraction);

  // The dielectric and the metal start, solved side by side (each alone on its thread, so the
  // results do not depend on the thread count); the lower cost wins, the dielectric on a tie.
  std::array<Start, 2> solved;
  std::array<double, 2> cost;
  cost.fill(std::numeric_limits<double>::infinity());
  ParallelFor(2, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const bool metal = i == 1;
      Start& x = solved[i];
      x = BestStart(samples, eps, metal);
      ceres::Problem problem;
      for (const Prepared& s : samples) {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<Residual, 3, 3, 1, 1, 3, 1>(new Residual{&s, &eps}),
            options.loss_scale > 0 ? new ceres::HuberLoss(options.loss_scale) : nullptr, x.base,
            &x.metallic, &x.roughness, x.f0, &x.specular);
      }
      for (int c = 0; c < 3; ++c) {
        problem.SetParameterLowerBound(x.base, c, 0);
        problem.SetParameterUpperBound(x.base, c, 1);
        problem.SetParameterLowerBound(x.f0, c, 0);
        problem.SetParameterUpperBound(x.f0, c, kMaxDielectricF0);
      }
      problem.SetParameterLowerBound(&x.metallic, 0, 0);
      problem.SetParameterUpperBound(&x.metallic, 0, 1);
      problem.SetParameterLowerBound(&x.roughness, 0, kMinRoughness);
      problem.SetParameterUpperBound(&x.roughness, 0, 1);
      problem.SetParameterLowerBound(&x.specular, 0, 0);
      problem.SetParameterUpperBound(&x.specular, 0, 1);
      ceres::Solver::Options solver;
      solver.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
      solver.max_num_iterations = options.max_iterations;
      solver.function_tolerance = 1e-7;
      solver.parameter_tolerance = 1e-8;
      solver.num_threads = 1;
      ceres::Solver::Summary summary;
      ceres::Solve(solver, &problem, &summary);
      cost[i] = summary.final_cost;
    }
  });
  GltfFit best;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < solved.size(); ++i) {
    if (!(cost[i] < best_cost)) continue;
    best_cost = cost[i];
    const Start& x = solved[i];
    brdf::GltfParams& p = best.params;
    p.base_color = brdf::Rgb(x.base[0], x.base[1], x.base[2]).cwiseMax(0).cwiseMin(1);
    p.metallic = std::clamp(x.metallic, 0.0, 1.0);
    p.roughness = std::clamp(x.roughness, kMinRoughness, 1.0);
    p.specular = std::clamp(x.specular, 0.0, 1.0);
    // f0 as ior (its largest channel) and specularColor (f0 over that channel).
    const brdf::Rgb f0 =
        brdf::Rgb(x.f0[0], x.f0[1], x.f0[2]).cwiseMax(0).cwiseMin(kMaxDielectricF0);
    const double top = f0.maxCoeff();
    if (top > 1e-8) {
      const double r = std::sqrt(top);
      p.ior = std::clamp((1 + r) / (1 - r), 1.0, 10.0);
      p.specular_color = (f0 / brdf::gltf::IorF0(p.ior)).cwiseMin(1.0);
    } else {
      p.ior = 1.5;
      p.specular_color = brdf::Rgb::Zero();
    }
  }
  if (!std::isfinite(best_cost)) throw Error("the glTF fit failed");
  best.params.Validate();
  best.source = options.source;
  best.sample_count = static_cast<int>(samples.size());
  best.residual = std::sqrt(2 * best_cost / (3.0 * static_cast<double>(samples.size())));
  best.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  return best;
}

void AddGltfVersion(brdf::Material* material, const GltfFitOptions& options,
                    const std::vector<DirectionSample>& samples) {
  options.Validate();
  if (material->kind == brdf::ModelKind::kGltf) {
    material->gltf_fit = {{"source", "the material itself (kind gltf)"}};
    return;
  }
  const std::shared_ptr<const brdf::Brdf> model = material->Model();
  const GltfFit fit = options.source == "samples"
                          ? FitGltf(samples, options)
                          : FitGltf(HemisphereSamples(*model, options), options);
  material->gltf = fit.params;
  const brdf::SphereFigure figure =
      brdf::SpherePsnr(*model, brdf::GltfModel(fit.params), options.sphere);
  nlohmann::json per_light = nlohmann::json::object();
  for (std::size_t i = 0; i < figure.psnr_db.size(); ++i) {
    per_light[std::to_string(static_cast<int>(options.sphere.light_angles_deg[i]))] =
        std::isfinite(figure.psnr_db[i]) ? nlohmann::json(figure.psnr_db[i])
                                         : nlohmann::json("inf");
  }
  const auto finite_or_text = [](double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json("inf");
  };
  material->gltf_fit = {
      {"source", fit.source == "rung" ? "the chosen rung over the whole hemisphere"
                                      : "the capture's direction samples"},
      {"rung", brdf::ModelKindName(material->kind)},
      {"residual", fit.residual},
      {"directions", fit.sample_count},
      {"sphere_vs_model",
       {{"mean_psnr_db", finite_or_text(figure.mean_psnr_db)},
        {"worst_psnr_db", finite_or_text(figure.worst_psnr_db)},
        {"per_light_deg", per_light},
        {"protocol", "evaluate/sphere_test.h: the glTF version against the rung it came from, " +
                         std::to_string(options.sphere.resolution) + " px"}}}};
}

}  // namespace brdfrig::reconstruct
