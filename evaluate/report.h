// A self-contained HTML report (image grids, inline SVG plots, tables, images beside it) and its
// plain-text twin for the terminal. Pictures come before the tables that detail them. Reports name
// the protocol of every figure they quote.
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

// Images side by side in rows and columns (e.g. models × lights), each with a caption: what a
// person compares at a glance. The text report keeps the captions (the numbers in them).
struct ImageCell {
  std::string file;  // relative to the report; empty = a cell with only its caption
  std::string caption;
};
struct ImageGridRow {
  std::string label;
  std::vector<ImageCell> cells;
};
struct ImageGrid {
  std::string caption;
  std::vector<std::string> columns;  // one heading per column
  std::vector<ImageGridRow> rows;
};

struct ReportSection {
  std::string title;
  std::vector<std::string> paragraphs;  // plain text (escaped in HTML)
  std::vector<Table> tables;
  std::vector<std::string> svg_plots;                       // inline SVG documents
  std::vector<std::pair<std::string, std::string>> images;  // (file relative to report, caption)
  std::vector<ImageGrid> grids;  // drawn first, then the plots, the tables and the images
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
