#include "calibrate/white_reference.h"

#include <cmath>
#include <sstream>

#include "calibrate/linear_grey.h"
#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::calibrate {
namespace {

struct Accumulator {
  double sum = 0, squares = 0;
  long count = 0;
  void Add(double v) {
    sum += v;
    squares += v * v;
    ++count;
  }
  double Mean() const { return sum / static_cast<double>(count); }
  double RelativeSpread() const {
    const double m = Mean();
    return std::sqrt(std::max(0.0, squares / static_cast<double>(count) - m * m)) / m;
  }
};

}  // namespace

void WhiteReferenceOptions::Validate() const {
  CheckOption(reference_albedo > 0 && reference_albedo <= 1,
              "WhiteReferenceOptions.reference_albedo", reference_albedo,
              "in (0, 1]: the tile's certified reflectance");
  CheckOption(inner_fraction > 0 && inner_fraction < 1, "WhiteReferenceOptions.inner_fraction",
              inner_fraction, "in (0, 1)");
  CheckOption(paper_margin_m >= 0 && paper_ring_m > 0, "WhiteReferenceOptions.paper_ring_m",
              paper_ring_m, "> 0 (and paper_margin_m >= 0)");
  CheckOption(max_tile_spread > 0, "WhiteReferenceOptions.max_tile_spread", max_tile_spread, "> 0");
}

std::string WhiteReferenceResult::ToString() const {
  std::ostringstream out;
  out << "paper albedo " << paper_albedo << " from " << per_photo.size() << " photos (";
  for (std::size_t i = 0; i < per_photo.size(); ++i) out << (i ? ", " : "") << per_photo[i];
  out << "); tile uniform to " << 100 * tile_spread << " %";
  return out.str();
}

WhiteReferenceResult CalibrateWhiteReference(const std::vector<CalibrationPhoto>& photos,
                                             const geometry::RigGeometry& rig,
                                             const WhiteReferenceOptions& options) {
  options.Validate();
  if (photos.empty()) throw Error("white reference: no photos");
  const geometry::CameraPose camera = rig.CameraAt(options.positions);
  const geometry::Vec3 light = rig.LightAt(options.positions);
  const geometry::Vec3 centre = camera.CenterInWorld();
  const geometry::Intrinsics& k = rig.intrinsics;
  const geometry::TargetGeometry& t = rig.target;
  WhiteReferenceResult result;
  for (const CalibrationPhoto& photo : photos) {
    if (photo.image.cols != k.width || photo.image.rows != k.height) {
      throw Error(photo.name + ": not the rig camera's " + std::to_string(k.width) + "x" +
                  std::to_string(k.height));
    }
    if (!options.flat_field.empty() && options.flat_field.size() != photo.image.size()) {
      throw Error(photo.name + ": the flat field is of another image size");
    }
    const cv::Mat signal = LinearGrey(photo.image);
    Accumulator tile, paper;
    long clipped = 0;
    for (int y = 0; y < signal.rows; ++y) {
      for (int x = 0; x < signal.cols; ++x) {
        const geometry::Vec3 ray = geometry::PixelRayInWorld(k, camera, {x, y});
        if (ray.z() >= 0) continue;
        const geometry::Vec3 p = centre - (centre.z() / ray.z()) * ray;
        const double ax = std::abs(p.x()), ay = std::abs(p.y());
        const double hw = 0.5 * t.cutout_width, hh = 0.5 * t.cutout_height;
        const bool on_tile = ax <= options.inner_fraction * hw && ay <= options.inner_fraction * hh;
        const double outside = std::max(ax - hw, ay - hh);  // distance outside the cut-out
        const bool on_paper = outside >= options.paper_margin_m &&
                              outside <= options.paper_margin_m + options.paper_ring_m;
        if (!on_tile && !on_paper) continue;
        const float s = signal.at<float>(y, x);
        if (s >= 0.999f) ++clipped;
        // Irradiance per unit intensity: cos θ_in / d².
        const geometry::Vec3 to_light = light - p;
        const double d2 = to_light.squaredNorm();
        const double irradiance = to_light.z() / std::sqrt(d2) / d2;
        double gain = 1;
        if (!options.flat_field.empty()) gain = options.flat_field.at<float>(y, x);
        const double value = s / (gain * irradiance);
        (on_tile ? tile : paper).Add(value);
      }
    }
    if (tile.count < 100 || paper.count < 100) {
      throw Error(photo.name +
                  ": the cut-out or the paper around it is not in view from the "
                  "rig's pose");
    }
    if (tile.Mean() < 0.02 * std::abs(tile.Mean() + paper.Mean()) || tile.Mean() <= 0) {
      throw Error(photo.name + ": reference tile not found: the cut-out is dark");
    }
    const double spread = tile.RelativeSpread();
    result.tile_spread = std::max(result.tile_spread, spread);
    if (spread > options.max_tile_spread) {
      throw Error(photo.name + ": reference tile not found: the cut-out's signal varies by " +
                  std::to_string(100 * spread) + " % (at most " +
                  std::to_string(100 * options.max_tile_spread) +
                  " %) once the light's fall-off is divided out; is a matte reference tile "
                  "filling the cut-out, flat on the sample plane?");
    }
    // A clipped glossy sample is "not a tile" above; a clipped tile or paper is this.
    if (clipped > 0) {
      throw Error(photo.name + ": overexposed (" + std::to_string(clipped) +
                  " pixels of the tile or paper at full scale): shorten the exposure");
    }
    result.per_photo.push_back(options.reference_albedo * paper.Mean() / tile.Mean());
  }
  double sum = 0;
  for (double v : result.per_photo) sum += v;
  result.paper_albedo = sum / static_cast<double>(result.per_photo.size());
  return result;
}

}  // namespace brdfrig::calibrate
