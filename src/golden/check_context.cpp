// What a run's checks share: see check_context.hpp.
#include "golden/check_context.hpp"

#include <fmt/format.h>

#include <utility>
#include <vector>

#include "input/text_file.hpp"
#include "output/output_file.hpp"

namespace particles::golden {

namespace fs = std::filesystem;

CheckContext::CheckContext(const scenario::GoldenManifest& manifest, fs::path folder, const CheckOptions& options,
                           long checks)
    : manifest_(manifest), folder_(std::move(folder)), options_(options), checks_(checks) {}

void CheckContext::done(const std::string& name) {
  std::lock_guard lock(mutex_);
  ++done_;
  if (options_.progress) options_.progress(done_, checks_, name);
}

void CheckContext::noteGl(const render::GlInfo& info) {
  std::lock_guard lock(mutex_);
  if (gl_.empty()) gl_ = render::describe(info);
}

std::string shownPath(const fs::path& path) {
  return path.lexically_normal().string();
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string readReference(const fs::path& file, std::uintmax_t maxInputMiB) {
  try {
    return input::readBinaryFile(file, maxInputMiB, input::Accept::regularOnly);
  } catch (const input::ReadError& e) {
    throw ReferenceError(fmt::format("reference {}: {}", shownPath(file), e.what()));
  }
}

bool referenceAbsent(const fs::path& file) {
  std::error_code ec;
  return fs::symlink_status(file, ec).type() == fs::file_type::not_found;
}

void writeText(const fs::path& file, const std::string& text) {
  output::OutputFile out(file);
  out.write(text);
  out.commit();
}

namespace {

// The entry's `set:` as --set overrides, each named by where the manifest writes it.
std::vector<scenario::Override> overridesOf(const scenario::GoldenManifest& manifest,
                                            const scenario::GoldenEntry& entry) {
  std::vector<scenario::Override> out;
  for (size_t i = 0; i < entry.sets.size(); ++i) {
    const scenario::GoldenPosition& at = entry.setsAt[i];
    out.push_back(
        {entry.sets[i].first, entry.sets[i].second, fmt::format("{}:{}:{}, set", manifest.file, at.line, at.column)});
  }
  return out;
}

}  // namespace

EntrySimulation::EntrySimulation(const scenario::GoldenManifest& manifest, const scenario::GoldenEntry& entry,
                                 std::uintmax_t maxInputMiB)
    : scenario_(scenario::loadScenarioFile(entry.scenario, overridesOf(manifest, entry), maxInputMiB)),
      stepper_(scenario_.system, scenario_.simulation.integrator, scenario_.simulation.dt) {}

std::string EntrySimulation::unreachable(const scenario::GoldenTime& time) const {
  if (time.seconds > scenario_.simulation.duration + 1e-9) {
    return fmt::format("t = {} s is after the scenario's duration, {} s", time.text, scenario_.simulation.duration);
  }
  return {};
}

void EntrySimulation::advanceTo(const scenario::GoldenTime& time, render::StyledRun* styled) {
  if (const std::string why = unreachable(time); !why.empty()) throw std::invalid_argument(why);
  if (styled) {
    styled->advanceTo(stepper_, scenario_.system, time.seconds);
  } else if (time.seconds > scenario_.system.time()) {
    stepper_.advanceTo(time.seconds);
  }
}

}  // namespace particles::golden
