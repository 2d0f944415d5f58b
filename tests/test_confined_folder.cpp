// The confined-folder rule (output/confined_folder.hpp): every file a command writes, replaces or
// removes in a folder it owns lies beneath that folder once resolved. Each case puts a decoy outside
// the folder and checks it untouched.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <set>
#include <string>

#include "cli_support.hpp"
#include "output/confined_folder.hpp"
#include "output/output_error.hpp"
#include "output/pending_output.hpp"

using namespace particles::output;
using particles::test::Scratch;
using particles::test::slurp;
namespace fs = std::filesystem;

namespace {

// A scratch folder with `folder/` (the confined one) and `decoy/notes.txt` beside it.
struct Decoyed : Scratch {
  fs::path folder = dir / "folder", decoy = dir / "decoy" / "notes.txt";
  Decoyed() {
    fs::create_directories(folder);
    fs::create_directories(decoy.parent_path());
    write("decoy/notes.txt", "PRECIOUS");
  }
  std::set<std::string> decoyFolder() const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(decoy.parent_path())) names.insert(e.path().filename().string());
    return names;
  }
  void decoyUntouched() const {
    CHECK(slurp(decoy) == "PRECIOUS");
    CHECK(decoyFolder() == std::set<std::string>{"notes.txt"});
  }
};

bool isLink(const fs::path& p) {
  return fs::symlink_status(p).type() == fs::file_type::symlink;
}

}  // namespace

TEST_CASE("confined folder: files are written beneath it, with the folders on their way") {
  Decoyed s;
  const ConfinedFolder folder(s.folder);
  folder.writeFile("a.txt", "one");
  folder.writeFile("sub/deeper/b.txt", "two");
  folder.writeFile("sub/../c.txt", "three");  // a `..` that stays inside
  CHECK(slurp(s.folder / "a.txt") == "one");
  CHECK(slurp(s.folder / "sub" / "deeper" / "b.txt") == "two");
  CHECK(slurp(s.folder / "c.txt") == "three");
  folder.writeFile("a.txt", "replaced");
  CHECK(slurp(s.folder / "a.txt") == "replaced");
  CHECK(folder.kindOf("sub") == EntryKind::directory);
  CHECK(folder.kindOf("sub/deeper/b.txt") == EntryKind::regular);
  CHECK(folder.kindOf("missing/x") == EntryKind::absent);
  CHECK(folder.kindOf("a.txt/x") == EntryKind::absent);
}

TEST_CASE("confined folder: a path that leaves it is refused, and nothing outside changes") {
  Decoyed s;
  const ConfinedFolder folder(s.folder);
  CHECK_THROWS_AS(folder.writeFile("../decoy/notes.txt", "x"), OutsideFolderError);
  CHECK_THROWS_AS(folder.writeFile("sub/../../decoy/new.txt", "x"), OutsideFolderError);
  CHECK_THROWS_AS(folder.writeFile(s.decoy, "x"), OutsideFolderError);  // absolute
  CHECK_THROWS_AS(folder.writeFile("", "x"), OutsideFolderError);
  CHECK_THROWS_AS(folder.remove("../decoy/notes.txt"), OutsideFolderError);
  s.decoyUntouched();
}

TEST_CASE("confined folder: links that lead outside are refused wherever they are on the path") {
  Decoyed s;
  fs::create_symlink(s.decoy, s.folder / "absolute.txt");               // absolute, to a file
  fs::create_symlink("../decoy/notes.txt", s.folder / "relative.txt");  // relative, up and out
  fs::create_symlink("../decoy/new.txt", s.folder / "dangling.txt");    // would create a file outside
  fs::create_symlink(s.decoy.parent_path(), s.folder / "outside");      // a folder on the way
  fs::create_symlink("relative.txt", s.folder / "chain.txt");           // inside, then out
  fs::create_directories(s.folder / "sub");
  fs::create_symlink("../../decoy", s.folder / "sub" / "up");  // out through a subfolder
  const ConfinedFolder folder(s.folder);
  for (const char* name : {"absolute.txt", "relative.txt", "dangling.txt", "outside/notes.txt", "outside/new.txt",
                           "chain.txt", "sub/up/notes.txt"}) {
    CAPTURE(name);
    CHECK_THROWS_AS(folder.writeFile(name, "x"), OutsideFolderError);
    CHECK_THROWS_AS(PendingOutput(folder, name), OutsideFolderError);
    CHECK_THROWS_AS(folder.kindOf(name), OutsideFolderError);
  }
  // Removing a link removes the link, never what it leads to.
  CHECK(folder.remove("absolute.txt"));
  CHECK_FALSE(fs::exists(fs::symlink_status(s.folder / "absolute.txt")));
  CHECK_THROWS_AS(folder.remove("outside/notes.txt"), OutsideFolderError);
  s.decoyUntouched();
  // The message names the file, the folder and where the link leads.
  try {
    folder.writeFile("relative.txt", "x");
  } catch (const OutsideFolderError& e) {
    const std::string what = e.what();
    CHECK(what.find("relative.txt") != std::string::npos);
    CHECK(what.find("leads outside") != std::string::npos);
  }
}

TEST_CASE("confined folder: a link that stays inside is followed, and stays a link") {
  Decoyed s;
  fs::create_directories(s.folder / "files");
  s.write("folder/files/target.txt", "old");
  fs::create_directories(s.folder / "links");
  fs::create_symlink("../files/target.txt", s.folder / "links" / "link.txt");
  fs::create_symlink("../files", s.folder / "links" / "files");
  const ConfinedFolder folder(s.folder);
  folder.writeFile("links/link.txt", "through the link");
  CHECK(slurp(s.folder / "files" / "target.txt") == "through the link");
  CHECK(isLink(s.folder / "links" / "link.txt"));
  folder.writeFile("links/files/new.txt", "through a folder link");
  CHECK(slurp(s.folder / "files" / "new.txt") == "through a folder link");
}

TEST_CASE("confined folder: what is not a regular file is not replaced") {
  Decoyed s;
  fs::create_directories(s.folder / "dir");
  REQUIRE(::mkfifo((s.folder / "fifo").c_str(), 0600) == 0);
  const ConfinedFolder folder(s.folder);
  CHECK_THROWS_AS(folder.writeFile("dir", "x"), OutputError);
  CHECK_THROWS_AS(folder.writeFile("fifo", "x"), OutputError);  // refused at once, never waited on
  CHECK(fs::is_directory(s.folder / "dir"));
  CHECK(fs::is_fifo(s.folder / "fifo"));
}

TEST_CASE("confined folder: the walk holds its folders open, so a folder moved away cannot lead out") {
  Decoyed s;
  const ConfinedFolder folder(s.folder);
  // The confined folder renamed while it is open: files still land in it, by its descriptor.
  fs::rename(s.folder, s.dir / "moved");
  folder.writeFile("x.txt", "in the moved folder");
  CHECK(slurp(s.dir / "moved" / "x.txt") == "in the moved folder");
  CHECK_FALSE(fs::exists(s.folder / "x.txt"));
  s.decoyUntouched();
}

TEST_CASE("confined folder: relativeBeneath, by names") {
  CHECK(relativeBeneath("/a/b/c.txt", "/a") == fs::path("b/c.txt"));
  CHECK(relativeBeneath("/a/b/../c.txt", "/a/") == fs::path("c.txt"));
  CHECK(relativeBeneath("/a/../b/c.txt", "/a").empty());
  CHECK(relativeBeneath("/a", "/a").empty());
  CHECK(relativeBeneath("/ab/c", "/a").empty());
}
