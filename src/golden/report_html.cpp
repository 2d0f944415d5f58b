// report.html: see report_html.hpp.
#include "golden/report_html.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <iterator>

#include "golden/report_text.hpp"

namespace particles::golden::report {

namespace {

// `[hidden]` wins over the widgets' own display, so that they stay hidden without JavaScript.
constexpr std::string_view kStyle = R"css(
:root { color-scheme: light; }
body { font: 14px/1.45 system-ui, sans-serif; margin: 1.5em; color: #1d1d1f; background: #fafafa; }
h1 { font-size: 1.5em; margin: 0 0 .4em; }
h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 1px solid #ccc; }
h3 { font-size: 1.05em; margin: .2em 0 .5em; }
[hidden] { display: none !important; }
table { border-collapse: collapse; margin: .4em 0; }
th, td { padding: 2px 12px 2px 0; text-align: left; vertical-align: top; }
table.list th, table.list td { border-bottom: 1px solid #e4e4e4; }
td.n { text-align: right; font-variant-numeric: tabular-nums; }
.none { color: #999; }
.ok { color: #2e7d32; } .bad { color: #c62828; }
section.result { background: #fff; border: 1px solid #ddd; border-left: 6px solid #c62828; margin: 1em 0; padding: .6em 1em; }
section.missing { border-left-color: #ef6c00; } section.error { border-left-color: #6a1b9a; }
.badge { display: inline-block; padding: 0 .5em; border-radius: 3px; color: #fff; font-size: .85em; }
.badge.failed { background: #c62828; } .badge.missing { background: #ef6c00; }
.badge.error { background: #6a1b9a; } .badge.passed { background: #2e7d32; }
.control { display: inline-block; padding: 0 .4em; border: 1px dashed #777; border-radius: 3px; font-size: .85em; color: #444; }
.message { white-space: pre-wrap; font-weight: 600; }
.pictures, .compare { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; margin: .6em 0; }
figure { margin: 0; }
figcaption { font-size: .9em; color: #555; max-width: 40em; }
img.frame { display: block; box-sizing: border-box; min-width: 192px; max-width: 100%; height: auto;
  border: 1px solid #999; image-rendering: pixelated; background: #fff; }
.stage { position: relative; display: inline-block; line-height: 0; }
.stage img.over { position: absolute; left: 0; top: 0; width: 100%; height: 100%; min-width: 0; }
.slider input { display: block; width: 100%; margin: .3em 0; }
.blink img { cursor: pointer; }
button { font: inherit; margin-top: .3em; }
code, pre { font: 12.5px ui-monospace, monospace; }
pre { background: #f3f3f3; padding: .4em .6em; overflow-x: auto; white-space: pre-wrap; overflow-wrap: anywhere; }
)css";

// The slider and the blink comparison of each `.compare` widget, which stays hidden until this runs.
constexpr std::string_view kScript = R"js(
"use strict";
document.querySelectorAll(".compare").forEach(function (widget) {
  var range = widget.querySelector(".slider input");
  var over = widget.querySelector(".slider img.over");
  function reveal() { over.style.clipPath = "inset(0 " + (100 - Number(range.value)) + "% 0 0)"; }
  range.addEventListener("input", reveal);
  reveal();

  var pictures = [{ src: widget.dataset.expected, name: "expected" }, { src: widget.dataset.actual, name: "actual" }];
  var picture = widget.querySelector(".blink img");
  var shown = widget.querySelector(".blink .shown");
  var button = widget.querySelector(".blink button");
  var index = 0, timer = null;
  function flip() {
    index = 1 - index;
    picture.src = pictures[index].src;
    picture.alt = pictures[index].name;
    shown.textContent = pictures[index].name;
  }
  picture.addEventListener("click", flip);
  button.addEventListener("click", function () {
    if (timer === null) {
      flip();
      timer = setInterval(flip, 500);
      button.textContent = "Stop blinking";
    } else {
      clearInterval(timer);
      timer = null;
      button.textContent = "Blink every 0.5 s";
    }
    button.setAttribute("aria-pressed", timer === null ? "false" : "true");
  });
  widget.hidden = false;
});
)js";

using Out = std::back_insert_iterator<std::string>;

std::string html(std::string_view text) {
  return escapeMarkup(text);
}
std::string htmlAttribute(std::string_view text) {
  return escapeMarkup(text, Markup::attribute);
}
// A cell's text, or a grey dash when there is none.
std::string htmlOrDash(std::string_view text) {
  return text.empty() ? "<span class=\"none\">—</span>" : html(text);
}

std::string badge(Outcome outcome) {
  return fmt::format("<span class=\"badge {0}\">{0}</span>", outcomeName(outcome));
}

bool isFailing(Outcome outcome) {
  return outcome != Outcome::passed;
}

// ---- the headline -------------------------------------------------------------------------------

template <typename Result>
GoldenResults::Counts countOutcomes(const std::vector<Result>& results) {
  GoldenResults::Counts c;
  for (const Result& r : results) {
    c.passed += r.outcome == Outcome::passed;
    c.failed += r.outcome == Outcome::failed;
    c.missing += r.outcome == Outcome::missing;
    c.error += r.outcome == Outcome::error;
  }
  return c;
}

void countsRow(Out out, std::string_view what, const GoldenResults::Counts& c) {
  const auto cell = [](long n, bool bad) {
    return fmt::format("<td class=\"n{}\">{}</td>", bad && n > 0 ? " bad" : "", n);
  };
  fmt::format_to(out, "<tr><th>{}</th>{}{}{}{}{}</tr>\n", what, cell(c.passed, false), cell(c.failed, true),
                 cell(c.missing, true), cell(c.error, true), cell(c.total(), false));
}

std::string headline(const GoldenResults::Counts& c) {
  if (c.total() == 0) return "golden check: nothing was checked";
  if (c.total() == c.passed) return fmt::format("golden check: all {} passed", c.total());
  return fmt::format("golden check: {} of {} not passed", c.total() - c.passed, c.total());
}

void writeRuns(Out out, const std::vector<RunFacts>& runs) {
  fmt::format_to(out,
                 "<table class=\"list runs\"><tr><th>manifest</th><th>program</th><th>GL</th><th>LP_NUM_THREADS</th>"
                 "<th>overrides</th><th>shard</th><th>time</th></tr>\n");
  for (const RunFacts& r : runs) {
    fmt::format_to(out,
                   "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td><code>{}</code></td><td>{}</td>"
                   "<td class=\"n\">{}</td></tr>\n",
                   htmlOrDash(r.manifest), htmlOrDash(r.program), htmlOrDash(r.gl), htmlOrDash(r.lpNumThreads),
                   htmlOrDash(r.overrides), r.shard.empty() ? "whole manifest" : html(r.shard), secondsText(r.seconds));
  }
  fmt::format_to(out, "</table>\n");
}

// ---- failing results ----------------------------------------------------------------------------

std::string frameAnchor(std::size_t i) {
  return fmt::format("frame-{}", i);
}
std::string stateAnchor(std::size_t i) {
  return fmt::format("state-{}", i);
}

std::string controlLabel(const FrameResult& f) {
  return f.expectDiffer ? " <span class=\"control\">control: must differ</span>" : "";
}

void writeFactRow(Out out, std::string_view what, std::string_view htmlValue) {
  fmt::format_to(out, "<tr><th>{}</th><td>{}</td></tr>\n", what, htmlValue);
}

void writeReproduce(Out out, const std::vector<std::string>& commands) {
  if (commands.empty()) return;
  fmt::format_to(out, "<p>Reproduce (from where the check ran):</p>\n<pre><code>");
  for (const std::string& command : commands) fmt::format_to(out, "{}\n", html(command));
  fmt::format_to(out, "</code></pre>\n");
}

void writePicture(Out out, std::string_view file, std::string_view what, std::string_view name) {
  if (file.empty()) return;
  const std::string url = htmlAttribute(urlPath(file));
  fmt::format_to(out,
                 "<figure><a href=\"{0}\"><img class=\"frame\" src=\"{0}\" alt=\"{1} frame of {2}\"></a>"
                 "<figcaption>{1}: <a href=\"{0}\"><code>{3}</code></a></figcaption></figure>\n",
                 url, what, htmlAttribute(name), html(file));
}

// The slider and the blink comparison of an expected and an actual frame, for the script to wake.
void writeComparison(Out out, const FrameResult& f) {
  const std::string expected = htmlAttribute(urlPath(f.files.expected));
  const std::string actual = htmlAttribute(urlPath(f.files.actual));
  fmt::format_to(
      out,
      "<div class=\"compare\" hidden data-expected=\"{0}\" data-actual=\"{1}\">\n"
      "<figure class=\"slider\"><div class=\"stage\"><img class=\"frame under\" src=\"{0}\" alt=\"expected\">"
      "<img class=\"frame over\" src=\"{1}\" alt=\"actual\"></div>\n"
      "<input type=\"range\" min=\"0\" max=\"100\" value=\"50\" aria-label=\"how much of the actual frame to show\">\n"
      "<figcaption>Slider: the actual frame left of the cut, the expected frame right of it.</figcaption></figure>\n"
      "<figure class=\"blink\"><img class=\"frame\" src=\"{0}\" alt=\"expected\">\n"
      "<figcaption>Blink: showing <span class=\"shown\">expected</span>; click the picture to switch.</figcaption>\n"
      "<button type=\"button\" aria-pressed=\"false\">Blink every 0.5 s</button></figure>\n"
      "</div>\n",
      expected, actual);
}

void writeFailingFrame(Out out, const FrameResult& f, std::size_t index) {
  fmt::format_to(out, "<section class=\"result {}\" id=\"{}\">\n<h3>{} <code>{}</code>{}</h3>\n",
                 outcomeName(f.outcome), frameAnchor(index), badge(f.outcome), html(f.name), controlLabel(f));
  if (!f.message.empty()) fmt::format_to(out, "<p class=\"message\">{}</p>\n", html(f.message));
  fmt::format_to(out, "<table class=\"facts\">\n");
  writeFactRow(out, "scenario", fmt::format("<code>{}</code> at t = {}", html(f.scenario), html(f.time)));
  writeFactRow(out, "reference", fmt::format("<code>{}</code>", htmlOrDash(f.reference)));
  writeFactRow(out, "expects", html(expectationText(f)));
  if (f.numbers) {
    const FrameNumbers& n = *f.numbers;
    writeFactRow(out, "differing pixels", html(shareText(n)));
    writeFactRow(out, "tolerance", html(toleranceText(n)));
    writeFactRow(out, "largest channel difference", html(largestText(n)));
    writeFactRow(out, "box of the differences", html(boxText(n)));
    writeFactRow(out, "size", fmt::format("{}×{} px", n.width, n.height));
  }
  writeFactRow(out, "time", secondsText(f.seconds));
  fmt::format_to(out, "</table>\n");
  const KeptFiles& k = f.files;
  if (!k.expected.empty() || !k.actual.empty() || !k.diff.empty()) {
    fmt::format_to(out, "<div class=\"pictures\">\n");
    writePicture(out, k.expected, "expected", f.name);
    writePicture(out, k.actual, "actual", f.name);
    writePicture(out, k.diff, "diff", f.name);
    fmt::format_to(out, "</div>\n");
    if (!k.diff.empty()) {
      fmt::format_to(out,
                     "<p>In the diff, magenta pixels differ by more than the threshold, teal ones by less; the yellow "
                     "frame is their box, over a dimmed grey copy of the expected frame.</p>\n");
    }
  }
  if (!k.expected.empty() && !k.actual.empty()) writeComparison(out, f);
  writeReproduce(out, f.reproduce);
  fmt::format_to(out, "</section>\n");
}

void writeDeviationRow(Out out, std::string_view what, const StateDeviation& d) {
  fmt::format_to(out,
                 "<tr><th>{}</th><td>{}</td><td><code>{}</code></td><td>{}</td><td class=\"n\">{}</td>"
                 "<td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n",
                 what, html(d.time), html(d.point), html(d.quantity), numberText(d.expected), numberText(d.actual),
                 numberText(d.difference), numberText(d.tolerance));
}

void writeFileLinks(Out out, const KeptFiles& files) {
  std::vector<std::string> links;
  for (const auto& [what, path] :
       {std::pair{"actual", &files.actual}, std::pair{"expected", &files.expected}, std::pair{"diff", &files.diff}}) {
    if (path->empty()) continue;
    links.push_back(
        fmt::format("<a href=\"{}\">{}</a> (<code>{}</code>)", htmlAttribute(urlPath(*path)), what, html(*path)));
  }
  if (!links.empty()) fmt::format_to(out, "<p>Files: {}</p>\n", fmt::join(links, ", "));
}

void writeFailingState(Out out, const StateResult& s, std::size_t index) {
  fmt::format_to(out, "<section class=\"result {}\" id=\"{}\">\n<h3>{} <code>{}</code> (state)</h3>\n",
                 outcomeName(s.outcome), stateAnchor(index), badge(s.outcome), html(s.name));
  if (!s.message.empty()) fmt::format_to(out, "<p class=\"message\">{}</p>\n", html(s.message));
  fmt::format_to(out, "<table class=\"facts\">\n");
  writeFactRow(
      out, "scenario",
      fmt::format("<code>{}</code> at t = {}", html(s.scenario), html(fmt::format("{}", fmt::join(s.times, ", ")))));
  writeFactRow(out, "reference", fmt::format("<code>{}</code>", htmlOrDash(s.reference)));
  writeFactRow(out, "values compared", fmt::format("{}", s.values));
  writeFactRow(out, "time", secondsText(s.seconds));
  fmt::format_to(out, "</table>\n");
  if (s.firstBeyond || s.largest) {
    fmt::format_to(out,
                   "<table class=\"list deviations\"><tr><th></th><th>time</th><th>point</th><th>quantity</th>"
                   "<th>expected</th><th>actual</th><th>difference</th><th>tolerance</th></tr>\n");
    if (s.firstBeyond) writeDeviationRow(out, "first beyond tolerance", *s.firstBeyond);
    if (s.largest) writeDeviationRow(out, "largest deviation", *s.largest);
    fmt::format_to(out, "</table>\n");
  }
  writeFileLinks(out, s.files);
  writeReproduce(out, s.reproduce);
  fmt::format_to(out, "</section>\n");
}

void writeFailureIndex(Out out, const GoldenResults& results) {
  fmt::format_to(out, "<ul class=\"index\">\n");
  for (std::size_t i = 0; i < results.frames.size(); ++i) {
    const FrameResult& f = results.frames[i];
    if (!isFailing(f.outcome)) continue;
    fmt::format_to(out, "<li>{} <a href=\"#{}\">frame <code>{}</code></a>{}</li>\n", badge(f.outcome), frameAnchor(i),
                   html(f.name), controlLabel(f));
  }
  for (std::size_t i = 0; i < results.states.size(); ++i) {
    const StateResult& s = results.states[i];
    if (!isFailing(s.outcome)) continue;
    fmt::format_to(out, "<li>{} <a href=\"#{}\">state <code>{}</code></a></li>\n", badge(s.outcome), stateAnchor(i),
                   html(s.name));
  }
  fmt::format_to(out, "</ul>\n");
}

// ---- passing results ----------------------------------------------------------------------------

void writePassingFrames(Out out, const std::vector<FrameResult>& frames) {
  fmt::format_to(out,
                 "<table class=\"list passed-frames\"><tr><th>frame</th><th>scenario</th><th>t</th><th>expects</th>"
                 "<th>differing pixels</th><th>largest</th><th>box</th><th>kept</th><th>time</th></tr>\n");
  for (const FrameResult& f : frames) {
    if (isFailing(f.outcome)) continue;
    std::string kept;
    for (const auto& [what, path] : {std::pair{"actual", &f.files.actual}, std::pair{"expected", &f.files.expected},
                                     std::pair{"diff", &f.files.diff}}) {
      if (!path->empty()) kept += fmt::format(" <a href=\"{}\">{}</a>", htmlAttribute(urlPath(*path)), what);
    }
    fmt::format_to(out,
                   "<tr><td><code>{}</code></td><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>"
                   "<td>{}</td><td>{}</td><td class=\"n\">{}</td></tr>\n",
                   html(f.name), html(f.scenario), html(f.time),
                   f.expectDiffer ? "<span class=\"control\">control: must differ</span>" : "match",
                   f.numbers ? html(shareText(*f.numbers)) : htmlOrDash(""),
                   f.numbers ? html(largestText(*f.numbers)) : htmlOrDash(""),
                   f.numbers ? html(boxText(*f.numbers)) : htmlOrDash(""), kept.empty() ? htmlOrDash("") : kept,
                   secondsText(f.seconds));
  }
  fmt::format_to(out, "</table>\n");
}

void writePassingStates(Out out, const std::vector<StateResult>& states) {
  fmt::format_to(out,
                 "<table class=\"list passed-states\"><tr><th>state</th><th>scenario</th><th>times</th>"
                 "<th>values</th><th>largest deviation</th><th>time</th></tr>\n");
  for (const StateResult& s : states) {
    if (isFailing(s.outcome)) continue;
    fmt::format_to(out,
                   "<tr><td><code>{}</code></td><td><code>{}</code></td><td>{}</td><td class=\"n\">{}</td><td>{}</td>"
                   "<td class=\"n\">{}</td></tr>\n",
                   html(s.name), html(s.scenario), html(fmt::format("{}", fmt::join(s.times, ", "))), s.values,
                   s.largest ? html(deviationText(*s.largest)) : htmlOrDash(""), secondsText(s.seconds));
  }
  fmt::format_to(out, "</table>\n");
}

}  // namespace

std::string reportHtml(const GoldenResults& results) {
  const GoldenResults::Counts frames = countOutcomes(results.frames), states = countOutcomes(results.states);
  const GoldenResults::Counts all = results.counts();
  const std::string title = headline(all);
  std::string text;
  Out out(text);
  fmt::format_to(out,
                 "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                 "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
                 "<title>{}</title>\n<link rel=\"icon\" href=\"data:,\">\n<style>{}</style>\n</head>\n<body>\n",
                 title, kStyle);
  fmt::format_to(out, "<h1 class=\"{}\">{}</h1>\n", all.total() == all.passed ? "ok" : "bad", title);
  fmt::format_to(out,
                 "<table class=\"list counts\"><tr><th></th><th>passed</th><th>failed</th><th>missing</th>"
                 "<th>error</th><th>total</th></tr>\n");
  countsRow(out, "frames", frames);
  countsRow(out, "states", states);
  countsRow(out, "all", all);
  fmt::format_to(out, "</table>\n");
  writeRuns(out, results.runs);

  if (all.total() != all.passed) {
    fmt::format_to(out, "<h2>Not passed</h2>\n");
    writeFailureIndex(out, results);
    for (std::size_t i = 0; i < results.frames.size(); ++i) {
      if (isFailing(results.frames[i].outcome)) writeFailingFrame(out, results.frames[i], i);
    }
    for (std::size_t i = 0; i < results.states.size(); ++i) {
      if (isFailing(results.states[i].outcome)) writeFailingState(out, results.states[i], i);
    }
  }
  if (frames.passed > 0) {
    fmt::format_to(out, "<h2>Passed frames</h2>\n");
    writePassingFrames(out, results.frames);
  }
  if (states.passed > 0) {
    fmt::format_to(out, "<h2>Passed states</h2>\n");
    writePassingStates(out, results.states);
  }
  fmt::format_to(out, "<script>{}</script>\n</body>\n</html>\n", kScript);
  return text;
}

}  // namespace particles::golden::report
