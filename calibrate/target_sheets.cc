#include "calibrate/target_sheets.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <opencv2/aruco/charuco.hpp>

#include "common/error.h"

namespace brdfrig::calibrate {
namespace {

constexpr double kPointsPerMm = 72.0 / 25.4;

std::string Mm(double metres, int decimals = 1) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, 1e3 * metres);
  return buffer;
}

// Black cells of an ArUco marker (border included) as squares of one path, filled once so that
// neighbouring cells merge without hairline seams. `x`, `y`: its top-left corner on the page.
void AddMarker(cairo_t* cr, const cv::aruco::Dictionary& dictionary, int id, double x, double y,
               double side) {
  const int cells = dictionary.markerSize + 2;
  cv::Mat bits;
  dictionary.drawMarker(id, cells, bits, 1);
  const double cell = side / cells;
  for (int r = 0; r < cells; ++r) {
    for (int c = 0; c < cells; ++c) {
      if (bits.at<std::uint8_t>(r, c) == 0)
        cairo_rectangle(cr, x + c * cell, y + r * cell, cell, cell);
    }
  }
}

void Text(cairo_t* cr, double x, double y, double size_mm, const std::string& text) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size_mm);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, text.c_str());
}

// A bar of `length` (mm) in alternating black and white 10 mm segments, outlined, centred on the
// page at height `y` (its top edge), with its length written under it.
void ScaleBar(cairo_t* cr, double page_width_mm, double y, double length_mm, bool with_text) {
  const double x0 = 0.5 * (page_width_mm - length_mm);
  const double height = 2.0;
  cairo_set_source_rgb(cr, 0, 0, 0);
  for (int i = 0; 10.0 * i < length_mm - 1e-9; i += 2) {
    cairo_rectangle(cr, x0 + 10.0 * i, y, std::min(10.0, length_mm - 10.0 * i), height);
  }
  cairo_fill(cr);
  cairo_set_line_width(cr, 0.15);
  cairo_rectangle(cr, x0, y, length_mm, height);
  cairo_stroke(cr);
  if (!with_text) return;
  Text(cr, x0, y + height + 3.0, 2.5,
       "0        scale bar: " + Mm(1e-3 * length_mm, 0) +
           " mm end to end, 10 mm segments. Print at 100 % (no fit to page) and check it.");
}

void DrawCharuco(cairo_t* cr, const CharucoSpec& spec, bool with_text, bool with_scale) {
  const cv::Ptr<cv::aruco::CharucoBoard> board = spec.MakeBoard();
  const Eigen::Vector2d origin = 1e3 * spec.OriginOnPage();
  const double square = 1e3 * spec.square_m;
  cairo_set_source_rgb(cr, 0, 0, 0);
  // OpenCV's board: the square at the origin is black, markers in the others.
  for (int y = 0; y < spec.squares_y; ++y) {
    for (int x = 0; x < spec.squares_x; ++x) {
      if ((x + y) % 2 == 0) {
        cairo_rectangle(cr, origin.x() + x * square, origin.y() + y * square, square, square);
      }
    }
  }
  for (std::size_t i = 0; i < board->ids.size(); ++i) {
    const cv::Point3f top_left = board->objPoints[i][0];
    AddMarker(cr, *board->dictionary, board->ids[i], origin.x() + 1e3 * top_left.x,
              origin.y() + 1e3 * top_left.y, 1e3 * spec.marker_m);
  }
  cairo_fill(cr);
  const double page_w = 1e3 * spec.page_width_m, page_h = 1e3 * spec.page_height_m;
  if (with_scale) {
    ScaleBar(cr, page_w, page_h - 1e3 * kScaleStripM + 6.0, 1e3 * ScaleBarLength(spec.page_width_m),
             with_text);
  }
  if (!with_text) return;
  Text(cr, origin.x(), 0.5 * origin.y() + 1.2, 3.0,
       "brdfrig ChArUco board: " + std::to_string(spec.squares_x) + " x " +
           std::to_string(spec.squares_y) + " squares of " + Mm(spec.square_m, 2) +
           " mm, markers " + Mm(spec.marker_m, 2) + " mm, " + spec.dictionary + ", page " +
           Mm(spec.page_width_m, 0) + " x " + Mm(spec.page_height_m, 0) + " mm");
}

