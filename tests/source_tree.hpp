#pragma once
// Where the tests find the checkout's files: CMake passes its folder as PARTICLES_SOURCE_DIR. One
// definition for every test file, since the test files are compiled in batches (CMakeLists.txt):
// two files' own copies would clash in one batch.

#include <filesystem>
#include <string>

namespace particles::test {

inline const std::string kSource = PARTICLES_SOURCE_DIR;
inline const std::filesystem::path kScenarios = std::filesystem::path(PARTICLES_SOURCE_DIR) / "scenarios";

}  // namespace particles::test
