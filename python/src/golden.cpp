// particles._particles: golden checks (python/src/bindings.hpp); particles.golden (python/particles/
// golden.py) is their Python face.
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"

namespace particles::python {

using namespace pybind11::literals;

namespace {

// Each result as a Python object of its own (a copy).
template <class T>
py::list objectsOf(const std::vector<T>& results) {
  py::list out;
  for (const T& r : results) out.append(py::cast(Object<T>(r)));
  return out;
}

}  // namespace

namespace {

// A result's field as a getter: its value, its text (text()), its path (pathText()), its texts, or
// the name of its choice. `cls` names the Python class (Registered::require).
template <class T, class V>
auto fieldOf(V T::*member, const char* cls) {
  return [member, cls](const Object<T>& o) { return valueOf(o, cls).*member; };
}
template <class T>
auto textOf(std::string T::*member, const char* cls) {
  return [member, cls](const Object<T>& o) { return text(valueOf(o, cls).*member); };
}
template <class T>
auto pathOf(std::string T::*member, const char* cls) {
  return [member, cls](const Object<T>& o) { return pathText(valueOf(o, cls).*member); };
}
template <class T>
auto textsOf(std::vector<std::string> T::*member, const char* cls) {
  return [member, cls](const Object<T>& o) { return textList(valueOf(o, cls).*member); };
}
template <class T>
auto nameOf(golden::Outcome T::*member, const char* cls) {
  return [member, cls](const Object<T>& o) { return std::string(name(valueOf(o, cls).*member)); };
}

// shard= as "K/N" (the command line's --shard) or a (K, N) pair; None: all. The range is the C++
// call's to check.
std::optional<golden::Shard> shardOf(const py::object& shard) {
  if (shard.is_none()) return std::nullopt;
  const char* const takes = "golden.check: shard takes \"K/N\" or (K, N), the K-th of N parts";
  if (py::isinstance<py::str>(shard)) {
    const std::string text = shard.cast<std::string>();
    const size_t slash = text.find('/');
    if (slash == std::string::npos || slash == 0 || slash + 1 == text.size() ||
        text.find_first_not_of("0123456789/") != std::string::npos || text.find('/', slash + 1) != std::string::npos ||
        slash > 9 || text.size() - slash - 1 > 9) {
      throw ArgumentError(std::string(takes) + ", not " + quoted(text));
    }
    return golden::Shard{std::stoi(text.substr(0, slash)), std::stoi(text.substr(slash + 1))};
  }
  if (py::isinstance<py::tuple>(shard) && py::len(shard) == 2) {
    return golden::Shard{wholeInt(shard[py::int_(0)], "golden.check", "shard's K"),
                         wholeInt(shard[py::int_(1)], "golden.check", "shard's N")};
  }
  throw ArgumentError(std::string(takes) + ", not a " + typeName(shard));
}

void bindFrameCheck(py::module_& module) {
  py::class_<Object<golden::FrameCheck>>(module, "FrameCheck",
                                         "One frame's result of a golden check (particles.golden.check).")
      .def_property_readonly("name", textOf(&golden::FrameCheck::name, "FrameCheck"),
                             "The frame's name in the manifest (cloth_t2.5).")
      .def_property_readonly("scenario", textOf(&golden::FrameCheck::scenario, "FrameCheck"),
                             "Its scenario, as the manifest writes it.")
      .def_property_readonly("time", textOf(&golden::FrameCheck::time, "FrameCheck"),
                             "Its time, s, as the manifest writes it.")
      .def_property_readonly("control", fieldOf(&golden::FrameCheck::control, "FrameCheck"),
                             "An `expect: differ` control: passes when it differs.")
      .def_property_readonly("outcome", nameOf(&golden::FrameCheck::outcome, "FrameCheck"),
                             "'passed', 'failed', 'missing' or 'error'.")
      .def_property_readonly("message", textOf(&golden::FrameCheck::message, "FrameCheck"),
                             "Why, in one line; '' when it passed.")
      .def_property_readonly("differing", fieldOf(&golden::FrameCheck::differing, "FrameCheck"),
                             "Pixels beyond the threshold.")
      .def_property_readonly("pixels", fieldOf(&golden::FrameCheck::pixels, "FrameCheck"),
                             "Pixels compared: width × height.")
      .def_property_readonly("largest", fieldOf(&golden::FrameCheck::largest, "FrameCheck"),
                             "The largest channel difference, 0 to 255.")
      .def_property_readonly("actual", pathOf(&golden::FrameCheck::actual, "FrameCheck"),
                             "The frame drawn, relative to the report folder ('' when not kept).")
      .def_property_readonly("expected", pathOf(&golden::FrameCheck::expected, "FrameCheck"),
                             "The reference, as kept in the report folder.")
      .def_property_readonly("diff", pathOf(&golden::FrameCheck::diff, "FrameCheck"),
                             "The difference picture, as kept in the report folder.")
      .def_property_readonly("reproduce", textsOf(&golden::FrameCheck::reproduce, "FrameCheck"),
                             "Shell commands that reproduce the result.")
      .def("__repr__", [](const Object<golden::FrameCheck>& o) {
        const golden::FrameCheck& f = valueOf(o, "FrameCheck");
        return text("<FrameCheck " + f.name + ": " + std::string(name(f.outcome)) + ">");
      });
}

void bindStateCheck(py::module_& module) {
  py::class_<Object<golden::StateCheck>>(module, "StateCheck",
                                         "One state's result of a golden check (particles.golden.check).")
      .def_property_readonly("name", textOf(&golden::StateCheck::name, "StateCheck"),
                             "The state's name in the manifest.")
      .def_property_readonly("scenario", textOf(&golden::StateCheck::scenario, "StateCheck"),
                             "Its scenario, as the manifest writes it.")
      .def_property_readonly("times", textsOf(&golden::StateCheck::times, "StateCheck"),
                             "Its times, as the manifest writes them.")
      .def_property_readonly("outcome", nameOf(&golden::StateCheck::outcome, "StateCheck"),
                             "'passed', 'failed', 'missing' or 'error'.")
      .def_property_readonly("message", textOf(&golden::StateCheck::message, "StateCheck"),
                             "Why, in one line; '' when it passed.")
      .def_property_readonly("values", fieldOf(&golden::StateCheck::values, "StateCheck"), "Values compared.")
      .def_property_readonly("point", textOf(&golden::StateCheck::point, "StateCheck"),
                             "The first value beyond its tolerance (else the largest): its point.")
      .def_property_readonly("quantity", textOf(&golden::StateCheck::quantity, "StateCheck"),
                             "... its quantity: x, y, vx, vy, angle or omega.")
      .def_property_readonly("expected", fieldOf(&golden::StateCheck::expected, "StateCheck"),
                             "... the reference's value.")
      .def_property_readonly("actual", fieldOf(&golden::StateCheck::actual, "StateCheck"), "... this run's value.")
      .def_property_readonly("difference", fieldOf(&golden::StateCheck::difference, "StateCheck"),
                             "... actual − expected.")
      .def_property_readonly("tolerance", fieldOf(&golden::StateCheck::tolerance, "StateCheck"),
                             "... the tolerance it was held to.")
      .def_property_readonly("reproduce", textsOf(&golden::StateCheck::reproduce, "StateCheck"),
                             "Shell commands that reproduce the result.")
      .def("__repr__", [](const Object<golden::StateCheck>& o) {
        const golden::StateCheck& s = valueOf(o, "StateCheck");
        return text("<StateCheck " + s.name + ": " + std::string(name(s.outcome)) + ">");
      });
}

void bindGoldenReport(py::module_& module) {
  py::class_<Object<golden::Report>>(module, "GoldenReport", "What a golden check found (particles.golden.check).")
      .def_property_readonly(
          "frames", [](const Object<golden::Report>& o) { return objectsOf(valueOf(o, "GoldenReport").frames); },
          "Each frame's FrameCheck, in manifest order.")
      .def_property_readonly(
          "states", [](const Object<golden::Report>& o) { return objectsOf(valueOf(o, "GoldenReport").states); },
          "Each state's StateCheck, in manifest order.")
      .def_property_readonly("passed", fieldOf(&golden::Report::passed, "GoldenReport"), "How many checks passed.")
      .def_property_readonly("failed", fieldOf(&golden::Report::failed, "GoldenReport"), "How many failed.")
      .def_property_readonly("missing", fieldOf(&golden::Report::missing, "GoldenReport"),
                             "How many have no reference yet.")
      .def_property_readonly("errors", fieldOf(&golden::Report::errors, "GoldenReport"),
                             "How many could not be checked.")
      .def_property_readonly("bad_reference", fieldOf(&golden::Report::badReference, "GoldenReport"),
                             "A reference was not a usable file.")
      .def_property_readonly("html", pathOf(&golden::Report::html, "GoldenReport"),
                             "report.html's path: expected, actual and diff of each failure.")
      .def_property_readonly("summary", textOf(&golden::Report::summary, "GoldenReport"),
                             "The line `particles golden check` prints last.")
      .def_property_readonly(
          "all_passed", [](const Object<golden::Report>& o) { return valueOf(o, "GoldenReport").allPassed(); },
          "Every check passed.")
      .def("__bool__", [](const Object<golden::Report>& o) { return valueOf(o, "GoldenReport").allPassed(); })
      .def("__repr__", [](const Object<golden::Report>& o) {
        const golden::Report& r = valueOf(o, "GoldenReport");
        return text("<GoldenReport " + r.summary + ">");
      });
}

}  // namespace

void bindGolden(py::module_& module) {
  bindFrameCheck(module);
  bindStateCheck(module);
  bindGoldenReport(module);
  module.def(
      "_golden_check",
      [](const std::string& manifest, const std::string& output, std::vector<std::string> only, const py::object& shard,
         const py::object& gl, bool gpu, const py::object& raster, std::optional<int> threshold,
         std::optional<double> maxShare, int jobs) {
        golden::Options options;
        options.output = output;
        options.only = std::move(only);
        options.shard = shardOf(shard);
        options.gl = choiceOf(gl, "golden.check", "gl", kGlBackends);
        options.gpu = gpu;
        if (!raster.is_none()) options.raster = choiceOf(raster, "golden.check", "raster", kRasters);
        options.threshold = threshold;
        options.maxShare = maxShare;
        options.jobs = jobs;
        return Object<golden::Report>(withoutGil([&] { return golden::check(manifest, options); }));
      },
      "manifest"_a, "output"_a, "only"_a, "shard"_a, "gl"_a, "gpu"_a, "raster"_a, "threshold"_a, "max_share"_a,
      "jobs"_a, "particles.golden.check's C++ side.");
}

}  // namespace particles::python
