// particles._particles: a style given as a dict or a style file's text (python/src/bindings.hpp).
// A dict mirrors the scenario's `style` section key for key, as C++'s particles::Style does: it is
// written as YAML and merged by the scenario loader's style-file path, so that a wrong key or value
// is the file's ScenarioError, with its message.
#include <string>

#include "bindings.hpp"

namespace particles::python {

namespace {

// What Scenario::setStyle calls a style in its messages, as a style file is called by its path.
constexpr const char* kStyleLabel = "style";

}  // namespace

void setStyleOf(Scenario& scenario, const py::handle& style, const char* call) {
  static const py::handle mapping = py::object(py::module_::import("collections.abc").attr("Mapping")).release();
  if (style.is_none()) {
    scenario.setStyle(Style{});
    return;
  }
  if (py::isinstance<py::str>(style)) {
    const std::string yaml = style.cast<std::string>();
    withoutGil([&] { scenario.setStyle(yaml); });
    return;
  }
  if (!py::isinstance(style, mapping)) {
    throw ArgumentError(std::string(call) +
                        ": style takes a dict of the style section's keys (particles, springs, bodies, colorbar, "
                        "title, scale_bar, select), a style file's text or None, not " +
                        typeName(style));
  }
  if (py::len(style) == 0) {
    scenario.setStyle(Style{});
    return;
  }
  const std::string yaml = yamlText(style, call, kStyleLabel);
  try {
    withoutGil([&] { scenario.setStyle(yaml); });
  } catch (const ScenarioError& e) {
    // A line and column of YAML written here would only mislead: the key path names the dict's key.
    if (e.file() != kStyleLabel) throw;
    throw ScenarioError(e.file(), 0, 0, e.keyPath(), e.message(), e.origin());
  }
}

}  // namespace particles::python
