#include <particles/version.hpp>

namespace particles {

const char* version() noexcept { return PARTICLES_VERSION_STRING; }

}  // namespace particles
