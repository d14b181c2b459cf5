#include "brdf/microfacet_model.h"

#include <cmath>
#include <sstream>

#include "brdf/microfacet_terms.h"
#include "common/error.h"

namespace brdfrig::brdf {
namespace {

[[noreturn]] void Invalid(const std::string& field, const std::string& rule, double got) {
  std::ostringstream msg;
  msg.precision(17);
  msg << field << " = " << got << "; " << rule;
  throw Error(msg.str());
}

void CheckUnitColour(const Rgb& c, const char* field) {
  static constexpr const char* kChannels[3] = {"red", "green", "blue"};
  for (int i = 0; i < 3; ++i) {
    if (!(c[i] >= 0 && c[i] <= 1)) {
      Invalid(std::string(field) + "." + kChannels[i], "must be in [0, 1]", c[i]);
    }
  }
}

void CheckRoughness(double alpha, const char* field) {
  if (!(alpha >= 1e-4 && alpha <= 4)) Invalid(field, "must be in [1e-4, 4]", alpha);
}

}  // namespace

const char* DistributionName(Distribution d) {
  switch (d) {
    case Distribution::kGgx:
      return "ggx";
    case Distribution::kBeckmann:
      return "beckmann";
    case Distribution::kTable:
      return "microfacet";
  }
  return "?";
}

void MicrofacetModelParams::Validate() const {
  CheckUnitColour(diffuse, "diffuse");
  CheckUnitColour(f0, "f0");
  CheckRoughness(alpha, "alpha");
  if (fresnel_knots.size() > static_cast<std::size_t>(kMaxFresnelKnots)) {
    Invalid("fresnel_knots.size", "must be <= " + std::to_string(kMaxFresnelKnots),
            static_cast<double>(fresnel_knots.size()));
  }
  for (std::size_t k = 0; k < fresnel_knots.size(); ++k) {
    if (!(std::abs(fresnel_knots[k]) <= 20)) {
      Invalid("fresnel_knots[" + std::to_string(k) + "]", "must be finite and within ±20",
              fresnel_knots[k]);
    }
  }
  if (distribution != Distribution::kTable) {
    if (!log_d.empty()) Invalid("log_d.size", "must be 0 for an analytic distribution", 0);
    return;
  }
  if (log_d.size() < 2 || log_d.size() > static_cast<std::size_t>(kMaxTableKnots)) {
    Invalid("log_d.size", "must be in [2, " + std::to_string(kMaxTableKnots) + "]",
            static_cast<double>(log_d.size()));
  }
  for (std::size_t k = 0; k < log_d.size(); ++k) {
    const std::string field = "log_d[" + std::to_string(k) + "]";
    if (!(std::abs(log_d[k]) <= 700)) Invalid(field, "must be finite and within ±700", log_d[k]);
    // D falls away from the normal: the fit's parameterization guarantees it; a file must too.
    if (k > 0 && log_d[k] > log_d[k - 1] + 1e-9) {
      Invalid(field, "must be <= log_d[" + std::to_string(k - 1) + "] (D is monotone)", log_d[k]);
    }
  }
  if (!(max_theta_h > 1e-4 && max_theta_h <= M_PI / 2)) {
    Invalid("max_theta_h", "must be in (1e-4, pi/2]", max_theta_h);
  }
  CheckRoughness(shadowing_alpha, "shadowing_alpha");
}

MicrofacetModel::MicrofacetModel(MicrofacetModelParams params) : params_(std::move(params)) {
  params_.Validate();
  if (params_.distribution == Distribution::kTable) {
    const int knots = static_cast<int>(params_.log_d.size());
    normalization_ = microfacet::TableNormalization(params_.log_d.data(), knots,
                                                    params_.max_theta_h, params_.alpha);
    if (!(normalization_ > 0) || !std::isfinite(normalization_)) {
      Invalid("log_d", "the distribution's projected area must be finite and > 0", normalization_);
    }
    const double shift = std::log(normalization_);
    normalized_log_d_ = params_.log_d;
    for (double& x : normalized_log_d_) x -= shift;
  }
}

double MicrofacetModel::D(double cos_h) const {
  switch (params_.distribution) {
    case Distribution::kGgx:
      return microfacet::GgxD(cos_h, params_.alpha);
    case Distribution::kBeckmann:
      return microfacet::BeckmannD(cos_h, params_.alpha);
    case Distribution::kTable: {
      const double theta_h = std::acos(std::clamp(cos_h, -1.0, 1.0));
      return std::exp(microfacet::TableLogD(normalized_log_d_.data(),
                                            static_cast<int>(normalized_log_d_.size()),
                                            params_.max_theta_h, params_.alpha, theta_h));
    }
  }
  return 0;
}

double MicrofacetModel::G1(double cos_t) const {
  switch (params_.distribution) {
    case Distribution::kGgx:
      return microfacet::GgxG1(cos_t, params_.alpha);
    case Distribution::kBeckmann:
      return microfacet::BeckmannG1(cos_t, params_.alpha);
    case Distribution::kTable:
      return microfacet::GgxG1(cos_t, params_.shadowing_alpha);
  }
  return 0;
}

Rgb MicrofacetModel::Eval(const Vec3& l, const Vec3& v, const Vec3& n) const {
  const double cos_i = n.dot(l), cos_o = n.dot(v);
  if (cos_i <= 0 || cos_o <= 0) return Rgb::Zero();
  Rgb f = params_.diffuse / M_PI;
  const Vec3 sum = l + v;
  const double norm = sum.norm();
  if (norm < 1e-300) return f;
  const Vec3 h = sum / norm;
  const double cos_h = std::min(1.0, n.dot(h));
  const double cos_d = std::clamp(l.dot(h), 0.0, 1.0);
  const double spec = D(cos_h) * G1(cos_i) * G1(cos_o) / (4 * cos_i * cos_o);
  const double correction = std::exp(microfacet::FresnelCorrection(
      params_.fresnel_knots.data(), static_cast<int>(params_.fresnel_knots.size()),
      std::acos(cos_d)));
  for (int c = 0; c < 3; ++c) {
    f[c] += microfacet::Schlick(params_.f0[c], cos_d) * correction * spec;
  }
  return f;
}

std::string MicrofacetModel::Name() const {
  std::ostringstream out;
  out << DistributionName(params_.distribution) << "(alpha=" << params_.alpha
      << ", f0=" << params_.f0.transpose() << ", diffuse=" << params_.diffuse.transpose();
  if (params_.distribution == Distribution::kTable) out << ", " << params_.log_d.size() << " knots";
  out << ")";
  return out.str();
}

}  // namespace brdfrig::brdf
