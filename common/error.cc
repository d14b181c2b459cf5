#include "common/error.h"

namespace brdfrig {
namespace {

std::string Located(const std::string& file, int line, int column, const std::string& message) {
  std::string where = file;
  if (line > 0) where += ":" + std::to_string(line);
  if (column > 0) where += ":" + std::to_string(column);
  return where + ": " + message;
}

}  // namespace

FileError::FileError(const std::string& file, int line, int column, const std::string& message)
    : Error(Located(file, line, column, message)), file_(file), line_(line), column_(column) {}

FileError::FileError(const std::string& file, const std::string& message)
    : FileError(file, 0, 0, message) {}

}  // namespace brdfrig
