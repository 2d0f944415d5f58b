// particles::golden::check: see include/particles/golden.hpp. The golden room's checkIntoReport,
// which `particles golden check` runs too (src/app/golden_command.cpp).
#include <particles/golden.hpp>

#include <fmt/format.h>

#include <particles/errors.hpp>
#include <particles/version.hpp>

#include "api/guarded_call.hpp"
#include "input/printable_text.hpp"
#include "golden/check_report.hpp"
#include "golden/results.hpp"
#include "render/gl_backend.hpp"
#include "render/render_options.hpp"

namespace particles::golden {

namespace {

// The options as the golden room takes them; ArgumentError for a value the command line refuses.
ReportRequest requestOf(const std::string& manifest, const Options& o) {
  ReportRequest request;
  request.manifestFile = manifest;
  request.folder = o.output;
  request.folderName = "output";
  request.program = fmt::format("particles {}", version());
  request.check.manifestGiven = manifest;
  request.check.only = o.only;
  if (o.shard) request.check.shard = std::pair{o.shard->index, o.shard->count};  // runCheck checks the range
  if (particles::name(o.gl).empty()) throw ArgumentError("golden::check: gl is not a GlBackend");
  request.check.gl = render::GlRequest{o.gl, o.gpu};
  render::validate(request.check.gl);
  if (o.raster) {
    if (particles::name(*o.raster).empty()) throw ArgumentError("golden::check: raster is not a Raster");
    request.check.overrides.raster = *o.raster;
  }
  if (o.threshold && (*o.threshold < 0 || *o.threshold > 255)) {
    throw ArgumentError(fmt::format("golden::check: threshold must be 0 to 255, got {}", *o.threshold));
  }
  if (o.maxShare && !(*o.maxShare >= 0.0 && *o.maxShare <= 1.0)) {
    throw ArgumentError(fmt::format("golden::check: maxShare must be 0 to 1, got {}", *o.maxShare));
  }
  if (o.jobs < 0 || o.jobs > kMaxJobs) {
    throw ArgumentError(fmt::format("golden::check: jobs must be 0 (automatic) to {}, got {}", kMaxJobs, o.jobs));
  }
  request.check.overrides.threshold = o.threshold;
  request.check.overrides.maxShare = o.maxShare;
  request.check.jobs = o.jobs > 0 ? o.jobs : defaultJobs();
  request.check.progress = o.progress;
  return request;
}

FrameCheck frameCheckOf(const FrameResult& f) {
  FrameCheck out;
  out.name = f.name;
  out.scenario = f.scenario;
  out.time = f.time;
  out.control = f.expectDiffer;
  out.outcome = f.outcome;
  out.message = f.message;
  if (f.numbers) {
    out.differing = f.numbers->differing;
    out.pixels = f.numbers->pixels;
    out.largest = f.numbers->largest;
  }
  out.actual = f.files.actual;
  out.expected = f.files.expected;
  out.diff = f.files.diff;
  out.reproduce = f.reproduce;
  return out;
}

StateCheck stateCheckOf(const StateResult& s) {
  StateCheck out;
  out.name = s.name;
  out.scenario = s.scenario;
  out.times = s.times;
  out.outcome = s.outcome;
  out.message = s.message;
  out.values = s.values;
  const std::optional<StateDeviation>& shown = s.firstBeyond ? s.firstBeyond : s.largest;
  if (shown) {
    out.point = shown->point;
    out.quantity = shown->quantity;
    out.expected = shown->expected;
    out.actual = shown->actual;
    out.difference = shown->difference;
    out.tolerance = shown->tolerance;
  }
  out.reproduce = s.reproduce;
  return out;
}

}  // namespace

Report check(const std::string& manifest, const Options& options) {
  return api::guardedCall("golden::check", [&] {
    const ReportRequest request = requestOf(manifest, options);
    const CheckRun run = checkIntoReport(loadManifest(manifest, request.check.maxInputMiB), request);
    Report result;
    for (const FrameResult& f : run.results.frames) result.frames.push_back(frameCheckOf(f));
    for (const StateResult& s : run.results.states) result.states.push_back(stateCheckOf(s));
    const GoldenResults::Counts counts = run.results.counts();
    result.passed = counts.passed;
    result.failed = counts.failed;
    result.missing = counts.missing;
    result.errors = counts.error;
    result.badReference = run.badReference;
    result.html = (request.folder / kReportHtml).string();
    result.summary = summaryLine(run.results, request.folder);
    return result;
  });
}

}  // namespace particles::golden
