// The commands that reproduce a result: see reproduce_commands.hpp.
#include "golden/reproduce_commands.hpp"

#include <fmt/format.h>

#include "golden/check_context.hpp"
#include "output/shell_words.hpp"

namespace particles::golden {

using output::shellCommand;

namespace {

void append(std::vector<std::string>& words, const std::vector<std::string>& more) {
  words.insert(words.end(), more.begin(), more.end());
}

}  // namespace

std::vector<std::string> glWords(const render::GlRequest& gl) {
  std::vector<std::string> words;
  if (gl.backend != render::GlBackend::automatic) words = {"--gl", std::string(render::glBackendName(gl.backend))};
  if (gl.gpu) words.push_back("--gpu");
  return words;
}

std::string renderCommand(const CheckOptions& options, const scenario::GoldenEntry& entry, const std::string& name,
                          const std::string& time, const render::RenderOptions& look) {
  std::vector<std::string> words = {options.program, "render", shownPath(entry.scenario), "-o", name + ".png",
                                    "--at",          time};
  append(words, render::lookWords(look));
  for (const auto& [path, value] : entry.sets) append(words, {"--set", path + "=" + value});
  append(words, glWords(options.gl));
  return shellCommand(words);
}

std::string compareCommand(const CheckOptions& options, const std::string& reference, const std::string& name,
                           const render::CompareTolerance& tolerance) {
  return shellCommand({options.program, "compare", reference, name + ".png", "--threshold",
                       fmt::format("{}", tolerance.threshold), "--max-share", fmt::format("{}", tolerance.maxShare),
                       "--diff", name + ".diff.png"});
}

std::string checkCommand(const CheckOptions& options, const std::string& name) {
  std::vector<std::string> words = {options.program, "golden", "check", options.manifestGiven, "--only", name};
  append(words, options.overrides.args());
  append(words, glWords(options.gl));
  return shellCommand(words);
}

std::string noReferenceYet(const CheckOptions& options, const std::string& reference) {
  return fmt::format("no reference {} yet: create it with {}", reference,
                     shellCommand({options.program, "golden", "update", options.manifestGiven, "--missing"}));
}

std::vector<std::string> CheckOverrides::args() const {
  std::vector<std::string> words;
  if (raster) append(words, {"--raster", std::string(render::rasterNameOf(*raster))});
  if (threshold) append(words, {"--threshold", fmt::format("{}", *threshold)});
  if (maxShare) append(words, {"--max-share", fmt::format("{}", *maxShare)});
  return words;
}

std::string CheckOverrides::text() const {
  return fmt::format("{}", fmt::join(args(), " "));
}

}  // namespace particles::golden
