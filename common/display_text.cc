#include "common/display_text.h"

#include <cstdio>

namespace brdfrig {

namespace {

bool IsControl(char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }

std::string HexEscape(char c) {
  char escaped[8];
  std::snprintf(escaped, sizeof escaped, "\\x%02x", static_cast<unsigned char>(c));
  return escaped;
}

}  // namespace

std::string DisplayPath(const std::string& path) {
  bool plain = true;
  for (char c : path) plain = plain && !IsControl(c);
  if (plain) return path;
  std::string quoted = "$'";
  for (char c : path) {
    if (c == '\n') {
      quoted += "\\n";
    } else if (c == '\t') {
      quoted += "\\t";
    } else if (c == '\\' || c == '\'') {
      quoted += std::string("\\") + c;
    } else if (IsControl(c)) {
      quoted += HexEscape(c);
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

std::string OneLine(const std::string& text) {
  std::string line;
  for (char c : text) {
    if (c == '\n') {
      line += "\\n";
    } else if (IsControl(c)) {
      line += HexEscape(c);
    } else {
      line += c;
    }
  }
  return line;
}

}  // namespace brdfrig
