#include "evaluate/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/atomic_file.h"

namespace brdfrig::evaluate {
namespace {

std::string Escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

// Text inside a single-quoted attribute (file names).
std::string EscapeAttribute(const std::string& text) {
  std::string out;
  for (char c : Escape(text)) out += c == '\'' ? std::string("&#39;") : std::string(1, c);
  return out;
}

}  // namespace

std::string Report::Html() const {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>" << Escape(title)
    << "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;color:#222}"
       "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:3px 8px;"
       "text-align:right}th{background:#eee}caption{text-align:left;font-weight:bold;"
       "padding:4px 0}figure{display:inline-block;margin:4px}img{max-width:340px}"
       "figcaption{font-size:12px}table.grid td{text-align:center;vertical-align:top;"
       "font-size:12px}table.grid th{text-align:left;max-width:220px}table.grid "
       "img{display:block;margin:auto}"
       ".plot{display:inline-block;vertical-align:top}</style></head><body>\n<h1>"
    << Escape(title) << "</h1>\n";
  for (const ReportSection& s : sections) {
    h << "<h2>" << Escape(s.title) << "</h2>\n";
    for (const std::string& p : s.paragraphs) h << "<p>" << Escape(p) << "</p>\n";
    for (const ImageGrid& g : s.grids) {
      h << "<table class='grid'><caption>" << Escape(g.caption) << "</caption><tr><th></th>";
      for (const std::string& c : g.columns) h << "<th>" << Escape(c) << "</th>";
      h << "</tr>\n";
      for (const ImageGridRow& row : g.rows) {
        h << "<tr><th>" << Escape(row.label) << "</th>";
        for (const ImageCell& cell : row.cells) {
          h << "<td>";
          if (!cell.file.empty()) h << "<img src='" << EscapeAttribute(cell.file) << "'>";
          h << Escape(cell.caption) << "</td>";
        }
        h << "</tr>\n";
      }
      h << "</table>\n";
    }
    for (const std::string& svg : s.svg_plots) h << "<div class='plot'>" << svg << "</div>\n";
    for (const Table& t : s.tables) {
      h << "<table><caption>" << Escape(t.caption) << "</caption><tr>";
      for (const std::string& c : t.header) h << "<th>" << Escape(c) << "</th>";
      h << "</tr>\n";
      for (const auto& row : t.rows) {
        h << "<tr>";
        for (const std::string& c : row) h << "<td>" << Escape(c) << "</td>";
        h << "</tr>\n";
      }
      h << "</table>\n";
    }
    for (const auto& [file, caption] : s.images) {
      h << "<figure><img src='" << EscapeAttribute(file) << "'><figcaption>" << Escape(caption)
        << "</figcaption></figure>\n";
    }
  }
  h << "</body></html>\n";
  return h.str();
}

std::string Report::Text() const {
  std::ostringstream out;
  out << title << "\n" << std::string(title.size(), '=') << "\n";
  for (const ReportSection& s : sections) {
    out << "\n" << s.title << "\n" << std::string(s.title.size(), '-') << "\n";
    for (const std::string& p : s.paragraphs) out << p << "\n";
    for (const ImageGrid& g : s.grids) {
      out << "\n" << g.caption << "\n";
      for (const ImageGridRow& row : g.rows) {
        out << "  " << row.label << ":";
        for (std::size_t c = 0; c < row.cells.size(); ++c) {
          out << (c ? " |" : "") << " " << (c < g.columns.size() ? g.columns[c] + " " : "")
              << row.cells[c].caption;
        }
        out << "\n";
      }
    }
    for (const Table& t : s.tables) {
      std::vector<std::size_t> width(t.header.size(), 0);
      for (std::size_t c = 0; c < t.header.size(); ++c) width[c] = t.header[c].size();
      for (const auto& row : t.rows) {
        for (std::size_t c = 0; c < row.size() && c < width.size(); ++c) {
          width[c] = std::max(width[c], row[c].size());
        }
      }
      out << "\n" << t.caption << "\n";
      auto line = [&](const std::vector<std::string>& cells) {
        for (std::size_t c = 0; c < width.size(); ++c) {
          const std::string cell = c < cells.size() ? cells[c] : "";
          out << (c ? "  " : "") << std::string(width[c] - std::min(width[c], cell.size()), ' ')
              << cell;
        }
        out << "\n";
      };
      line(t.header);
      for (const auto& row : t.rows) line(row);
    }
  }
  return out.str();
}

void Report::WriteHtml(const std::filesystem::path& dir) const {
  WriteFileAtomically(dir / "report.html", Html());
}

}  // namespace brdfrig::evaluate
