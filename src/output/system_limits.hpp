#pragma once
// What the output room's path checks share about the system they run on (internal to output/).

#include <cstring>
#include <string>

namespace particles::output {

// Linux's own limit (MAXSYMLINKS) on links followed while resolving one path.
inline constexpr int kMaxLinkHops = 40;

// errno's words, for messages.
inline std::string errnoText(int error) {
  return std::strerror(error);
}

}  // namespace particles::output
