// writeReport (results.hpp): the report folder's three files, each written under a temporary name
// and renamed over its own when complete (output::OutputFile), so a reader (CI's artefact upload,
// `golden report`) never sees half of one.
#include <string>

#include "golden/junit_xml.hpp"
#include "golden/report_html.hpp"
#include "golden/results.hpp"
#include "golden/results_json.hpp"
#include "output/output_file.hpp"

namespace particles::golden {

namespace {

void writeWhole(const std::filesystem::path& file, const std::string& text) {
  output::OutputFile out(file);
  out.write(text);
  out.commit();
}

}  // namespace

void writeReport(const std::filesystem::path& folder, const GoldenResults& results) {
  // results.json first: the page and junit.xml say what it holds.
  writeWhole(folder / kResultsJson, report::resultsJson(results));
  writeWhole(folder / kJunitXml, report::junitXml(results));
  writeWhole(folder / kReportHtml, report::reportHtml(results));
}

}  // namespace particles::golden
