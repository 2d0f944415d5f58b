#include "render/render_options.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace particles::render {

void validate(const RenderOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > kMaxImageSide || o.height > kMaxImageSide) {
    throw std::invalid_argument("image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                                " is out of range (1 to 16384 pixels per side)");
  }
  if (std::find(kSampleCounts.begin(), kSampleCounts.end(), o.msaa) == kSampleCounts.end()) {
    throw std::invalid_argument("msaa " + std::to_string(o.msaa) + " is not one of 1 (off), 2, 4, 8, 16");
  }
  if (!(o.particleRadius.value > 0.0)) throw std::invalid_argument("particle radius must be positive");
  if (!(o.springWidthPx > 0.0) || !(o.rodWidthPx > 0.0) || !(o.guideWidthPx > 0.0) || !(o.outlineWidthPx > 0.0)) {
    throw std::invalid_argument("line widths must be positive");
  }
  if (!(o.strainForFullColor > 0.0)) throw std::invalid_argument("strainForFullColor must be positive");
}

}  // namespace particles::render
