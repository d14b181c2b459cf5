// report.json is the source of every report: it holds every figure (with its protocol) and the
// job's own sections; report.html and the text summary are generated from it, so what a person
// reads and what a script reads cannot disagree.
//
//   {"format": "brdfrig-report", "version": 1, "title": "...",
//    "sections": [{"title", "paragraphs", "tables": [{"caption", "header", "rows"}]}, ...],
//    "figures": {"preview": {...},                          (evaluate/material_preview.h)
//                "coverage": {...},                         (evaluate/coverage_report.h)
//                "brdf_plots": {...},                       (evaluate/brdf_plots.h)
//                "held_out": {...}, "sphere": {...}, "brdf": {...}, (evaluate/material_report.h)
//                "validation_photos": {...},                (evaluate/validation_photos.h)
//                "validation_photos_gltf": {...}}}          (the glTF version's, numbers only)
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "evaluate/report.h"

namespace brdfrig::evaluate {

// An empty report.json with its title.
nlohmann::json NewReportJson(const std::string& title);

// A job's own section (paragraphs, tables, images) as report.json stores it.
nlohmann::json SectionJson(const ReportSection& section);

// The report a person reads: first the material (spheres), the plan's coverage and the BRDF
// curves, then the job's sections, then one section per remaining figure group (held-out views
// by elevation with plots and images, sphere test, BRDF against the truth, validation photos).
// Throws brdfrig::Error on a report.json of another format.
Report ReportFromJson(const nlohmann::json& report);

struct WrittenReport {
  std::filesystem::path json, html, text_file;
  std::string text;
};

// Writes report.json, then report.html and report.txt generated from it (each atomically).
WrittenReport WriteReport(const std::filesystem::path& dir, const nlohmann::json& report);

}  // namespace brdfrig::evaluate
