#pragma once
// A public Image as the render room's, after checking its size against its bytes: what
// Image::savePng, Image::encodePng and VideoWriter::write take (internal to the API).

#include <string_view>

#include <particles/renderer.hpp>

#include "render/image.hpp"

namespace particles::api {

// ArgumentError "CALL: a WxH NOUN needs N bytes of RGBA, it has M" unless width and height are
// positive and rgba holds width × height × 4 bytes.
render::Image checkedImage(const Image& image, std::string_view call, std::string_view noun = "image");

}  // namespace particles::api
