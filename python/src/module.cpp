// particles._particles: the module, its exceptions and Scenario (python/src/bindings.hpp).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>

#include "bindings.hpp"

namespace particles::python {

using namespace pybind11::literals;

namespace {

// The exception classes, made once at import and kept by the module's attributes.
struct ExceptionClasses {
  PyObject* error = nullptr;
  PyObject* scenarioError = nullptr;
  PyObject* simulationError = nullptr;
  PyObject* outputError = nullptr;
  PyObject* argumentError = nullptr;
};
ExceptionClasses classes;

PyObject* newExceptionClass(py::module_& module, const char* name, const char* doc, py::tuple bases) {
  const std::string qualified = std::string("particles.") + name;
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (cls == nullptr) throw py::error_already_set();
  module.add_object(name, py::handle(cls));  // the module holds the reference
  return cls;
}

// Raises `cls(what)` with the given attributes set on the exception.
void raise(PyObject* cls, const char* what, const py::dict& attributes = {}) {
  py::object exception = py::reinterpret_borrow<py::object>(cls)(what);
  for (auto [name, value] : attributes) py::setattr(exception, name, value);
  PyErr_SetObject(cls, exception.ptr());
}

// A value Python passes to Scenario.set, as the text `--set` takes; ArgumentError for other types.
std::string settingText(std::string_view path, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  if (py::isinstance<py::float_>(value)) {
    const double number = value.cast<double>();
    if (!std::isfinite(number)) {
      throw ArgumentError("Scenario.set: " + std::string(path) + " must be finite, got " + py::repr(value).cast<std::string>());
    }
    return py::repr(value).cast<std::string>();  // the shortest text that reads back as the same double
  }
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  throw ArgumentError("Scenario.set: the value of " + std::string(path) + " must be a str, int, float or bool, not " +
                      py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
}

void setAll(Scenario& scenario, const py::object& settings) {
  if (settings.is_none()) return;
  if (!py::isinstance<py::dict>(settings)) {
    throw ArgumentError("Scenario: set= takes a dict of key path → value, not " +
                        py::str(py::type::handle_of(settings).attr("__name__")).cast<std::string>());
  }
  for (auto [key, value] : settings.cast<py::dict>()) {
    if (!py::isinstance<py::str>(key)) throw ArgumentError("Scenario: the keys of set= are key paths (str), like \"forces[0].ks\"");
    const std::string path = key.cast<std::string>();
    scenario.set(path, settingText(path, value));
  }
}

std::string describeScenario(const Scenario& scenario) {
  return "<particles.Scenario '" + scenario.name() + "' from " + scenario.file() + ": " + scenario.integrator() +
         ", dt = " + py::repr(py::float_(scenario.dt())).cast<std::string>() + " s, " +
         py::repr(py::float_(scenario.duration())).cast<std::string>() + " s, " + std::to_string(scenario.particleCount()) +
         " particles, " + std::to_string(scenario.bodyCount()) + " bodies>";
}

unsigned long mainThreadId = 0;

}  // namespace

void rememberMainThread() {
  mainThreadId = py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
}

InterruptCheck::InterruptCheck()
    : mainThread_(PyThread_get_thread_ident() == mainThreadId),
      next_(std::chrono::steady_clock::now() + std::chrono::milliseconds(50)) {}

bool InterruptCheck::keepGoing() {
  if (!mainThread_) return true;
  const auto now = std::chrono::steady_clock::now();
  if (now < next_) return true;
  next_ = now + std::chrono::milliseconds(50);
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() == 0) return true;
  interrupted_ = true;  // the handler's exception (KeyboardInterrupt) stays set for raiseIfInterrupted
  return false;
}

void InterruptCheck::raiseIfInterrupted() const {
  if (interrupted_) throw py::error_already_set();
}

void bindErrors(py::module_& module) {
  classes.error = newExceptionClass(module, "Error",
                                    "Every error particles raises: bad input, a simulation that blew up, an output "
                                    "that could not be written. str(e) is the whole message.",
                                    py::make_tuple(py::handle(PyExc_Exception)));
  classes.scenarioError = newExceptionClass(
      module, "ScenarioError",
      "A scenario that cannot be loaded or a setting it does not take. Attributes: file, line and column (0 when "
      "not from a place in the file), key_path (like 'forces[2].ks', or ''), reason (the message without the place).",
      py::make_tuple(py::handle(classes.error), py::handle(PyExc_ValueError)));
  classes.simulationError = newExceptionClass(
      module, "SimulationError",
      "A step that blew up. The simulation stays at the last good state. Attributes: step (counted from 1), time "
      "(s, the time that step would have reached), integrator, dt (s), reason.",
      py::make_tuple(py::handle(classes.error), py::handle(PyExc_RuntimeError)));
  classes.outputError = newExceptionClass(module, "OutputError",
                                          "A file that could not be written (a PNG, a video); nothing is left of it.",
                                          py::make_tuple(py::handle(classes.error), py::handle(PyExc_OSError)));
  classes.argumentError = newExceptionClass(
      module, "ArgumentError",
      "A value an API call does not take: a negative step count, an index out of range, a frame of the wrong "
      "shape or dtype, a closed simulation.",
      py::make_tuple(py::handle(classes.error), py::handle(PyExc_ValueError)));

  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const ScenarioError& e) {
      raise(classes.scenarioError, e.what(),
            py::dict("file"_a = e.file(), "line"_a = e.line(), "column"_a = e.column(), "key_path"_a = e.keyPath(),
                     "reason"_a = e.message()));
    } catch (const SimulationError& e) {
      raise(classes.simulationError, e.what(),
            py::dict("step"_a = e.step(), "time"_a = e.time(), "integrator"_a = e.integrator(), "dt"_a = e.dt(),
                     "reason"_a = e.reason()));
    } catch (const OutputError& e) {
      raise(classes.outputError, e.what());
    } catch (const ArgumentError& e) {
      raise(classes.argumentError, e.what());
    } catch (const Error& e) {
      raise(classes.error, e.what());
    }
  });
}

