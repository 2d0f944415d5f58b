#include "scenario/scenario_error.hpp"

#include <fmt/format.h>

#include <utility>

namespace particles::scenario {

ScenarioError::ScenarioError(std::string file, int line, int column, std::string keyPath, std::string message,
                             std::string origin)
    : std::runtime_error([&] {
        std::string where = file;
        if (line > 0) where += fmt::format(":{}:{}", line, column);
        std::string key = keyPath;
        if (!origin.empty()) key += key.empty() ? fmt::format("({})", origin) : fmt::format(" (from {})", origin);
        return key.empty() ? fmt::format("{}: error: {}", where, message)
                           : fmt::format("{}: error: {}: {}", where, key, message);
      }()),
      file_(std::move(file)),
      line_(line),
      column_(column),
      keyPath_(std::move(keyPath)),
      message_(std::move(message)),
      origin_(std::move(origin)) {}

}  // namespace particles::scenario
