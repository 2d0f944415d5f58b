// particles._particles: the module, its exceptions, Scenario, and the conversions every part uses
// (python/src/bindings.hpp).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <climits>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <set>
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
void raise(PyObject* cls, std::string_view what, const py::dict& attributes = {}) {
  py::object exception = py::reinterpret_borrow<py::object>(cls)(text(what));
  for (auto [name, value] : attributes) py::setattr(exception, name, value);
  PyErr_SetObject(cls, exception.ptr());
}

// Python's decoding of library text with an error handler; a failure here would only be out of
// memory, which pybind11 reports as MemoryError.
py::str decoded(std::string_view bytes, const char* errors) {
  PyObject* str = PyUnicode_DecodeUTF8(bytes.data(), Py_ssize_t(bytes.size()), errors);
  if (str == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(str);
}

std::string settingText(std::string_view path, const py::handle& value) {
  return yamlText(value, "Scenario.set", path);
}

// set='s key paths and values, applied in order; any mapping (a dict, MappingProxyType).
void setAll(Scenario& scenario, const py::object& settings) {
  if (settings.is_none()) return;
  if (!py::isinstance(settings, py::module_::import("collections.abc").attr("Mapping"))) {
    throw ArgumentError("Scenario: set= takes a dict (or another mapping) of key path → value, not " +
                        typeName(settings));
  }
  for (const py::handle item : settings.attr("items")()) {
    const py::tuple pair = py::reinterpret_borrow<py::tuple>(item);
    if (!py::isinstance<py::str>(pair[0])) {
      throw ArgumentError("Scenario: the keys of set= are key paths (str), like \"forces[0].ks\", not " +
                          typeName(pair[0]));
    }
    const std::string path = pair[0].cast<std::string>();
    scenario.set(path, settingText(path, pair[1]));
  }
}

// The Scenario behind a Python one (Registered::require).
const Scenario& scenarioOf(const ScenarioObject& object) {
  return valueOf(object, "Scenario");
}
Scenario& scenarioOf(ScenarioObject& object) {
  return valueOf(object, "Scenario");
}

// A Scenario getter as a Python one: its value, its text (text()), its path (pathText()), or the
// name of its choice.
template <class R>
auto scenarioValue(R (Scenario::*method)() const) {
  return [method](const ScenarioObject& o) { return (scenarioOf(o).*method)(); };
}
auto scenarioText(std::string (Scenario::*method)() const) {
  return [method](const ScenarioObject& o) { return text((scenarioOf(o).*method)()); };
}
auto scenarioPath(std::string (Scenario::*method)() const) {
  return [method](const ScenarioObject& o) { return pathText((scenarioOf(o).*method)()); };
}
auto scenarioChoice(Integrator (Scenario::*method)() const) {
  return [method](const ScenarioObject& o) { return std::string(name((scenarioOf(o).*method)())); };
}

std::string describeScenario(const Scenario& scenario) {
  return "<particles.Scenario '" + scenario.name() + "' from " + scenario.file() + ": " +
         std::string(name(scenario.integrator())) +
         ", dt = " + py::repr(py::float_(scenario.dt())).cast<std::string>() + " s, " +
         py::repr(py::float_(scenario.duration())).cast<std::string>() + " s, " +
         std::to_string(scenario.particleCount()) + " particles, " + std::to_string(scenario.bodyCount()) + " bodies>";
}

unsigned long mainThreadId = 0;

// The constructed objects' addresses (Registered), under their mutex: objects are made and freed on
// any thread (a frame's, a golden check's results).
std::mutex registryMutex;
std::set<const void*>& registry() {
  static std::set<const void*>* const addresses = new std::set<const void*>;  // outlives every object
  return *addresses;
}

}  // namespace

Registered::Registered() {
  const std::lock_guard lock(registryMutex);
  registry().insert(this);
}
Registered::Registered(const Registered&) : Registered() {}
Registered::~Registered() {
  const std::lock_guard lock(registryMutex);
  registry().erase(this);
}

void Registered::require(const void* self, const char* cls) {
  {
    const std::lock_guard lock(registryMutex);
    if (registry().count(self) != 0) return;
  }
  throw ArgumentError(std::string("this particles.") + cls +
                      " was never initialised (made by __new__ without __init__); make one by calling its class or "
                      "the function that returns it");
}

py::str text(std::string_view bytes) {
  return decoded(bytes, "backslashreplace");
}
py::str pathText(std::string_view bytes) {
  return decoded(bytes, "surrogateescape");
}

py::list textList(const std::vector<std::string>& items) {
  py::list out(items.size());
  for (size_t i = 0; i < items.size(); ++i) out[i] = text(items[i]);
  return out;
}

