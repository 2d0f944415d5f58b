#pragma once
// The one error of the scenario room: a scenario file, a --set or --limit option or a sweep file
// that cannot be used, with where (file, line, column, key path, option) and why.

#include <stdexcept>
#include <string>

namespace particles::scenario {

class ScenarioError : public std::runtime_error {
 public:
  // line, column: 1-based; 0 when the error has no position (an unreadable file, a --set value).
  // origin: the command-line option the offending value came from, or empty.
  ScenarioError(std::string file, int line, int column, std::string keyPath, std::string message,
                std::string origin = {});
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int column() const { return column_; }
  const std::string& keyPath() const { return keyPath_; }
  const std::string& message() const { return message_; }
  const std::string& origin() const { return origin_; }

 private:
  std::string file_;
  int line_, column_;
  std::string keyPath_, message_, origin_;
};

}  // namespace particles::scenario
