#pragma once
// Owning pointers for cairo objects, and the check of a cairo call's status (internal to plot/).

#include <cairo.h>

#include <memory>
#include <string>

#include "plot/errors.hpp"

namespace particles::plot {

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* cr) const { cairo_destroy(cr); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;

// Throws FigureError("WHAT: CALL: cairo's words") unless STATUS is success.
inline void checkCairo(cairo_status_t status, const char* what, const char* call) {
  if (status != CAIRO_STATUS_SUCCESS) {
    throw FigureError(std::string(what) + ": " + call + ": " + cairo_status_to_string(status));
  }
}

}  // namespace particles::plot
