#include "support/library_names.hpp"

namespace particles::test {

std::string_view libavcodecSoname() {
  return PARTICLES_LIBAVCODEC_SONAME;
}

std::string_view osmesaSoname() {
#ifdef PARTICLES_OSMESA_SONAME
  return PARTICLES_OSMESA_SONAME;
#else
  return {};
#endif
}

}  // namespace particles::test
