// User-facing errors: bad input files, bad options, hardware faults. Code invariants use assert;
// everything a person can fix is one of these, with a message that says what and where.
#pragma once

#include <stdexcept>
#include <string>

namespace brdfrig {

// Base of every error a user can act on. what() is the full message.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An error located in a user's file: the message starts with "file:line:column: ".
class FileError : public Error {
 public:
  FileError(const std::string& file, int line, int column, const std::string& message);
  // For files without a line structure (binary files, whole-file problems).
  FileError(const std::string& file, const std::string& message);

  const std::string& file() const { return file_; }
  int line() const { return line_; }      // 1-based; 0 when unknown
  int column() const { return column_; }  // 1-based; 0 when unknown

 private:
  std::string file_;
  int line_ = 0;
  int column_ = 0;
};

// An output could not be written (a full disk, a file where a directory goes): an error of the
// whole run, never a property of the data to skip past like a bad photo.
class OutputError : public Error {
 public:
  using Error::Error;
};

// An options struct failed its Validate(): names the field and the rule it broke.
class OptionsError : public Error {
 public:
  using Error::Error;
};

}  // namespace brdfrig
