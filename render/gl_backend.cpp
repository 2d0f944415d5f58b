#include "render/gl_backend.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "core/name_table.hpp"

namespace particles::render {

namespace {

constexpr NameTableRow<GlBackend> kNames[] = {
    {GlBackend::automatic, "auto"}, {GlBackend::egl, "egl"}, {GlBackend::osmesa, "osmesa"}};

}  // namespace

std::string_view glBackendName(GlBackend backend) {
  return nameOf(kNames, backend, "?");
}

std::optional<GlBackend> glBackendFromName(std::string_view name) {
  return valueNamed(kNames, name);
}

std::vector<std::string> glBackendNames() {
  std::vector<std::string> names;
  for (const auto& [b, name] : kNames) names.emplace_back(name);
  return names;
}

bool glBackendBuilt(GlBackend backend) {
  switch (backend) {
    case GlBackend::egl: return PARTICLES_WITH_EGL;
    case GlBackend::osmesa: return PARTICLES_WITH_OSMESA;
    case GlBackend::automatic: return true;
  }
  return false;
}

std::string glBuildDescription() {
  if (PARTICLES_WITH_EGL && PARTICLES_WITH_OSMESA) return "EGL and OSMesa";
  if (PARTICLES_WITH_EGL) return "EGL only (built with -DPARTICLES_WITH_OSMESA=OFF)";
  return "OSMesa only (built with -DPARTICLES_WITH_EGL=OFF)";
}

void validate(const GlRequest& request) {
  if (!glBackendBuilt(request.backend)) {
    throw std::invalid_argument(fmt::format("this particles has no {} backend: its GL is {}",
                                            request.backend == GlBackend::egl ? "EGL" : "OSMesa",
                                            glBuildDescription()));
  }
  if (request.gpu && request.backend == GlBackend::osmesa) {
    throw std::invalid_argument("a GPU needs EGL: OSMesa draws on the CPU only");
  }
  if (request.gpu && !glBackendBuilt(GlBackend::egl)) {
    throw std::invalid_argument(
        fmt::format("a GPU needs EGL, and this particles has none: its GL is {}", glBuildDescription()));
  }
  if (request.threads < 0) throw std::invalid_argument(fmt::format("{} rasteriser threads", request.threads));
}

std::string describe(const GlInfo& info) {
  if (!info.made) return "none (the cpu raster)";
  std::string text =
      fmt::format("{}, {}: {}, OpenGL {}", glBackendName(info.backend), info.device, info.renderer, info.version);
  if (!info.fallback.empty()) text += fmt::format(" (EGL: {})", info.fallback);
  return text;
}

}  // namespace particles::render
