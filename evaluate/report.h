// A self-contained HTML report (tables, inline SVG plots, images beside it) and its plain-text
// twin for the terminal. Reports name the protocol of every figure they quote.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "common/format.h"

namespace brdfrig::evaluate {

struct Table {
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

struct ReportSection {
  std::string title;
  std::vector<std::string> paragraphs;  // plain text (escaped in HTML)
  std::vector<Table> tables;
  std::vector<std::string> svg_plots;                       // inline SVG documents
  std::vector<std::pair<std::string, std::string>> images;  // (file relative to report, caption)
};

struct Report {
  std::string title;
  std::vector<ReportSection> sections;

  std::string Html() const;
  std::string Text() const;  // tables as aligned text, plots and images omitted
  // Writes report.html (atomically) into `dir`.
  void WriteHtml(const std::filesystem::path& dir) const;
};

}  // namespace brdfrig::evaluate
