#include "calibrate/marker_mask.h"

#include <cmath>

#include "calibrate/charuco_spec.h"
#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::calibrate {
namespace {

// How many markers fit along `span` with at least `spacing` between them.
int FitCount(double span, double marker, double spacing) {
  return static_cast<int>(std::floor((span + spacing) / (marker + spacing) + 1e-9));
}

// Centres of `count` markers spread evenly over [-span/2, span/2] (outer edges at the ends).
std::vector<double> Centres(int count, double span, double marker) {
  std::vector<double> c;
  if (count == 1) return {0.0};
  const double step = (span - marker) / (count - 1);
  for (int i = 0; i < count; ++i) c.push_back(-0.5 * (span - marker) + i * step);
  return c;
}

MaskMarker MarkerAt(int id, const Eigen::Vector2d& centre, double side) {
  const double h = 0.5 * side;
  // As printed (world +y up the page): top-left, top-right, bottom-right, bottom-left.
  return {id,
          {Eigen::Vector2d(centre.x() - h, centre.y() + h),
           Eigen::Vector2d(centre.x() + h, centre.y() + h),
           Eigen::Vector2d(centre.x() + h, centre.y() - h),
           Eigen::Vector2d(centre.x() - h, centre.y() - h)}};
}

}  // namespace

MarkerMaskSpec MarkerMaskSpec::ForTarget(const geometry::TargetGeometry& target) {
  MarkerMaskSpec spec;
  spec.cutout_width_m = target.cutout_width;
  spec.cutout_height_m = target.cutout_height;
  spec.paper_width_m = target.paper_width;
  spec.paper_height_m = target.paper_height;
  if (target.markers) {
    spec.marker_m = target.markers->marker;
    spec.gap_m = target.markers->gap;
    spec.spacing_m = target.markers->spacing;
    spec.dictionary = target.markers->dictionary;
    spec.first_id = target.markers->first_id;
  }
  return spec;
}

void MarkerMaskSpec::Validate() const {
  CheckOption(cutout_width_m > 0 && cutout_height_m > 0, "MarkerMaskSpec.cutout_width_m",
              cutout_width_m, "> 0 (and cutout_height_m too)");
  CheckOption(marker_m >= 0.004, "MarkerMaskSpec.marker_m", marker_m, ">= 0.004 metres");
  CheckOption(gap_m >= 0, "MarkerMaskSpec.gap_m", gap_m, ">= 0");
  CheckOption(spacing_m >= 0.2 * marker_m, "MarkerMaskSpec.spacing_m", spacing_m,
              ">= 0.2 * marker_m (white between markers lets each be found)");
  CheckOption(first_id >= 0, "MarkerMaskSpec.first_id", first_id, ">= 0");
  // The ring's outer edge, plus the scale strip below it, must lie on the paper.
  const double ring_w = cutout_width_m + 2 * (gap_m + marker_m);
  const double ring_h = cutout_height_m + 2 * (gap_m + marker_m);
  CheckOption(paper_width_m >= ring_w + 2 * marker_m, "MarkerMaskSpec.paper_width_m", paper_width_m,
              ">= the ring of markers plus a marker's width each side (" +
                  std::to_string(ring_w + 2 * marker_m) + ")");
  CheckOption(paper_height_m >= ring_h + 2 * (marker_m + kScaleStripM),
              "MarkerMaskSpec.paper_height_m", paper_height_m,
              ">= the ring of markers plus room for the title and the scale bar (" +
                  std::to_string(ring_h + 2 * (marker_m + kScaleStripM)) + ")");
  int size = 0;
  try {
    size = DictionarySize(dictionary);
  } catch (const Error& e) {
    throw OptionsError(std::string("MarkerMaskSpec.dictionary: ") + e.what());
  }
  const int count = static_cast<int>(MaskMarkers(*this).size());
  CheckOption(first_id + count <= size, "MarkerMaskSpec.first_id", first_id,
              "such that its " + std::to_string(count) + " markers fit the " +
                  std::to_string(size) + " of " + dictionary);
}

nlohmann::json MarkerMaskSpec::ToJson() const {
  return {{"type", "marker_mask"},
          {"cutout_m", {cutout_width_m, cutout_height_m}},
          {"paper_m", {paper_width_m, paper_height_m}},
          {"marker_m", marker_m},
          {"gap_m", gap_m},
          {"spacing_m", spacing_m},
          {"dictionary", dictionary},
          {"first_id", first_id}};
}

std::vector<MaskMarker> MaskMarkers(const MarkerMaskSpec& spec) {
  const double m = spec.marker_m;
  // Rows above and below the cut-out run the full width of the ring; the columns fill the
  // height between the rows.
  const double row_span = spec.cutout_width_m + 2 * (spec.gap_m + m);
  const double column_span = spec.cutout_height_m + 2 * spec.gap_m - 2 * spec.spacing_m;
  const double row_y = 0.5 * spec.cutout_height_m + spec.gap_m + 0.5 * m;
  const double column_x = 0.5 * spec.cutout_width_m + spec.gap_m + 0.5 * m;
  const std::vector<double> xs = Centres(FitCount(row_span, m, spec.spacing_m), row_span, m);
  const int column_count = FitCount(column_span, m, spec.spacing_m);
  const std::vector<double> ys =
      column_count > 0 ? Centres(column_count, column_span, m) : std::vector<double>{};

  std::vector<MaskMarker> markers;
  int id = spec.first_id;
  for (double x : xs) markers.push_back(MarkerAt(id++, {x, row_y}, m));
  for (auto y = ys.rbegin(); y != ys.rend(); ++y)
    markers.push_back(MarkerAt(id++, {column_x, *y}, m));
  for (auto x = xs.rbegin(); x != xs.rend(); ++x)
    markers.push_back(MarkerAt(id++, {*x, -row_y}, m));
  for (double y : ys) markers.push_back(MarkerAt(id++, {-column_x, y}, m));
  return markers;
}

}  // namespace brdfrig::calibrate