std::string quoted(const std::string& value) {
  const py::str text = decoded(value, "backslashreplace");
  if (py::len(text) <= 80) return py::repr(text).cast<std::string>();
  return py::repr(text[py::slice(0, 80, 1)]).cast<std::string>() + "… (" + std::to_string(value.size()) + " bytes)";
}

namespace {

template <class Choice, size_t N>
void bindChoice(py::module_& module, const char* pythonName, const char* doc, const Choice (&values)[N]) {
  py::enum_<Choice> choices(module, pythonName, doc);
  for (const Choice value : values) choices.value(std::string(name(value)).c_str(), value);
}

}  // namespace

void bindChoices(py::module_& module) {
  bindChoice(module, "Integrator", "The integrators; everywhere Python takes one, its name (a str) is taken too.",
             kIntegrators);
  bindChoice(module, "Theme", "A frame's colours: dark for the screen, light for printed reports.", kThemes);
  bindChoice(module, "Background", "What is behind the scene: the theme's colour, or nothing (alpha = coverage).",
             kBackgrounds);
  bindChoice(module, "Raster",
             "How a frame is drawn: auto, GL triangles, GL tiles, the resident GPU path, or the cpu raster.", kRasters);
  bindChoice(module, "GlBackend", "The GL backend: auto (EGL, else OSMesa), egl or osmesa.", kGlBackends);
  bindChoice(module, "Outcome", "A golden check's result: passed, failed, missing or error.", kOutcomes);
}

std::string typeName(const py::handle& value) {
  return py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>();
}

long long wholeNumber(const py::handle& value, const char* call, const char* what) {
  if (py::isinstance<py::bool_>(value) || py::isinstance<py::float_>(value) || !PyIndex_Check(value.ptr())) {
    throw ArgumentError(std::string(call) + ": " + what + " is a whole number, not " + typeName(value));
  }
  const auto number = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!number) throw py::error_already_set();
  int overflow = 0;
  const long long n = PyLong_AsLongLongAndOverflow(number.ptr(), &overflow);
  if (overflow > 0) return LLONG_MAX;
  if (overflow < 0) return LLONG_MIN;
  if (n == -1 && PyErr_Occurred()) throw py::error_already_set();
  return n;
}

