#include "plot/font.hpp"

#include <cairo-ft.h>
#include <ft2build.h>
#include FT_FREETYPE_H

#include <dlfcn.h>

#include <memory>
#include <string>
#include <system_error>

#include "plot/errors.hpp"
#include "plot/figure.hpp"

namespace particles::plot {

namespace {

// The FreeType objects behind a cairo face. A FreeType library is made per face so no FT_Library
// is shared between threads, and its lifetime is the face's: cairo documents that the FT_Face must
// outlive the cairo face, which may live on in cairo's font cache after we destroy our reference,
// so both are freed from the face's user-data destructor.
struct FreeTypeFace {
  FT_Library library = nullptr;
  FT_Face face = nullptr;
  ~FreeTypeFace() {
    if (face) FT_Done_Face(face);
    if (library) FT_Done_FreeType(library);
  }
};

const cairo_user_data_key_t kFreeTypeFaceKey{};

void destroyFreeTypeFace(void* p) {
  delete static_cast<FreeTypeFace*>(p);
}

std::string freeTypeMessage(FT_Error error) {
  const char* s = FT_Error_String(error);  // null unless FreeType was built with error strings
  return s ? std::string(s) : "FreeType error " + std::to_string(error);
}

// The folder of the file this code was loaded from: the program, libparticles.so or the Python
// module, whichever holds plot/ (each links it in). For the program, glibc names the file as it was
// started (argv[0], perhaps relative or found on PATH): the kernel's /proc/self/exe says where it is.
std::filesystem::path loadedFromFolder() {
  Dl_info info{};
  static const int kAnchor = 0;
  std::filesystem::path file = "/proc/self/exe";
  if (::dladdr(&kAnchor, &info) != 0 && info.dli_fname != nullptr && info.dli_fname[0] == '/') {
    file = info.dli_fname;
  }
  std::error_code ec;
  file = std::filesystem::canonical(file, ec);
  return ec ? std::filesystem::path() : file.parent_path();
}

}  // namespace

const std::filesystem::path& defaultFontFile() {
  static const std::filesystem::path file = [] {
    const std::filesystem::path folder = loadedFromFolder();
    if (!folder.empty()) {
      for (const char* bundled : kBundledFontFolders) {
        std::error_code ec;
        const auto candidate = folder / bundled / kDejaVuSans.filename();
        if (std::filesystem::is_regular_file(candidate, ec)) return candidate.lexically_normal();
      }
    }
    return kDejaVuSans;
  }();
  return file;
}

FontFace::FontFace(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw FigureError("font file " + file.string() +
                      " not found: figures need DejaVu Sans (Debian package fonts-dejavu-core, see scripts/deps)");
  }
  auto ft = std::make_unique<FreeTypeFace>();
  if (FT_Error e = FT_Init_FreeType(&ft->library)) {
    throw FigureError("FT_Init_FreeType failed: " + freeTypeMessage(e));
  }
  if (FT_Error e = FT_New_Face(ft->library, file.c_str(), 0, &ft->face)) {
    throw FigureError("cannot load font file " + file.string() + ": FT_New_Face: " + freeTypeMessage(e));
  }
  face_ = cairo_ft_font_face_create_for_ft_face(ft->face, 0);
  cairo_status_t status = cairo_font_face_status(face_);
  if (status == CAIRO_STATUS_SUCCESS) {
    status = cairo_font_face_set_user_data(face_, &kFreeTypeFaceKey, ft.get(), destroyFreeTypeFace);
  }
  if (status != CAIRO_STATUS_SUCCESS) {
    cairo_font_face_destroy(face_);
    face_ = nullptr;
    throw FigureError("cannot use font file " + file.string() +
                      ": cairo_ft_font_face_create_for_ft_face: " + cairo_status_to_string(status));
  }
  ft.release();  // now owned by the cairo face
}

FontFace::~FontFace() {
  cairo_font_face_destroy(face_);
}

}  // namespace particles::plot
