#include "evaluate/report_json.h"

#include <map>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/format.h"
#include "evaluate/brdf_plots.h"
#include "evaluate/coverage_report.h"
#include "evaluate/material_preview.h"
#include "evaluate/material_report.h"
#include "evaluate/svg_plot.h"
#include "evaluate/validation_photos.h"

namespace brdfrig::evaluate {
namespace {

using nlohmann::json;

std::string Cell(const json& value, int decimals) { return Fixed(NumberFromJson(value), decimals); }

std::string RgbCell(const json& rgb, int decimals) {
  return Cell(rgb.at(0), decimals) + " " + Cell(rgb.at(1), decimals) + " " +
         Cell(rgb.at(2), decimals);
}

ReportSection HeldOutSection(const json& held) {
  ReportSection s{"Held-out views", {}, {}, {}, {}};
  const json& p = held.at("protocols");
  s.paragraphs.push_back(
      "Photos of views not used for the fit (camera and light at the same elevation, the light "
      "turned by phi about the sample normal) against renderings of the fit.");
  s.paragraphs.push_back("whole photo: " + p.at("whole_photo_psnr_db").get<std::string>() +
                         " (how the seed compared photos).");
  s.paragraphs.push_back("sample only: " + p.at("sample_only_psnr_db").get<std::string>() + ".");
  s.paragraphs.push_back("normalized sample (exposure independent): " +
                         p.at("normalized_sample_psnr_db").get<std::string>() + ".");
  s.paragraphs.push_back("relative RMSE: " + p.at("relative_rmse").get<std::string>() + ".");
  Table by{"Held-out views by elevation (means over light azimuths)",
           {"elevation (deg)", "views", "whole photo (dB)", "sample only (dB)",
            "normalized sample (dB)", "relative RMSE"},
           {}};
  for (const json& e : held.at("by_elevation")) {
    by.rows.push_back({Cell(e.at("elevation_deg"), 0), std::to_string(e.at("views").get<int>()),
                       Cell(e.at("whole_photo_psnr_db"), 2), Cell(e.at("sample_only_psnr_db"), 2),
                       Cell(e.at("normalized_sample_psnr_db"), 2), Cell(e.at("relative_rmse"), 4)});
  }
  s.tables.push_back(by);
  Table views{"Held-out PSNR (dB) and relative RMSE per view",
              {"elevation (deg)", "phi (deg)", "whole photo", "sample only", "normalized sample",
               "relative RMSE"},
              {}};
  std::map<long, Series> series;  // normalized sample PSNR against phi, one line per elevation
  for (const json& v : held.at("views")) {
    const double elevation = v.at("elevation_deg").get<double>();
    const double phi = v.at("phi_deg").get<double>();
    views.rows.push_back({Fixed(elevation, 0), Fixed(phi, 0), Cell(v.at("whole_photo_psnr_db"), 2),
                          Cell(v.at("sample_only_psnr_db"), 2),
                          Cell(v.at("normalized_sample_psnr_db"), 2),
                          Cell(v.at("relative_rmse"), 4)});
    Series& line = series[std::lround(elevation * 1000)];
    line.label = "elevation " + Fixed(elevation, 0) + "°";
    line.x.push_back(phi);
    line.y.push_back(NumberFromJson(v.at("normalized_sample_psnr_db")));
    if (v.contains("images")) {
      const json& im = v.at("images");
      const std::string where =
          "elevation " + Fixed(elevation, 0) + "°, phi " + Fixed(phi, 0) + "°";
      s.images.push_back({im.at("photo").get<std::string>(), where + ": held-out photo"});
      s.images.push_back({im.at("render").get<std::string>(), "rendering of the fitted model"});
      s.images.push_back({im.at("diff").get<std::string>(), "|difference| (same scale)"});
    }
  }
  s.tables.push_back(views);
  std::vector<Series> lines;
  for (auto& [key, line] : series) lines.push_back(line);
  s.svg_plots.push_back(SvgLinePlot(lines, {"Held-out normalized sample PSNR against phi",
                                            "phi (degrees)", "PSNR (dB)", 640, 400}));
  return s;
}

ReportSection SphereSection(const json& sphere) {
  ReportSection s{"Sphere test", {}, {}, {}, {}};
  s.paragraphs.push_back(
      "The fitted and the true material on a sphere under a directional light "
      "at several angles from the view direction. Protocol: " +
      sphere.at("protocol").get<std::string>() + ".");
  s.paragraphs.push_back("Mean sphere PSNR " + Cell(sphere.at("mean_psnr_db"), 2) +
                         " dB (worst light " + Cell(sphere.at("worst_psnr_db"), 2) +
                         " dB); mean relative RMSE " + Cell(sphere.at("mean_relative_rmse"), 4) +
                         ".");
  Table t{"Sphere test per light",
          {"light from view (deg)", "PSNR (dB)", "relative RMSE", "scale (truth 99th pct)"},
          {}};
  for (const json& l : sphere.at("lights")) {
    const std::string angle = Cell(l.at("light_angle_deg"), 0);
    t.rows.push_back(
        {angle, Cell(l.at("psnr_db"), 2), Cell(l.at("relative_rmse"), 4), Cell(l.at("scale"), 5)});
    if (l.contains("images")) {
      s.images.push_back(
          {l.at("images").at("truth").get<std::string>(), "light " + angle + "°: truth"});
      s.images.push_back({l.at("images").at("fit").get<std::string>(), "fit (same scale)"});
    }
  }
  t.rows.push_back(
      {"mean", Cell(sphere.at("mean_psnr_db"), 2), Cell(sphere.at("mean_relative_rmse"), 4), ""});
  s.tables.push_back(t);
  return s;
}

ReportSection BrdfSection(const json& b) {
  ReportSection s{"BRDF against the truth", {}, {}, {}, {}};
  s.paragraphs.push_back(
      "Log-cosine error (brdf::LogCosineError) of the fit against the simulated sample's BRDF: " +
      Cell(b.at("log_cosine_error"), 4));
  s.paragraphs.push_back("Directional albedo error, max over angles and channels: " +
                         Cell(b.at("max_albedo_error"), 3) + " (" +
                         b.at("protocol").get<std::string>() + ").");
  Table t{"Directional albedo (energy check; <= 1 conserves energy), R G B",
          {"theta_in (deg)", "truth", "fitted", "relative error"},
          {}};
  for (const json& a : b.at("albedo")) {
    t.rows.push_back({Cell(a.at("theta_in_deg"), 0), RgbCell(a.at("truth"), 4),
                      RgbCell(a.at("fitted"), 4), Cell(a.at("relative_error"), 3)});
  }
  s.tables.push_back(t);
  return s;
}

}  // namespace

json NewReportJson(const std::string& title) {
  return {{"format", "brdfrig-report"},
          {"version", 1},
          {"title", title},
          {"sections", json::array()},
          {"figures", json::object()}};
}

json SectionJson(const ReportSection& section) {
  json s = {{"title", section.title},
            {"paragraphs", section.paragraphs},
            {"tables", json::array()},
            {"images", json::array()}};
  for (const Table& t : section.tables) {
    s["tables"].push_back({{"caption", t.caption}, {"header", t.header}, {"rows", t.rows}});
  }
  for (const auto& [file, caption] : section.images) {
    s["images"].push_back({{"file", file}, {"caption", caption}});
  }
  if (!section.grids.empty()) {
    s["grids"] = json::array();
    for (const ImageGrid& g : section.grids) {
      json grid = {{"caption", g.caption}, {"columns", g.columns}, {"rows", json::array()}};
      for (const ImageGridRow& row : g.rows) {
        json cells = json::array();
        for (const ImageCell& c : row.cells) {
          cells.push_back({{"file", c.file}, {"caption", c.caption}});
        }
        grid["rows"].push_back({{"label", row.label}, {"cells", cells}});
      }
      s["grids"].push_back(grid);
    }
  }
  return s;
}

Report ReportFromJson(const json& report) {
  if (report.value("format", "") != "brdfrig-report") {
    throw Error("report.json: not a brdfrig report (format " + report.value("format", "?") + ")");
  }
  Report out;
  out.title = report.at("title").get<std::string>();
  const json& figures = report.at("figures");
  // What a person looks for first comes first: the material itself, what the photos covered,
  // and its BRDF as curves; then the job's own tables and the figures' details.
  if (figures.contains("preview")) {
    const json* photos =
        figures.contains("validation_photos") ? &figures.at("validation_photos") : nullptr;
    const json* photos_gltf = figures.contains("validation_photos_gltf")
                                  ? &figures.at("validation_photos_gltf")
                                  : nullptr;
    out.sections.push_back(MaterialPreviewSection(figures.at("preview"), photos, photos_gltf));
  }
  if (figures.contains("coverage")) out.sections.push_back(CoverageSection(figures.at("coverage")));
  if (figures.contains("brdf_plots")) {
    out.sections.push_back(BrdfPlotsSection(figures.at("brdf_plots")));
  }
  for (const json& s : report.at("sections")) {
    ReportSection section{s.at("title").get<std::string>(), {}, {}, {}, {}};
    section.paragraphs = s.at("paragraphs").get<std::vector<std::string>>();
    for (const json& t : s.at("tables")) {
      section.tables.push_back({t.at("caption").get<std::string>(),
                                t.at("header").get<std::vector<std::string>>(),
                                t.at("rows").get<std::vector<std::vector<std::string>>>()});
    }
    for (const json& i : s.value("images", json::array())) {
      section.images.push_back(
          {i.at("file").get<std::string>(), i.at("caption").get<std::string>()});
    }
    for (const json& g : s.value("grids", json::array())) {
      ImageGrid grid{
          g.at("caption").get<std::string>(), g.at("columns").get<std::vector<std::string>>(), {}};
      for (const json& row : g.at("rows")) {
        ImageGridRow r{row.at("label").get<std::string>(), {}};
        for (const json& c : row.at("cells")) {
          r.cells.push_back({c.at("file").get<std::string>(), c.at("caption").get<std::string>()});
        }
        grid.rows.push_back(r);
      }
      section.grids.push_back(grid);
    }
    out.sections.push_back(section);
  }
  if (figures.contains("held_out")) out.sections.push_back(HeldOutSection(figures["held_out"]));
  if (figures.contains("sphere")) out.sections.push_back(SphereSection(figures["sphere"]));
  if (figures.contains("brdf")) out.sections.push_back(BrdfSection(figures["brdf"]));
  if (figures.contains("validation_photos")) {
    out.sections.push_back(ValidationPhotosSection(figures["validation_photos"]));
  }
  return out;
}

WrittenReport WriteReport(const std::filesystem::path& dir, const json& report) {
  std::filesystem::create_directories(dir);
  const Report r = ReportFromJson(report);  // before writing: a bad report leaves no files
  WrittenReport written{dir / "report.json", dir / "report.html", dir / "report.txt", r.Text()};
  WriteFileAtomically(written.json, report.dump(2) + "\n");
  WriteFileAtomically(written.html, r.Html());
  WriteFileAtomically(written.text_file, written.text);
  return written;
}

}  // namespace brdfrig::evaluate
