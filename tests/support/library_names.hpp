#pragma once
// The SONAMEs this build opens with dlopen (CMakeLists.txt reads them from the libraries it found):
// the tests put an unloadable file of that name first on the loader's path. Kept out of the test
// files, in particles_test_support, so that the test files compile to the same objects in build
// trees that differ only in their GL backends (build/ and build-egl/), which then share them
// through ccache.

#include <string_view>

namespace particles::test {

// libavcodec's SONAME, "libavcodec.so.59" on Debian 12.
std::string_view libavcodecSoname();

// OSMesa's SONAME, "libOSMesa.so.8"; empty where the build has no OSMesa backend.
std::string_view osmesaSoname();

}  // namespace particles::test
