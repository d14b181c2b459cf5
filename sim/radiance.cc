#include "sim/radiance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "brdf/analytic.h"
#include "common/parallel.h"
#include "sim/simulator.h"

namespace brdfrig::sim {
namespace {

using brdf::Rgb;
using geometry::Vec3;

// The board's ink and paper are surfaces of their own so that pixels straddling a printed edge
// are anti-aliased like the cut-out's.
enum Surface : std::uint8_t {
  kSky = 0,
  kTable = 1,
  kPaper = 2,
  kSample = 3,
  kBoardPaper = 4,
  kBoardInk = 5,
  kMaskInk = 6  // a marker mask's print (markers, cut line, scale bar)
};

// Where a ray meets the scene board's page.
struct BoardHit {
  double distance;       // along the unit ray
  Eigen::Vector2d page;  // metres from the page's top-left
  bool front;            // the printed side faces the camera
};

struct Emitter {
  Vec3 position;
  double intensity;
};

// Emitters of the light: the point itself, or an area light's disk facing the origin sampled
// on a Vogel (golden-angle) spiral, which covers a disk evenly for any count.
std::vector<Emitter> Emitters(const Scene& scene, const TrueGeometry& g) {
  if (!g.light_on) return {};
  if (!scene.effects.area_light) return {{g.light_position, g.light_intensity}};
  const AreaLightEffect& area = *scene.effects.area_light;
  const Vec3 normal = -g.light_position.normalized();
  const Vec3 helper = std::abs(normal.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX();
  const Vec3 u = normal.cross(helper).normalized();
  const Vec3 v = normal.cross(u);
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<Emitter> emitters;
  for (int i = 0; i < area.samples; ++i) {
    const double r = area.radius * std::sqrt((i + 0.5) / area.samples);
    const double phi = i * golden_angle;
    emitters.push_back({g.light_position + r * (std::cos(phi) * u + std::sin(phi) * v),
                        g.light_intensity / area.samples});
  }
  return emitters;
}

class Shader {
 public:
  Shader(const Scene& scene, const TrueGeometry& g, const std::vector<Rgb>& sample_albedo,
         const SheetPrint* board, const SheetPrint* mask)
      : scene_(scene),
        g_(g),
        center_(g.camera.CenterInWorld()),
        emitters_(Emitters(scene, g)),
        paper_(Rgb::Constant(scene.rig.target.paper_albedo)),
        table_(scene.background_albedo),
        sample_albedo_(sample_albedo),
        board_(g.board_pose >= 0 ? board : nullptr),
        mask_(mask),
        page_from_world_(g.world_from_page.inverse()) {}

  Vec3 Ray(double u, double v) const {
    return geometry::PixelRayInWorld(g_.intrinsics, g_.camera, Eigen::Vector2d(u, v));
  }

  // The board, when the ray meets its page before anything else.
  std::optional<BoardHit> HitBoard(const Vec3& ray) const {
    if (board_ == nullptr) return std::nullopt;
    const Vec3 origin = page_from_world_ * center_;
    const Vec3 direction = page_from_world_.linear() * ray;
    if (std::abs(direction.z()) < 1e-12) return std::nullopt;
    const double t = -origin.z() / direction.z();
    if (t <= 0) return std::nullopt;
    const Vec3 p = origin + t * direction;
    if (!board_->OnPage(p.x(), p.y())) return std::nullopt;
    // The sample plane (or the table) in front of the board hides it.
    if (ray.z() < 0 && center_.z() > 0 && -center_.z() / ray.z() < t) return std::nullopt;
    return BoardHit{t, {p.x(), p.y()}, direction.z() > 0};
  }

  Surface SurfaceAt(const Vec3& ray, Vec3* point) const {
    if (const auto hit = HitBoard(ray)) {
      *point = center_ + hit->distance * ray;
      return hit->front && board_->Ink(hit->page.x(), hit->page.y()) ? kBoardInk : kBoardPaper;
    }
    if (ray.z() >= 0 || center_.z() <= 0) return kSky;
    *point = center_ - (center_.z() / ray.z()) * ray;
    const geometry::TargetGeometry& t = scene_.rig.target;
    const double ax = std::abs(point->x()), ay = std::abs(point->y());
    if (ax <= 0.5 * t.cutout_width && ay <= 0.5 * t.cutout_height) {
      return ax <= 0.5 * scene_.sample.width && ay <= 0.5 * scene_.sample.height ? kSample : kTable;
    }
    if (ax > 0.5 * t.paper_width || ay > 0.5 * t.paper_height) return kTable;
    return mask_ != nullptr && mask_->Ink(MaskPageX(*point), MaskPageY(*point)) ? kMaskInk : kPaper;
  }

  Surface SurfaceAtPixel(double u, double v) const {
    Vec3 point;
    return SurfaceAt(Ray(u, v), &point);
  }

  Rgb Radiance(double u, double v) const {
    const Vec3 ray = Ray(u, v);
    if (const auto hit = HitBoard(ray)) return BoardRadiance(ray, *hit);
    Vec3 point;
    const Surface surface = SurfaceAt(ray, &point);
    if (surface == kSky) return Rgb::Zero();
    const bool on_paper = surface == kPaper || surface == kMaskInk;
    // The printed albedo is looked up on the paper only (the sample's pixels are most of them).
    const brdf::Lambert paper = on_paper ? PaperAt(point) : paper_;
    const brdf::Brdf& material = surface == kSample ? *scene_.sample.brdf
                                 : on_paper         ? static_cast<const brdf::Brdf&>(paper)
                                                    : static_cast<const brdf::Brdf&>(table_);
    const Vec3 n = Vec3::UnitZ();
    const Vec3 view = (center_ - point).normalized();
    Rgb sum = Rgb::Zero();
    for (const Emitter& e : emitters_) {
      Vec3 l = e.position - point;
      const double d2 = l.squaredNorm();
      l /= std::sqrt(d2);
      const double cos_in = l.z();
      if (cos_in <= 0) continue;
      sum += material.Eval(l, view, n) * (e.intensity * cos_in / d2);
    }
    if (scene_.effects.ambient) {
      sum += scene_.effects.ambient->radiance * (on_paper ? paper.albedo() : Albedo(surface, view));
    }
    return sum;
  }

 private:
  // The marker mask's page coordinates of a point of the sample plane (sim/sheet_print.h).
  double MaskPageX(const Vec3& p) const { return p.x() + 0.5 * scene_.rig.target.paper_width; }
  double MaskPageY(const Vec3& p) const { return 0.5 * scene_.rig.target.paper_height - p.y(); }

  // The paper at a point: bare, or printed on a marker mask.
  brdf::Lambert PaperAt(const Vec3& p) const {
    if (mask_ == nullptr) return paper_;
    return brdf::Lambert(Rgb::Constant(mask_->Albedo(MaskPageX(p), MaskPageY(p))));
  }

  // The print is Lambertian: albedo / pi times the irradiance of each emitter on the side
  // the camera sees (the back of the sheet is bare paper).
  Rgb BoardRadiance(const Vec3& ray, const BoardHit& hit) const {
    const Vec3 point = center_ + hit.distance * ray;
    const Vec3 printed_side = -(g_.world_from_page.linear() * Vec3::UnitZ());
    const Vec3 n = hit.front ? printed_side : Vec3(-printed_side);
    const double albedo =
        hit.front ? board_->Albedo(hit.page.x(), hit.page.y()) : scene_.board->paper_albedo;
    double irradiance = 0;
    for (const Emitter& e : emitters_) {
      Vec3 l = e.position - point;
      const double d2 = l.squaredNorm();
      const double cos_in = l.dot(n) / std::sqrt(d2);
      if (cos_in > 0) irradiance += e.intensity * cos_in / d2;
    }
    Rgb sum = Rgb::Constant(albedo / M_PI * irradiance);
    if (scene_.effects.ambient) sum += scene_.effects.ambient->radiance * albedo;
    return sum;
  }

  // Directional albedo towards the viewer: by reciprocity the fraction of a uniform sky's
  // radiance that leaves towards it.
  Rgb Albedo(Surface surface, const Vec3& view) const {
    if (surface == kTable) return table_.albedo();
    const double t = std::clamp(view.z(), 0.0, 1.0) * (sample_albedo_.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(t), sample_albedo_.size() - 2);
    const double frac = t - static_cast<double>(i);
    return sample_albedo_[i] * (1 - frac) + sample_albedo_[i + 1] * frac;
  }

  const Scene& scene_;
  const TrueGeometry& g_;
  Vec3 center_;
  std::vector<Emitter> emitters_;
  brdf::Lambert paper_, table_;
  const std::vector<Rgb>& sample_albedo_;
  const SheetPrint* board_;  // null without a board
  const SheetPrint* mask_;   // null on a plain mask
  Eigen::Isometry3d page_from_world_;
};

}  // namespace

cv::Mat SynthesizeRadiance(const Scene& scene, const TrueGeometry& g,
                           const std::vector<Rgb>& sample_albedo, const SheetPrint* board,
                           const SheetPrint* mask, int threads) {
  const int width = g.intrinsics.width, height = g.intrinsics.height;
  const Shader shader(scene, g, sample_albedo, board, mask);
  const int n = scene.render.supersampling;

  // Surface seen at every pixel corner: a pixel whose four corners disagree straddles an edge.
  cv::Mat corners;
  if (n > 1) {
    corners.create(height + 1, width + 1, CV_8U);
    ParallelFor(
        height + 1,
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t y = begin; y < end; ++y) {
            auto* row = corners.ptr<std::uint8_t>(static_cast<int>(y));
            for (int x = 0; x <= width; ++x) {
              row[x] = shader.SurfaceAtPixel(x - 0.5, static_cast<double>(y) - 0.5);
            }
          }
        },
        threads);
  }

