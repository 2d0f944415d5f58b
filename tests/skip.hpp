#pragma once
// A test that cannot run in this build or on this machine (a GL backend left out, no GPU, a
// sanitizer's address space) says so instead of passing in silence. doctest decides skips only
// before a test runs, so skipTest prints "SKIPPED: <reason>", which CTest reports as a skip
// (SKIP_REGULAR_EXPRESSION on the tests doctest_discover_tests adds, CMakeLists.txt), and appends
// the reason to skipped-tests.txt beside the test program, which scripts/test prints after the
// tests, as it does for tests/sweep/slurm_test.sh. The caller returns right after:
//   if (!glBackendBuilt(GlBackend::egl)) return skipTest("this particles has no EGL backend");

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <source_location>
#include <string>
#include <string_view>

namespace particles::test {

inline void skipTest(std::string_view reason, std::source_location where = std::source_location::current()) {
  DOCTEST_ADD_MESSAGE_AT(where.file_name(), int(where.line()), "SKIPPED: " << reason);
  const std::filesystem::path log = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "skipped-tests.txt";
  std::ofstream(log, std::ios::app) << std::filesystem::path(where.file_name()).filename().string() << ":"
                                    << where.line() << " skipped: " << reason << "\n";
}

}  // namespace particles::test