void bindScenario(py::module_& module) {
  py::class_<Scenario>(module, "Scenario", R"doc(A scenario: what `particles run` reads from a YAML file, with settings changed
as `--set` changes them. A Simulation is made from it; changing the scenario afterwards does not
change simulations made before.

    scenario = particles.Scenario.load("scenarios/cloth.yaml", set={"integrator": "rk4", "dt": 0.002})
    scenario.set("forces[1].ks", 80.0)
)doc")
      .def_static(
          "load",
          [](const std::filesystem::path& path, const py::object& set) {
            Scenario scenario = Scenario::load(path.string());
            setAll(scenario, set);
            return scenario;
          },
          "path"_a, py::kw_only(), "set"_a = py::none(),
          R"doc(Loads a scenario file (YAML). `set` is a dict of key path → value, applied in
order as `--set KEY=VALUE` would be: key paths like "forces[2].ks", or the shorthands
"integrator", "dt", "duration" and "implicit_solver". Raises ScenarioError naming the file, line,
column and key.)doc")
      .def_static(
          "from_text",
          [](std::string_view yaml, const std::string& label, const py::object& set) {
            Scenario scenario = Scenario::fromText(yaml, label);
            setAll(scenario, set);
            return scenario;
          },
          "yaml"_a, "label"_a = "<text>", py::kw_only(), "set"_a = py::none(),
          "A scenario from YAML text; `label` stands for the file name in messages. `set` as in load().")
      .def(
          "set",
          [](py::object self, std::string_view path, const py::handle& value) {
            self.cast<Scenario&>().set(path, settingText(path, value));
            return self;
          },
          "path"_a, "value"_a,
          R"doc(Changes one setting as `--set PATH=VALUE` does (str, int, float or bool) and
returns the scenario, so that calls chain. Checked at once: a bad key or value raises
ScenarioError and leaves the scenario as it was.)doc")
      .def("copy", [](const Scenario& scenario) { return Scenario(scenario); }, "An independent copy.")
      .def("__copy__", [](const Scenario& scenario) { return Scenario(scenario); })
      .def("__deepcopy__", [](const Scenario& scenario, const py::handle&) { return Scenario(scenario); }, "memo"_a)
      .def("validate", &Scenario::validate,
           "What `particles check` prints for it: a summary of a valid scenario. Raises ScenarioError otherwise.")
      .def_property_readonly("name", &Scenario::name, "The scenario's name.")
      .def_property_readonly("description", &Scenario::description, "Its description, or ''.")
      .def_property_readonly("file", &Scenario::file, "The path it was loaded from, or from_text's label.")
      .def_property_readonly("integrator", &Scenario::integrator, "The integrator, as scenarios name it (rk4, ...).")
      .def_property_readonly("dt", &Scenario::dt, "The time step, s.")
      .def_property_readonly("duration", &Scenario::duration, "The simulated seconds `particles run` covers.")
      .def_property_readonly("steps", &Scenario::steps, "The steps of dt that cover the duration.")
      .def_property_readonly("fps", &Scenario::fps, "Frames per simulated second when rendered.")
      .def_property_readonly("particle_count", &Scenario::particleCount, "How many particles it has.")
      .def_property_readonly("body_count", &Scenario::bodyCount, "How many rigid bodies it has.")
      .def("__repr__", &describeScenario);
}

}  // namespace particles::python

PYBIND11_MODULE(_particles, module) {
  using namespace particles::python;
  module.doc() = "particles' C++ library (include/particles/); import particles, not this module.";
  module.attr("__version__") = particles::version();
  rememberMainThread();
  bindErrors(module);
  bindScenario(module);
  bindSimulation(module);
  bindRendering(module);
  bindGolden(module);
}
