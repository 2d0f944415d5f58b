// particles._particles: golden checks (python/src/bindings.hpp); particles.golden (python/particles/
// golden.py) is their Python face.
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"

namespace particles::python {

using namespace pybind11::literals;

void bindGolden(py::module_& module) {
  py::class_<golden::FrameCheck>(module, "FrameCheck", "One frame's result of a golden check (particles.golden.check).")
      .def_readonly("name", &golden::FrameCheck::name, "The frame's name in the manifest (cloth_t2.5).")
      .def_readonly("scenario", &golden::FrameCheck::scenario, "Its scenario, as the manifest writes it.")
      .def_readonly("time", &golden::FrameCheck::time, "Its time, s, as the manifest writes it.")
      .def_readonly("control", &golden::FrameCheck::control, "An `expect: differ` control: passes when it differs.")
      .def_readonly("outcome", &golden::FrameCheck::outcome, "'passed', 'failed', 'missing' or 'error'.")
      .def_readonly("message", &golden::FrameCheck::message, "Why, in one line; '' when it passed.")
      .def_readonly("differing", &golden::FrameCheck::differing, "Pixels beyond the threshold.")
      .def_readonly("pixels", &golden::FrameCheck::pixels, "Pixels compared: width × height.")
      .def_readonly("largest", &golden::FrameCheck::largest, "The largest channel difference, 0 to 255.")
      .def_readonly("actual", &golden::FrameCheck::actual, "The frame drawn, relative to the report folder ('' when not kept).")
      .def_readonly("expected", &golden::FrameCheck::expected, "The reference, as kept in the report folder.")
      .def_readonly("diff", &golden::FrameCheck::diff, "The difference picture, as kept in the report folder.")
      .def_readonly("reproduce", &golden::FrameCheck::reproduce, "Shell commands that reproduce the result.")
      .def("__repr__", [](const golden::FrameCheck& f) { return "<FrameCheck " + f.name + ": " + f.outcome + ">"; });
  py::class_<golden::StateCheck>(module, "StateCheck", "One state's result of a golden check (particles.golden.check).")
      .def_readonly("name", &golden::StateCheck::name, "The state's name in the manifest.")
      .def_readonly("scenario", &golden::StateCheck::scenario, "Its scenario, as the manifest writes it.")
      .def_readonly("times", &golden::StateCheck::times, "Its times, as the manifest writes them.")
      .def_readonly("outcome", &golden::StateCheck::outcome, "'passed', 'failed', 'missing' or 'error'.")
      .def_readonly("message", &golden::StateCheck::message, "Why, in one line; '' when it passed.")
      .def_readonly("values", &golden::StateCheck::values, "Values compared.")
      .def_readonly("point", &golden::StateCheck::point, "The first value beyond its tolerance (else the largest): its point.")
      .def_readonly("quantity", &golden::StateCheck::quantity, "... its quantity: x, y, vx, vy, angle or omega.")
      .def_readonly("expected", &golden::StateCheck::expected, "... the reference's value.")
      .def_readonly("actual", &golden::StateCheck::actual, "... this run's value.")
      .def_readonly("difference", &golden::StateCheck::difference, "... actual − expected.")
      .def_readonly("tolerance", &golden::StateCheck::tolerance, "... the tolerance it was held to.")
      .def_readonly("reproduce", &golden::StateCheck::reproduce, "Shell commands that reproduce the result.")
      .def("__repr__", [](const golden::StateCheck& s) { return "<StateCheck " + s.name + ": " + s.outcome + ">"; });
  py::class_<golden::Report>(module, "GoldenReport", "What a golden check found (particles.golden.check).")
      .def_readonly("frames", &golden::Report::frames, "Each frame's FrameCheck, in manifest order.")
      .def_readonly("states", &golden::Report::states, "Each state's StateCheck, in manifest order.")
      .def_readonly("passed", &golden::Report::passed, "How many checks passed.")
      .def_readonly("failed", &golden::Report::failed, "How many failed.")
      .def_readonly("missing", &golden::Report::missing, "How many have no reference yet.")
      .def_readonly("errors", &golden::Report::errors, "How many could not be checked.")
      .def_readonly("bad_reference", &golden::Report::badReference, "A reference was not a usable file.")
      .def_readonly("html", &golden::Report::html, "report.html's path: expected, actual and diff of each failure.")
      .def_readonly("summary", &golden::Report::summary, "The line `particles golden check` prints last.")
      .def_property_readonly("all_passed", &golden::Report::allPassed, "Every check passed.")
      .def("__bool__", &golden::Report::allPassed)
      .def("__repr__", [](const golden::Report& r) { return "<GoldenReport " + r.summary + ">"; });

  module.def(
      "_golden_check",
      [](const std::string& manifest, const std::string& output, std::vector<std::string> only, const std::string& shard,
         const std::string& gl, bool gpu, const std::string& raster, std::optional<int> threshold,
         std::optional<double> maxShare, int jobs) {
        golden::Options options;
        options.output = output;
        options.only = std::move(only);
        options.shard = shard;
        options.gl = gl;
        options.gpu = gpu;
        options.raster = raster;
        options.threshold = threshold;
        options.maxShare = maxShare;
        options.jobs = jobs;
        py::gil_scoped_release released;
        return golden::check(manifest, options);
      },
      "manifest"_a, "output"_a, "only"_a, "shard"_a, "gl"_a, "gpu"_a, "raster"_a, "threshold"_a, "max_share"_a,
      "jobs"_a,
      "particles.golden.check's C++ side.");
}

}  // namespace particles::python