int wholeInt(const py::handle& value, const char* call, const char* what) {
  const long long n = wholeNumber(value, call, what);
  if (n > INT_MAX || n < INT_MIN) {
    throw ArgumentError(std::string(call) + ": " + what + " is out of range, got " +
                        py::str(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()))).cast<std::string>());
  }
  return int(n);
}

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
  // The C API rather than py::gil_scoped_acquire: a thread ended at interpreter exit inside
  // PyGILState_Ensure unwinds from here (withoutGil), with no destructor in the way.
  const PyGILState_STATE gil = PyGILState_Ensure();
  const bool signalled = PyErr_CheckSignals() != 0;
  PyGILState_Release(gil);
  if (!signalled) return true;
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
      "not from a place in the file), key_path (like 'forces[2].ks', or ''), message (why, without the place), "
      "origin (where the value came from: a set() call, a --set option; or '').",
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
            py::dict("file"_a = pathText(e.file()), "line"_a = e.line(), "column"_a = e.column(),
                     "key_path"_a = text(e.keyPath()), "message"_a = text(e.message()), "origin"_a = text(e.origin())));
    } catch (const SimulationError& e) {
      raise(classes.simulationError, e.what(),
            py::dict("step"_a = e.step(), "time"_a = e.time(), "integrator"_a = std::string(name(e.integrator())),
                     "dt"_a = e.dt(), "reason"_a = text(e.reason())));
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
  py::class_<ScenarioObject>(module, "Scenario",
                             R"doc(A scenario: what `particles run` reads from a YAML file, with settings changed
as `--set` changes them. A Simulation is made from it; changing the scenario afterwards does not
change simulations made before.

    scenario = particles.Scenario.load("scenarios/cloth.yaml", set={"integrator": "rk4", "dt": 0.002})
    scenario.set("forces[1].ks", 80.0)
)doc")
      .def_static(
          "load",
          [](const std::filesystem::path& path, const py::object& set, const py::object& style) {
            // Reading may wait on a pipe's writer: the other Python threads go on meanwhile.
            Scenario scenario = withoutGil([&] { return Scenario::load(path.string()); });
            setStyleOf(scenario, style, "Scenario.load");
            setAll(scenario, set);
            return ScenarioObject(std::move(scenario));
          },
          "path"_a, py::kw_only(), "set"_a = py::none(), "style"_a = py::none(),
          R"doc(Loads a scenario file (YAML). `set` is a mapping of key path → value, applied in
order as `--set KEY=VALUE` would be: key paths like "forces[2].ks", or the shorthands
"integrator", "dt", "duration" and "implicit_solver". `style` is set_style()'s. Raises
ScenarioError naming the file, line, column and key. A FIFO with no writer is refused at once.)doc")
      .def_static(
          "from_text",
          [](std::string_view yaml, const std::string& label, const py::object& set, const py::object& style) {
            Scenario scenario = withoutGil([&] { return Scenario::fromText(yaml, label); });
            setStyleOf(scenario, style, "Scenario.from_text");
            setAll(scenario, set);
            return ScenarioObject(std::move(scenario));
          },
          "yaml"_a, "label"_a = "<text>", py::kw_only(), "set"_a = py::none(), "style"_a = py::none(),
          "A scenario from YAML text (at most 64 MiB, as a file); `label` stands for the file name in messages. "
          "`set` and `style` as in load().")
      .def(
          "set",
          [](py::object self, std::string_view path, const py::handle& value) {
            scenarioOf(self.cast<ScenarioObject&>()).set(path, settingText(path, value));
            return self;
          },
          "path"_a, "value"_a,
          R"doc(Changes one setting as `--set PATH=VALUE` does and returns the scenario, so that
calls chain. The value: a str is YAML text as --set takes it ("[50, 2]"); a bool, int, float
(exactly: it reads back as the same double), None, list, tuple, dict or numpy scalar or array is
written as the YAML of that value. Checked at once: a bad key or value raises ScenarioError and
leaves the scenario as it was.)doc")
      .def(
          "set_style",
          [](py::object self, const py::handle& style) {
            setStyleOf(scenarioOf(self.cast<ScenarioObject&>()), style, "Scenario.set_style");
            return self;
          },
          "style"_a,
          R"doc(Merges a style over the scenario's own `style` section, as `particles render --style
FILE` merges a style file, and returns the scenario. `style` is a dict of the section's keys, as
YAML writes them ({"particles": {"color_by": "speed", "range": [0, 2]}, "colorbar": {"for":
"particles"}, "select": [{"particles": "bob", "trail": {"seconds": 2}}]}; None in it takes the
scenario's key away, as `~`), or a style file's text (str); None or an empty one takes the style
away. A later call replaces this one; it is merged before every set() value. Checked at once with
the file's checks: a bad key or value raises ScenarioError (file "style", its key_path the dict's
key, without a line or column for a dict) and leaves the scenario as it was. Simulations made
afterwards draw it.)doc")
      .def(
          "copy", [](const ScenarioObject& s) { return ScenarioObject(scenarioOf(s)); }, "An independent copy.")
      .def("__copy__", [](const ScenarioObject& s) { return ScenarioObject(scenarioOf(s)); })
      .def(
          "__deepcopy__", [](const ScenarioObject& s, const py::handle&) { return ScenarioObject(scenarioOf(s)); },
          "memo"_a)
      .def("summary", scenarioText(&Scenario::summary),
           "What `particles check` prints for it: one line naming its contents, integrator, dt and duration.")
      .def_property_readonly("name", scenarioText(&Scenario::name), "The scenario's name.")
      .def_property_readonly("description", scenarioText(&Scenario::description), "Its description, or ''.")
      .def_property_readonly("file", scenarioPath(&Scenario::file),
                             "The path it was loaded from, or from_text's label.")
      .def_property_readonly("integrator", scenarioChoice(&Scenario::integrator),
                             "The integrator, as scenarios name it (rk4, ...).")
      .def_property_readonly("dt", scenarioValue(&Scenario::dt), "The time step, s.")
      .def_property_readonly("duration", scenarioValue(&Scenario::duration),
                             "The simulated seconds `particles run` covers.")
      .def_property_readonly("steps", scenarioValue(&Scenario::steps), "The steps of dt that cover the duration.")
      .def_property_readonly("fps", scenarioValue(&Scenario::fps), "Frames per simulated second when rendered.")
      .def_property_readonly("particle_count", scenarioValue(&Scenario::particleCount), "How many particles it has.")
      .def_property_readonly("body_count", scenarioValue(&Scenario::bodyCount), "How many rigid bodies it has.")
      .def("__repr__", [](const ScenarioObject& o) {
        const Scenario& s = scenarioOf(o);
        return text(describeScenario(s));
      });
}

}  // namespace particles::python

PYBIND11_MODULE(_particles, module) {
  using namespace particles::python;
  module.doc() = "particles' C++ library (include/particles/); import particles, not this module.";
  module.attr("__version__") = particles::version();
  rememberMainThread();
  bindErrors(module);
  bindChoices(module);
  bindScenario(module);
  bindSimulation(module);
  bindRendering(module);
  bindGolden(module);
}
