#pragma once
// Errors at the figures boundary. The command line maps FigureError to exit code 3 ("output
// failure") and CsvError to exit code 2 ("bad input"), docs/physics.md §12.

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

namespace particles::plot {

// A figure could not be drawn or written: names the path or the font file and the failing call,
// with cairo's or the system's message.
class FigureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A CSV input is malformed or unreadable. what() reads "FILE:LINE:COLUMN: message"; line and column
// count from 1, the column in bytes, pointing at the start of the offending field. A file that
// cannot be read at all has line = column = 0 and reads "FILE: message".
class CsvError : public std::runtime_error {
 public:
  CsvError(std::filesystem::path file, std::size_t line, std::size_t column, const std::string& message)
      : std::runtime_error(line > 0 ? fmt::format("{}:{}:{}: {}", file.string(), line, column, message)
                                    : fmt::format("{}: {}", file.string(), message)),
        file_(std::move(file)),
        line_(line),
        column_(column) {}
  const std::filesystem::path& file() const { return file_; }
  std::size_t line() const { return line_; }
  std::size_t column() const { return column_; }

 private:
  std::filesystem::path file_;
  std::size_t line_, column_;
};

}  // namespace particles::plot
