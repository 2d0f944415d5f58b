// The rule: see distinct_files.hpp.
#include "output/distinct_files.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <system_error>

#include "output/output_error.hpp"
#include "output/pending_output.hpp"

namespace particles::output {

namespace fs = std::filesystem;

namespace {

// What a path names: a file that exists (its device and inode), or, for one that does not, the
// name it would be created under.
struct Identity {
  bool exists = false;
  bool characterDevice = false;
  dev_t device = 0;
  ino_t inode = 0;
  fs::path name;
};

Identity identify(const fs::path& path) {
  Identity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {  // stat, not lstat: every link on the way followed
    id.exists = true;
    id.characterDevice = S_ISCHR(st.st_mode);
    id.device = st.st_dev;
    id.inode = st.st_ino;
    return id;
  }
  fs::path target = path;
  try {
    target = followLinks(path);
  } catch (const OutputError&) {
    // A loop of links: named as given here; writing it fails with its own message.
  }
  if (!target.has_filename() && target.has_parent_path()) target = target.parent_path();  // "frames/"
  // Not lexically_normal first: "link/.." is the folder above the link's target, which only the
  // filesystem knows; weakly_canonical resolves the part that exists and then normalises the rest.
  std::error_code ec;
  id.name = fs::weakly_canonical(fs::absolute(target, ec), ec);
  if (ec) id.name = fs::absolute(target, ec).lexically_normal();
  return id;
}

bool same(const Identity& a, const Identity& b) {
  if (a.exists != b.exists) return false;
  if (!a.exists) return a.name == b.name;
  if (a.characterDevice) return false;  // nothing in it to overwrite (see the header)
  return a.device == b.device && a.inode == b.inode;
}

// Whether `inner` is `folder` or lies beneath it, both named by their canonical paths (the part
// that exists resolved through its links, the rest made normal).
bool beneath(const fs::path& folder, const fs::path& inner) {
  std::error_code ec;
  const fs::path out = fs::weakly_canonical(fs::absolute(folder, ec), ec);
  const fs::path in = fs::weakly_canonical(fs::absolute(inner, ec), ec);
  const fs::path relative = in.lexically_relative(out);
  return in == out || (!relative.empty() && *relative.begin() != "..");
}

}  // namespace

bool sameFile(const fs::path& a, const fs::path& b) {
  return same(identify(a), identify(b));
}

void requireDistinctFiles(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
  struct Identified {
    const NamedFile* file;
    Identity id;
  };
  auto identifyAll = [](const std::vector<NamedFile>& files) {
    std::vector<Identified> out;
    for (const NamedFile& f : files) {
      if (!f.path.empty()) out.push_back({&f, identify(f.path)});
    }
    return out;
  };
  const std::vector<Identified> outs = identifyAll(outputs), ins = identifyAll(inputs);
  auto refuse = [](const NamedFile& output, const NamedFile& other, const char* what) {
    throw SameFileError(fmt::format("{} '{}' and {} '{}' name the same file; an output never replaces {}", output.role,
                                    output.path.string(), other.role, other.path.string(), what));
  };
  for (size_t i = 0; i < outs.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (same(outs[j].id, outs[i].id)) refuse(*outs[j].file, *outs[i].file, "another output");
    }
    for (const Identified& in : ins) {
      if (same(outs[i].id, in.id)) refuse(*outs[i].file, *in.file, "an input");
      if (outs[i].file->wholeFolder && beneath(outs[i].file->path, in.file->path)) {
        throw SameFileError(
            fmt::format("{} '{}' is a folder replaced whole, and {} '{}' is in it; an output never "
                        "replaces an input",
                        outs[i].file->role, outs[i].file->path.string(), in.file->role, in.file->path.string()));
      }
    }
  }
}

}  // namespace particles::output
