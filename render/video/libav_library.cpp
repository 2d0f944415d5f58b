#include "render/video/libav_library.hpp"

#include <fmt/format.h>

#include <dlfcn.h>

#include <mutex>
#include <string>
#include <type_traits>

#include "render/errors.hpp"

namespace particles::render::libav {

namespace {

// The SONAMEs the build linked against (CMakeLists.txt reads them from the libraries pkg-config
// found): the same ABI as the headers the pointers' types come from.
struct LibraryName {
  const char* avutil = PARTICLES_LIBAVUTIL_SONAME;
  const char* avcodec = PARTICLES_LIBAVCODEC_SONAME;
  const char* avformat = PARTICLES_LIBAVFORMAT_SONAME;
  const char* avfilter = PARTICLES_LIBAVFILTER_SONAME;
};

// Debian's package for a SONAME: libavcodec.so.59 is in libavcodec59.
std::string debianPackage(const std::string& soname) {
  const std::size_t so = soname.find(".so.");
  return so == std::string::npos ? soname : soname.substr(0, so) + soname.substr(so + 4);
}

std::string debianPackages() {
  const LibraryName names;
  return fmt::format("{} {} {} {}", debianPackage(names.avutil), debianPackage(names.avcodec),
                     debianPackage(names.avformat), debianPackage(names.avfilter));
}

// Guards the log level and whether the libraries are open, so that a level set while they are
// being opened is not lost.
std::mutex& logLevelMutex() {
  static std::mutex mutex;
  return mutex;
}
int requestedLogLevel = AV_LOG_INFO;  // libav's own default
bool librariesOpen = false;

struct Library {
  Functions functions;
  std::string error;  // why the libraries could not be opened; empty when they were
};

Library openLibraries() {
  Library library;
  const LibraryName names;
  struct Handles {
    void* avutil = nullptr;
    void* avcodec = nullptr;
    void* avformat = nullptr;
    void* avfilter = nullptr;
  } handles;
  // Each before those that depend on it, so that a failure names the first library missing.
  for (auto [handle, soname] :
       {std::pair{&handles.avutil, names.avutil}, std::pair{&handles.avcodec, names.avcodec},
        std::pair{&handles.avformat, names.avformat}, std::pair{&handles.avfilter, names.avfilter}}) {
    *handle = ::dlopen(soname, RTLD_NOW | RTLD_LOCAL);
    if (!*handle) {
      const char* why = ::dlerror();
      library.error = fmt::format(
          "FFmpeg's library {} could not be loaded ({}): MP4, WebM and GIF need FFmpeg's libraries (Debian: {}); "
          "PNG frames do not",
          soname, why ? why : "no reason given", debianPackages());
      return library;
    }
  }
  std::string missing;
  const auto find = [&](auto& function, void* handle, const char* soname, const char* name) {
    function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(::dlsym(handle, name));
    if (!function) missing += fmt::format("{}{} (in {})", missing.empty() ? "" : ", ", name, soname);
  };
#define PARTICLES_LIBAV_FIND(library_, name) find(library.functions.name, handles.library_, names.library_, #name);
  PARTICLES_LIBAV_FUNCTIONS(PARTICLES_LIBAV_FIND)
#undef PARTICLES_LIBAV_FIND
  if (!missing.empty()) library.error = fmt::format("FFmpeg's libraries lack {}", missing);
  return library;
}

const Library& opening() {
  static const Library library = [] {
    Library result = openLibraries();
    if (result.error.empty()) {
      const std::lock_guard lock(logLevelMutex());
      result.functions.av_log_set_level(requestedLogLevel);
      librariesOpen = true;
    }
    return result;
  }();
  return library;
}

}  // namespace

const Functions& ffmpeg() {
  const Library& library = opening();
  if (!library.error.empty()) throw OutputError(library.error);
  return library.functions;
}

void setLogLevel(int level) {
  const std::lock_guard lock(logLevelMutex());
  requestedLogLevel = level;
  if (librariesOpen) opening().functions.av_log_set_level(level);
}

}  // namespace particles::render::libav
