#include "reconstruct/direction_samples.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/parallel.h"

namespace brdfrig::reconstruct {
namespace {

struct Pixel {
  brdf::Vec3 l, v;
  std::array<double, 3> f;
  std::array<double, 3> radiance;  // as merged, before the radiometry
  std::array<double, 3> floor_f;   // f at the noise floor's radiance
  double theta_h, theta_d;
};

// Where the blocks go: the samples, and the bounds of blocks below the noise floor.
struct BlockOutput {
  double noise_floor = 0;
  std::vector<DirectionSample> samples;
  std::vector<DirectionSample> bounds;
  int pixels_below_noise_floor = 0;
};

// The noise floor is judged on blocks of at least this many pixels (a small block inherits the
// verdict of the smallest enclosing block that has them). A block of a few pixels has a mean
// as noisy as the floor is high: judged on its own, its upward fluctuations would be kept and
// its downward ones dropped, which reads a dark region brighter than it is, the bias the floor
// exists to avoid. 64 pixels average the read noise to an eighth.
constexpr std::size_t kFloorPixels = 64;

// Whether the mean radiance of `pixels`, in its brightest channel, is below the floor.
bool BelowNoiseFloor(const std::vector<const Pixel*>& pixels, double noise_floor) {
  std::array<double, 3> radiance{};
  for (const Pixel* p : pixels) {
    for (int c = 0; c < 3; ++c) radiance[c] += p->radiance[c];
  }
  return *std::max_element(radiance.begin(), radiance.end()) / static_cast<double>(pixels.size()) <
         noise_floor;
}

void Emit(const std::vector<const Pixel*>& pixels, bool below_noise_floor, BlockOutput* out) {
  if (pixels.empty()) return;
  const double n = static_cast<double>(pixels.size());
  DirectionSample s;
  s.l.setZero();
  s.v.setZero();
  std::array<double, 3> floor_f{};
  for (const Pixel* p : pixels) {
    s.l += p->l;
    s.v += p->v;
    for (int c = 0; c < 3; ++c) {
      s.f[c] += p->f[c];
      floor_f[c] += p->floor_f[c];
    }
  }
  s.l.normalize();
  s.v.normalize();
  for (double& f : s.f) f /= n;
  s.weight = n;
  if (below_noise_floor) {
    // The bound: the block's mean plus two standard errors of its read noise (the floor is two
    // sigmas, so floor / sqrt(n)). Clipping the noise at zero only raises the mean, so the
    // bound holds for photos written with or without a black level.
    for (int c = 0; c < 3; ++c) s.f[c] = std::max(s.f[c], 0.0) + floor_f[c] / n / std::sqrt(n);
    out->pixels_below_noise_floor += static_cast<int>(pixels.size());
    out->bounds.push_back(s);
  } else {
    out->samples.push_back(s);
  }
}

// Emits the block as one sample, or splits it into four while its angular spans are too wide.
// `below_noise_floor`: the verdict of the enclosing block (at the root: of the block itself).
void Reduce(const std::vector<const Pixel*>& pixels, const std::vector<int>& px,
            const std::vector<int>& py, int x0, int y0, int size,
            const DirectionSampleOptions& options, bool below_noise_floor, BlockOutput* out) {
  if (pixels.empty()) return;
  if (pixels.size() >= kFloorPixels) {
    below_noise_floor = BelowNoiseFloor(pixels, out->noise_floor);
  }
  double h_lo = 1e9, h_hi = -1e9, d_lo = 1e9, d_hi = -1e9;
  for (const Pixel* p : pixels) {
    h_lo = std::min(h_lo, p->theta_h);
    h_hi = std::max(h_hi, p->theta_h);
    d_lo = std::min(d_lo, p->theta_d);
    d_hi = std::max(d_hi, p->theta_d);
  }
  const bool narrow =
      h_hi - h_lo <= std::max(options.min_theta_h_span, options.relative_theta_h_span * h_lo) &&
      d_hi - d_lo <= options.max_theta_d_span;
  if (narrow || size <= 1) {
    Emit(pixels, below_noise_floor, out);
    return;
  }
  const int half = size / 2;
  for (int qy = 0; qy < 2; ++qy) {
    for (int qx = 0; qx < 2; ++qx) {
      std::vector<const Pixel*> sub;
      std::vector<int> sx, sy;
      for (std::size_t i = 0; i < pixels.size(); ++i) {
        if ((px[i] >= x0 + half) == (qx == 1) && (py[i] >= y0 + half) == (qy == 1)) {
          sub.push_back(pixels[i]);
          sx.push_back(px[i]);
          sy.push_back(py[i]);
        }
      }
      Reduce(sub, sx, sy, x0 + qx * half, y0 + qy * half, half, options, below_noise_floor, out);
    }
  }
}

}  // namespace

void DirectionSampleOptions::Validate() const {
  if (max_block_px < 1 || max_block_px > 256 || (max_block_px & (max_block_px - 1)) != 0) {
    throw OptionsError("DirectionSampleOptions.max_block_px = " + std::to_string(max_block_px) +
                       "; must be a power of 2 in [1, 256]");
  }
  if (!(min_theta_h_span > 0)) {
    throw OptionsError("DirectionSampleOptions.min_theta_h_span must be > 0");
  }
  if (!(relative_theta_h_span >= 0)) {
    throw OptionsError("DirectionSampleOptions.relative_theta_h_span must be >= 0");
  }
  if (!(max_theta_d_span > 0)) {
    throw OptionsError("DirectionSampleOptions.max_theta_d_span must be > 0");
  }
}

HalfAngles HalfAnglesOf(const brdf::Vec3& l, const brdf::Vec3& v) {
  const brdf::Vec3 sum = l + v;
  const double norm = sum.norm();
  if (norm < 1e-300) return {M_PI / 2, M_PI / 2};
  const brdf::Vec3 h = sum / norm;
  // atan2 forms: accurate at 0 (acos loses half the digits there).
  return {std::atan2(std::hypot(h.x(), h.y()), h.z()), std::atan2(h.cross(l).norm(), h.dot(l))};
}

DirectionSamples ExtractDirectionSamples(const cv::Mat& radiance, const cv::Mat& valid,
                                         double noise_floor, const PlaneView& view,
                                         const geometry::Vec3& light, const Radiometry& radiometry,
                                         const geometry::TargetGeometry& target,
                                         const SampleOptions& sample_options,
                                         const DirectionSampleOptions& options) {
  sample_options.Validate();
  options.Validate();
  const SampleRegion region = SampleRegionOf(view, target, sample_options);
  const PlaneView::Box& box = region.box;
  const geometry::Vec3& camera = view.camera_centre();
  const int b = options.max_block_px;
  const int blocks_x = std::max(0, (box.x1 - box.x0 + b - 1) / b);
  const int blocks_y = std::max(0, (box.y1 - box.y0 + b - 1) / b);

  // One row of blocks per task: deterministic order whatever the thread count.
  std::vector<BlockOutput> rows(static_cast<std::size_t>(blocks_y), BlockOutput{noise_floor});
  std::vector<int> used(static_cast<std::size_t>(blocks_y), 0);
  ParallelFor(rows.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      const int y0 = box.y0 + static_cast<int>(r) * b;
      for (int bx = 0; bx < blocks_x; ++bx) {
        const int x0 = box.x0 + bx * b;
        std::vector<Pixel> pixels;
        std::vector<int> px, py;
        for (int y = y0; y < std::min(y0 + b, box.y1); ++y) {
          for (int x = x0; x < std::min(x0 + b, box.x1); ++x) {
            const auto p = view.PointAt(x, y);
            if (!p || !region.Contains(*p)) continue;
            if (!valid.at<uchar>(y, x)) continue;
            const double e = PointLightIrradiance(light, *p);
            const cv::Vec3f value = radiance.at<cv::Vec3f>(y, x);
            if (!(e > 0) || !std::isfinite(value[0]) || !std::isfinite(value[1]) ||
                !std::isfinite(value[2])) {
              continue;
            }
            Pixel pixel;
            pixel.l = (light - *p).normalized();
            pixel.v = (camera - *p).normalized();
            if (pixel.l.z() <= 0 || pixel.v.z() <= 0) continue;
            const cv::Vec3d k = radiometry.ScaleAt(x, y);
            // B,G,R image → R,G,B material channels.
            pixel.f = {value[2] / (k[2] * e), value[1] / (k[1] * e), value[0] / (k[0] * e)};
            pixel.radiance = {value[2], value[1], value[0]};
            pixel.floor_f = {noise_floor / (k[2] * e), noise_floor / (k[1] * e),
                             noise_floor / (k[0] * e)};
            const HalfAngles angles = HalfAnglesOf(pixel.l, pixel.v);
            pixel.theta_h = angles.theta_h;
            pixel.theta_d = angles.theta_d;
            pixels.push_back(pixel);
            px.push_back(x);
            py.push_back(y);
          }
        }
        std::vector<const Pixel*> pointers;
        for (const Pixel& p : pixels) pointers.push_back(&p);
        used[r] += static_cast<int>(pixels.size());
        if (pointers.empty()) continue;
        Reduce(pointers, px, py, x0, y0, b, options, BelowNoiseFloor(pointers, noise_floor),
               &rows[r]);
      }
    }
  });
  DirectionSamples out;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    out.samples.insert(out.samples.end(), rows[r].samples.begin(), rows[r].samples.end());
    out.bounds.insert(out.bounds.end(), rows[r].bounds.begin(), rows[r].bounds.end());
    out.pixels_used += used[r] - rows[r].pixels_below_noise_floor;
    out.pixels_below_noise_floor += rows[r].pixels_below_noise_floor;
  }
  out.theta_h_min = out.theta_d_min = 1e9;
  out.theta_h_max = out.theta_d_max = 0;
  for (const DirectionSample& s : out.samples) {
    const HalfAngles a = HalfAnglesOf(s.l, s.v);
    out.theta_h_min = std::min(out.theta_h_min, a.theta_h);
    out.theta_h_max = std::max(out.theta_h_max, a.theta_h);
    out.theta_d_min = std::min(out.theta_d_min, a.theta_d);
    out.theta_d_max = std::max(out.theta_d_max, a.theta_d);
  }
  if (out.samples.empty()) out.theta_h_min = out.theta_d_min = 0;
  return out;
}

}  // namespace brdfrig::reconstruct