  cv::Mat image(height, width, CV_32FC3);
  ParallelFor(
      height,
      [&](std::size_t begin, std::size_t end) {
        for (int y = static_cast<int>(begin); y < static_cast<int>(end); ++y) {
          auto* out = image.ptr<cv::Vec3f>(y);
          for (int x = 0; x < width; ++x) {
            Rgb value;
            const bool edge =
                n > 1 &&
                !(corners.at<std::uint8_t>(y, x) == corners.at<std::uint8_t>(y, x + 1) &&
                  corners.at<std::uint8_t>(y, x) == corners.at<std::uint8_t>(y + 1, x) &&
                  corners.at<std::uint8_t>(y, x) == corners.at<std::uint8_t>(y + 1, x + 1));
            if (!edge) {
              value = shader.Radiance(x, y);
            } else {
              value = Rgb::Zero();
              for (int j = 0; j < n; ++j) {
                for (int i = 0; i < n; ++i) {
                  value += shader.Radiance(x - 0.5 + (i + 0.5) / n, y - 0.5 + (j + 0.5) / n);
                }
              }
              value /= n * n;
            }
            out[x] = cv::Vec3f(static_cast<float>(value[2]), static_cast<float>(value[1]),
                               static_cast<float>(value[0]));
          }
        }
      },
      threads);
  return image;
}

}  // namespace brdfrig::sim
