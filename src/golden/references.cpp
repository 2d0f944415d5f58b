// Writing references and merging report folders: see references.hpp.
#include "golden/references.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>
#include <stdexcept>

#include "golden/state_table.hpp"
#include "input/text_file.hpp"
#include "output/confined_folder.hpp"
#include "output/distinct_files.hpp"
#include "render/png_io.hpp"

namespace particles::golden {

namespace fs = std::filesystem;
using scenario::GoldenEntry;
using scenario::GoldenManifest;

namespace {

// A check of the manifest by name: whether it is a frame, and whether update may write its reference.
struct Named {
  bool frame = true;
  bool writable = true;  // not a control, not compared with another's reference
  fs::path reference;
};

std::map<std::string, Named> checksByName(const GoldenManifest& m) {
  std::map<std::string, Named> out;
  for (const GoldenEntry& e : m.frames) {
    for (const scenario::GoldenTime& t : e.times) {
      out[t.frameName] = {true, !e.expectDiffer && !e.reference, frameReference(m, t.frameName)};
    }
  }
  for (const GoldenEntry& e : m.states) out[e.stateName] = {false, true, stateReference(m, e.stateName)};
  return out;
}

std::string readWhole(const fs::path& file, std::uintmax_t maxInputMiB) {
  try {
    return input::readBinaryFile(file, maxInputMiB, input::Accept::regularOnly);
  } catch (const input::ReadError& e) {
    throw std::invalid_argument(fmt::format("{}: {}", file.string(), e.what()));
  }
}

// A kept file of a report folder, read only when it lies beneath the folder once resolved.
std::string readKept(const fs::path& folder, const std::string& kept, std::uintmax_t maxInputMiB) {
  try {
    output::ConfinedFolder(folder).kindOf(kept);
  } catch (const output::OutsideFolderError& e) {
    throw std::invalid_argument(e.what());
  }
  return readWhole(folder / kept, maxInputMiB);
}

// The file's bytes once they are known to be what a reference of this kind holds.
void checkContent(const std::string& bytes, bool frame, const std::string& label) {
  if (frame) {
    render::readPngBytes({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, label);
  } else {
    parseStateText(bytes, label);
  }
}

// Writes `bytes` as the reference when they differ from what is there; says what it did. The file
// is written from the references folder's descriptor (output/confined_folder.hpp): a link that
// leads out of it is refused where it is written, even one made after requireReferencesInPlace.
ReferenceChange writeReference(const output::ConfinedFolder& references, const fs::path& reference,
                               const std::string& bytes, const std::string& name, std::uintmax_t maxInputMiB) {
  ReferenceChange change;
  change.name = name;
  const fs::path relative = reference.lexically_relative(references.root());
  if (references.kindOf(relative) != output::EntryKind::absent) {
    std::string old;
    try {
      old = input::readBinaryFile(reference, maxInputMiB, input::Accept::regularOnly);
    } catch (const input::ReadError&) {  // unreadable: replaced
    }
    if (old == bytes) return change;
    change.kind = ReferenceChange::Kind::changed;
  } else {
    change.kind = ReferenceChange::Kind::created;
  }
  references.writeFile(relative, bytes);
  return change;
}

// The references' folder as the manifest resolves it ("." when it names none).
fs::path referencesRoot(const GoldenManifest& manifest) {
  return manifest.references.empty() ? fs::path(".") : manifest.references;
}

// A reference's name within its folder (NAME.png, NAME.csv).
fs::path referenceName(const fs::path& reference, const GoldenManifest& manifest) {
  return reference.lexically_relative(referencesRoot(manifest));
}

// The references folder, made when missing.
output::ConfinedFolder referencesFolder(const GoldenManifest& manifest) {
  return output::ConfinedFolder(referencesRoot(manifest), output::ConfinedFolder::Create::yes);
}

std::string frameChange(const FrameResult& r) {
  if (!r.numbers) return r.message;
  const FrameNumbers& n = *r.numbers;
  return fmt::format("{:.4f} % of the pixels differ by more than {} ({} of {}), largest difference {}", 100.0 * n.share,
                     n.threshold, n.differing, n.pixels, n.largest);
}

std::string stateChange(const StateResult& r) {
  if (!r.largest) return r.message;
  const StateDeviation& d = *r.largest;
  return fmt::format("largest difference {:.3g} in {} of {} at t = {} ({} → {})", d.difference, d.quantity, d.point,
                     d.time, d.expected, d.actual);
}

}  // namespace

void requireReferencesInPlace(const GoldenManifest& manifest, bool written) {
  std::error_code ec;
  if (!fs::exists(referencesRoot(manifest), ec)) return;  // nothing there yet: update makes it, check finds all missing
  const output::ConfinedFolder references(referencesRoot(manifest));
  std::vector<output::NamedFile> inputs = {{"the manifest", manifest.file}};
  for (const auto* entries : {&manifest.frames, &manifest.states}) {
    for (const GoldenEntry& e : *entries) inputs.push_back({"scenario", e.scenario});
  }
  for (const auto& [name, check] : checksByName(manifest)) {
    references.kindOf(referenceName(check.reference, manifest));  // throws OutsideFolderError
    if (written && check.writable) output::requireDistinctFiles({{"reference " + name, check.reference}}, inputs);
  }
}

UpdateOutcome writeRenderedReferences(const GoldenManifest& manifest, const fs::path& folder, const CheckRun& run,
                                      std::uintmax_t maxInputMiB) {
  const std::map<std::string, Named> named = checksByName(manifest);
  const output::ConfinedFolder references = referencesFolder(manifest);
  UpdateOutcome out;
  auto take = [&](const std::string& name, Outcome outcome, const std::string& message, const KeptFiles& files,
                  const std::string& how) {
    const Named& n = named.at(name);
    if (!n.writable) {
      out.notes.push_back(
          fmt::format("{}: a control or a check against another frame's reference: it has no "
                      "reference of its own to write",
                      name));
      return;
    }
    if (outcome == Outcome::error || files.actual.empty()) {
      out.errors.push_back(fmt::format("{}: {}", name, message));
      return;
    }
    ReferenceChange c =
        writeReference(references, n.reference, readWhole(folder / files.actual, maxInputMiB), name, maxInputMiB);
    if (c.kind == ReferenceChange::Kind::changed) c.how = how;
    out.changes.push_back(std::move(c));
  };
  for (const FrameResult& r : run.results.frames) take(r.name, r.outcome, r.message, r.files, frameChange(r));
  for (const StateResult& r : run.results.states) take(r.name, r.outcome, r.message, r.files, stateChange(r));
  return out;
}

namespace {

// What one report folder says of a check.
struct Sighting {
  fs::path folder;
  bool passed = false;
  std::string actual;  // the kept file, when it failed or was missing
  std::string how;
};

// What the folders say of the checks asked for (`names`, or all): each check's sightings, the
// checks in the order first seen, the checks refused already and the folders set aside.
struct Sightings {
  std::map<std::string, std::vector<Sighting>> seen;
  std::vector<std::string> order;
  std::vector<Refusal> refused;
  std::vector<std::string> notes;
};

Sightings readSightings(const GoldenManifest& manifest, const std::map<std::string, Named>& named,
                        const std::vector<fs::path>& folders, const std::vector<std::string>& names,
                        std::uintmax_t maxInputMiB) {
  Sightings out;
  for (const fs::path& folder : folders) {
    const GoldenResults results = readResults(folder, maxInputMiB);
    // Folders whose pixels are not the manifest's own (another raster path or tolerance), or that
    // are reports of another manifest, say nothing for or against: set aside, and said so.
    const auto overridden =
        std::find_if(results.runs.begin(), results.runs.end(), [](const RunFacts& f) { return !f.overrides.empty(); });
    if (overridden != results.runs.end()) {
      out.notes.push_back(fmt::format("ignored {}: checked with {}, not the manifest's own settings", folder.string(),
                                      overridden->overrides));
      continue;
    }
    const bool thisManifest = std::any_of(results.runs.begin(), results.runs.end(), [&](const RunFacts& f) {
      return fs::path(f.manifest).lexically_normal() == fs::path(manifest.file).lexically_normal();
    });
    if (!thisManifest) {
      out.notes.push_back(fmt::format("ignored {}: a report of {}, not {}", folder.string(),
                                      results.runs.empty() ? std::string("no manifest") : results.runs.front().manifest,
                                      manifest.file));
      continue;
    }
    auto note = [&](const std::string& name, Outcome outcome, const KeptFiles& files, const std::string& how,
                    bool control) {
      if (!names.empty() && std::find(names.begin(), names.end(), name) == names.end()) return;
      if (control) return;  // a control's frame is never a reference
      if (!named.count(name)) {
        out.refused.push_back({name, fmt::format("{} has it, the manifest no longer does", folder.string())});
        return;
      }
      if (!out.seen.count(name)) out.order.push_back(name);
      Sighting s{folder, outcome == Outcome::passed, "", how};
      if ((outcome == Outcome::failed || outcome == Outcome::missing) && !files.actual.empty()) {
        s.actual = files.actual;
      } else if (outcome != Outcome::passed) {
        s.how = "error";
      }
      out.seen[name].push_back(std::move(s));
    };
    for (const FrameResult& r : results.frames) note(r.name, r.outcome, r.files, frameChange(r), r.expectDiffer);
    for (const StateResult& r : results.states) note(r.name, r.outcome, r.files, stateChange(r), false);
  }
  return out;
}

// The actual file every folder kept of one check, the same bytes in each: its bytes and the first
// sighting holding it, or why not (a folder that passed or could not check it, files that differ,
// a file that is not a reference).
std::string agreedActual(const std::vector<Sighting>& all, const Named& n, std::uintmax_t maxInputMiB,
                         const Sighting*& first, std::string& bytes) {
  for (const Sighting& s : all) {
    if (s.actual.empty()) {
      return fmt::format("{} {} where {} failed", s.folder.string(), s.passed ? "passed" : "could not check it",
                         all.front().folder.string());
    }
    try {
      std::string these = readKept(s.folder, s.actual, maxInputMiB);
      if (!first) {
        checkContent(these, n.frame, (s.folder / s.actual).string());
        first = &s;
        bytes = std::move(these);
      } else if (these != bytes) {
        return fmt::format("{} and {} hold different actual {}s", (first->folder / first->actual).string(),
                           (s.folder / s.actual).string(), n.frame ? "frame" : "state");
      }
    } catch (const std::invalid_argument& e) {
      return e.what();
    } catch (const std::runtime_error& e) {  // a PNG that does not decode
      return e.what();
    }
  }
  return "";
}

}  // namespace

UpdateOutcome acceptReferences(const GoldenManifest& manifest, const std::vector<fs::path>& folders,
                               const std::vector<std::string>& names, std::uintmax_t maxInputMiB) {
  const std::map<std::string, Named> named = checksByName(manifest);
  for (const std::string& name : names) {
    if (!named.count(name))
      throw std::invalid_argument(fmt::format("{}: the manifest has no frame or state of that name", name));
  }
  Sightings sightings = readSightings(manifest, named, folders, names, maxInputMiB);
  UpdateOutcome out;
  out.refused = std::move(sightings.refused);
  out.notes = std::move(sightings.notes);
  std::optional<output::ConfinedFolder> references;  // made at the first reference written
  for (const std::string& name : sightings.order) {
    const bool refusedAlready =
        std::any_of(out.refused.begin(), out.refused.end(), [&](const Refusal& r) { return r.name == name; });
    if (refusedAlready) continue;
    const std::vector<Sighting>& all = sightings.seen.at(name);
    const Named& n = named.at(name);
    if (!n.writable) continue;
    const bool anyActual = std::any_of(all.begin(), all.end(), [](const Sighting& s) { return !s.actual.empty(); });
    if (!anyActual) continue;  // passed everywhere: nothing to accept
    const Sighting* first = nullptr;
    std::string bytes;
    const std::string why = agreedActual(all, n, maxInputMiB, first, bytes);
    if (!why.empty()) {
      out.refused.push_back({name, why});
      continue;
    }
    if (!references) references.emplace(referencesFolder(manifest));
    ReferenceChange c = writeReference(*references, n.reference, bytes, name, maxInputMiB);
    c.from = (first->folder / first->actual).string();
    if (c.kind == ReferenceChange::Kind::changed) c.how = first->how;
    out.changes.push_back(std::move(c));
  }
  return out;
}

GoldenResults mergeReports(const std::vector<fs::path>& folders, const fs::path& into, std::uintmax_t maxInputMiB) {
  struct Part {
    fs::path folder;
    GoldenResults results;
    int shard = 0;
  };
  std::vector<Part> parts;
  for (const fs::path& folder : folders) {
    Part p{folder, readResults(folder, maxInputMiB)};
    if (p.results.runs.size() == 1 && !p.results.runs[0].shard.empty()) {
      p.shard = std::atoi(p.results.runs[0].shard.c_str());
    }
    parts.push_back(std::move(p));
  }
  if (std::all_of(parts.begin(), parts.end(), [](const Part& p) { return p.shard > 0; })) {
    std::stable_sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.shard < b.shard; });
  }
  GoldenResults merged;
  std::map<std::string, fs::path> owner;
  auto claim = [&](const std::string& name, const fs::path& folder) {
    const auto [it, fresh] = owner.emplace(name, folder);
    if (!fresh) {
      throw std::invalid_argument(fmt::format("{} and {} both hold {}: merge the shards of one run, each once",
                                              it->second.string(), folder.string(), name));
    }
  };
  // Every kept file of every part, with the folder that holds it; the pages are the merge's own.
  std::map<std::string, fs::path> kept;
  for (std::string_view page : {kReportHtml, kJunitXml, kResultsJson}) kept.emplace(page, into);
  auto claimFile = [&](const std::string& file, const fs::path& folder) {
    if (file.empty()) return;
    const auto [it, fresh] = kept.emplace(file, folder);
    if (!fresh) {
      throw std::invalid_argument(
          it->second == into
              ? fmt::format("{} keeps a file named {}, which is the merged report's own page", folder.string(), file)
              : fmt::format("{} and {} both keep {}: one check would show the other's file", it->second.string(),
                            folder.string(), file));
    }
  };
  // Every check by name, then every kept file, before anything is copied.
  for (const Part& p : parts) {
    for (const FrameResult& r : p.results.frames) claim(r.name, p.folder);
    for (const StateResult& r : p.results.states) claim(r.name, p.folder);
  }
  for (const Part& p : parts) {
    for (const FrameResult& r : p.results.frames) {
      for (const std::string* f : {&r.files.actual, &r.files.expected, &r.files.diff}) claimFile(*f, p.folder);
    }
    for (const StateResult& r : p.results.states) {
      for (const std::string* f : {&r.files.actual, &r.files.expected, &r.files.diff}) claimFile(*f, p.folder);
    }
  }
  // A file whose path is a folder of another's ("frames/a.png" and "frames/a.png/b.png"): in
  // sorted order the folder's path comes right before the paths beneath it.
  for (auto it = kept.begin(), next = std::next(it); next != kept.end(); ++it, ++next) {
    if (next->first.starts_with(it->first + "/")) {
      throw std::invalid_argument(fmt::format("{} keeps {} and {} keeps {}: one file's path is the other's folder",
                                              it->second.string(), it->first, next->second.string(), next->first));
    }
  }
  const output::ConfinedFolder target(into);
  auto copy = [&](const fs::path& folder, const KeptFiles& files) {
    for (const std::string* f : {&files.actual, &files.expected, &files.diff}) {
      if (!f->empty()) target.writeFile(*f, readKept(folder, *f, maxInputMiB));
    }
  };
  for (Part& p : parts) {
    merged.runs.insert(merged.runs.end(), p.results.runs.begin(), p.results.runs.end());
    for (FrameResult& r : p.results.frames) {
      copy(p.folder, r.files);
      merged.frames.push_back(std::move(r));
    }
    for (StateResult& r : p.results.states) {
      copy(p.folder, r.files);
      merged.states.push_back(std::move(r));
    }
  }
  return merged;
}

}  // namespace particles::golden