void DrawMask(cairo_t* cr, const MarkerMaskSpec& spec, bool with_text) {
  spec.Validate();
  const double page_w = 1e3 * spec.paper_width_m, page_h = 1e3 * spec.paper_height_m;
  // Mask coordinates (world x, y; origin at the cut-out's centre) to page millimetres.
  auto page_x = [&](double x) { return 0.5 * page_w + 1e3 * x; };
  auto page_y = [&](double y) { return 0.5 * page_h - 1e3 * y; };
  const cv::Ptr<cv::aruco::Dictionary> dictionary = DictionaryNamed(spec.dictionary);
  const std::vector<MaskMarker> markers = MaskMarkers(spec);
  cairo_set_source_rgb(cr, 0, 0, 0);
  for (const MaskMarker& m : markers) {
    AddMarker(cr, *dictionary, m.id, page_x(m.corners[0].x()), page_y(m.corners[0].y()),
              1e3 * spec.marker_m);
  }
  cairo_fill(cr);
  // The cut line lies just inside the cut-out: cutting along its outer edge leaves the cut-out
  // at its exact size and takes the line away with it, so the mask's edge is bare paper (a dark
  // border left there would be found as the edge, and move it outwards by its width).
  const double line = 0.3;
  const double cw = 1e3 * spec.cutout_width_m, ch = 1e3 * spec.cutout_height_m;
  cairo_set_source_rgb(cr, 0.45, 0.45, 0.45);
  cairo_set_line_width(cr, line);
  cairo_rectangle(cr, page_x(0) - 0.5 * cw + 0.5 * line, page_y(0) - 0.5 * ch + 0.5 * line,
                  cw - line, ch - line);
  cairo_stroke(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  ScaleBar(cr, page_w, page_h - 1e3 * kScaleStripM, 1e3 * ScaleBarLength(spec.paper_width_m),
           with_text);
  if (!with_text) return;
  Text(cr, page_x(0) - 0.5 * cw + 3, page_y(0), 3.0,
       "cut out " + Mm(spec.cutout_width_m) + " x " + Mm(spec.cutout_height_m) + " mm");
  Text(cr, page_x(0) - 0.5 * cw + 3, page_y(0) + 5, 2.5, "along the line's outer edge");
  cairo_set_source_rgb(cr, 0, 0, 0);
  const double ring_top = page_y(0.5 * spec.cutout_height_m + spec.gap_m + spec.marker_m);
  Text(cr, 0.5 * (page_w - 1e3 * spec.cutout_width_m) - 1e3 * (spec.gap_m + spec.marker_m),
       0.5 * ring_top, 3.0,
       "brdfrig marker mask: paper " + Mm(spec.paper_width_m) + " x " + Mm(spec.paper_height_m) +
           " mm, " + std::to_string(markers.size()) + " markers of " + Mm(spec.marker_m) + " mm, " +
           spec.dictionary + " ids " + std::to_string(markers.front().id) + "-" +
           std::to_string(markers.back().id));
}

cairo_status_t AppendToString(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

std::string RenderVector(double width_m, double height_m, SheetFormat format,
                         const std::function<void(cairo_t*)>& draw) {
  std::string out;
  // A PDF page is measured in points. An SVG's user units here are millimetres: cairo writes
  // the size it is given with the document unit appended (width="297mm") and the same numbers
  // as the viewBox, so one user unit is one millimetre on paper.
  const double scale = format == SheetFormat::kPdf ? kPointsPerMm : 1.0;
  const double w = 1e3 * width_m * scale, h = 1e3 * height_m * scale;
  cairo_surface_t* surface = format == SheetFormat::kPdf
                                 ? cairo_pdf_surface_create_for_stream(AppendToString, &out, w, h)
                                 : cairo_svg_surface_create_for_stream(AppendToString, &out, w, h);
  if (format == SheetFormat::kSvg) cairo_svg_surface_set_document_unit(surface, CAIRO_SVG_UNIT_MM);
  cairo_t* cr = cairo_create(surface);
  cairo_scale(cr, scale, scale);  // draw in millimetres
  draw(cr);
  cairo_show_page(cr);
  const cairo_status_t status = cairo_status(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  const cairo_status_t surface_status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS || surface_status != CAIRO_STATUS_SUCCESS) {
    throw Error(std::string("drawing the sheet failed: ") +
                cairo_status_to_string(status != CAIRO_STATUS_SUCCESS ? status : surface_status));
  }
  return out;
}

// Ink coverage of a drawing (in millimetres from the page's top-left) on an A8 surface.
cv::Mat Rasterize(double width_m, double height_m, double px_per_m,
                  const std::function<void(cairo_t*)>& draw) {
  const int width = static_cast<int>(std::lround(width_m * px_per_m));
  const int height = static_cast<int>(std::lround(height_m * px_per_m));
  if (width < 1 || height < 1 || static_cast<double>(width) * height > 4.0e8) {
    throw Error("rasterizing a sheet at " + std::to_string(px_per_m) +
                " px/m gives an unreasonable image size");
  }
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_A8, width, height);
  cairo_t* cr = cairo_create(surface);
  cairo_scale(cr, 1e-3 * px_per_m, 1e-3 * px_per_m);
  draw(cr);
  cairo_surface_flush(surface);
  const cairo_status_t status = cairo_status(cr);
  cv::Mat out(height, width, CV_8U);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  for (int y = 0; y < height && status == CAIRO_STATUS_SUCCESS; ++y) {
    std::memcpy(out.ptr(y), data + static_cast<std::ptrdiff_t>(y) * stride, width);
  }
  cairo_destroy(cr);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) {
    throw Error(std::string("rasterizing a sheet failed: ") + cairo_status_to_string(status));
  }
  return out;
}

}  // namespace

double ScaleBarLength(double page_width_m) {
  for (double length : {0.1, 0.05, 0.02}) {
    if (length <= page_width_m - 0.02) return length;
  }
  return 0.01;
}

std::string CharucoSheet(const CharucoSpec& spec, SheetFormat format) {
  spec.Validate();
  return RenderVector(spec.page_width_m, spec.page_height_m, format,
                      [&](cairo_t* cr) { DrawCharuco(cr, spec, true, true); });
}

std::string MaskSheet(const MarkerMaskSpec& spec, SheetFormat format) {
  spec.Validate();
  return RenderVector(spec.paper_width_m, spec.paper_height_m, format,
                      [&](cairo_t* cr) { DrawMask(cr, spec, true); });
}

cv::Mat RasterizeCharucoSheet(const CharucoSpec& spec, double px_per_m, bool with_scale) {
  spec.Validate();
  return Rasterize(spec.page_width_m, spec.page_height_m, px_per_m,
                   [&](cairo_t* cr) { DrawCharuco(cr, spec, false, with_scale); });
}

cv::Mat RasterizeMaskSheet(const MarkerMaskSpec& spec, double px_per_m) {
  spec.Validate();
  return Rasterize(spec.paper_width_m, spec.paper_height_m, px_per_m,
                   [&](cairo_t* cr) { DrawMask(cr, spec, false); });
}

}  // namespace brdfrig::calibrate
