#pragma once
// The Python module particles._particles (pybind11), built on the public C++ API alone
// (include/particles/): what Python sees of it is described in python/particles/_particles.pyi and
// docs/api.md. One file per part: module.cpp (the module, errors, Scenario, the conversions below),
// yaml_text.cpp (Python values as YAML: set()'s values, style dicts), style.cpp (a Scenario's
// style), simulation.cpp (Simulation and its numpy views), rendering.cpp (Renderer, frames,
// VideoWriter), golden.cpp (golden checks).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <chrono>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__GLIBCXX__)
#include <cxxabi.h>
#endif

#include <particles/particles.hpp>

namespace particles::python {

namespace py = pybind11;

void bindErrors(py::module_& module);
void bindScenario(py::module_& module);
void bindSimulation(py::module_& module);
void bindRendering(py::module_& module);
void bindGolden(py::module_& module);

// Text from the library as a Python str. Scenarios are read as bytes, so a name, a description or
// a message quoting them may hold bytes that are not UTF-8 (a Latin-1 file): those are shown as
// \xNN (backslashreplace) instead of the str failing with UnicodeDecodeError.
py::str text(std::string_view bytes);
// A path from the library as os.fsdecode gives it: bytes that are not UTF-8 as surrogates
// (surrogateescape), so that the str names the same file when given back.
py::str pathText(std::string_view bytes);
// Each as text().
py::list textList(const std::vector<std::string>& items);

// A whole number from Python: an int or anything with __index__ (numpy's integers), not a bool
// and not a float. One beyond `long long`'s range becomes its largest or smallest, which is out of
// every range a call takes (the call then says so). ArgumentError "CALL: WHAT is a whole number,
// not TYPE" otherwise.
long long wholeNumber(const py::handle& value, const char* call, const char* what);
// The same within int's range; ArgumentError naming the value otherwise.
int wholeInt(const py::handle& value, const char* call, const char* what);
// The name of a value's type, for messages.
std::string typeName(const py::handle& value);

// A value Python gives as YAML, written as the text the library reads, exactly: at the top a str
// is YAML text as written (`"[50, 2]"`), inside a list or dict a str is a string (double-quoted);
// bool, int (or anything with __index__), float (its repr, the shortest text that reads back as the
// same double), None (`null`; at the top, nothing), lists and tuples, dicts and other mappings with
// str keys, and numpy's scalars and arrays (as their .item() and .tolist(), which widen exactly).
// ArgumentError "CALL: … the value of PATH …" for anything else, a float that is not finite, a lone
// surrogate, or nesting deeper than 64.
std::string yamlText(const py::handle& value, std::string_view call, std::string_view path);

// Scenario.set_style's and the style= of load() and from_text(): a dict (the style section's keys,
// as yamlText writes it), a style file's text (str), or None or an empty dict or str (no style),
// given to Scenario::setStyle. A dict's errors name "style" and the key path without a line or
// column, as the C++ Style's do; `call` names the Python call in ArgumentError.
void setStyleOf(Scenario& scenario, const py::handle& style, const char* call);
// A str as a message quotes it: at most 80 characters of it, with its size in bytes when cut.
std::string quoted(const std::string& value);

// A choice (include/particles/choices.hpp) given as its name ("light", "backward_euler") or as a
// member of the module's enum (particles.Theme.light). ArgumentError naming `what` and the names
// otherwise.
template <class Choice, size_t N>
Choice choiceOf(const py::handle& value, const char* call, const char* what, const Choice (&values)[N]) {
  if (py::isinstance<py::str>(value)) {
    if (const std::optional<Choice> chosen = fromName<Choice>(value.cast<std::string>())) return *chosen;
  } else if (py::isinstance<Choice>(value)) {
    return value.cast<Choice>();
  }
  std::string names;
  for (const Choice choice : values) names += (names.empty() ? "" : ", ") + std::string(name(choice));
  const std::string given = py::isinstance<py::str>(value) ? quoted(value.cast<std::string>()) : "a " + typeName(value);
  throw ArgumentError(std::string(call) + ": " + what + " takes " + names + " (or its enum's members), not " + given);
}
inline constexpr Integrator kIntegrators[] = {
    Integrator::euler,  Integrator::midpoint,      Integrator::rk4, Integrator::symplecticEuler,
    Integrator::verlet, Integrator::backwardEuler, Integrator::bdf2};
inline constexpr Theme kThemes[] = {Theme::dark, Theme::light};
inline constexpr Background kBackgrounds[] = {Background::theme, Background::transparent};
inline constexpr Raster kRasters[] = {Raster::automatic, Raster::triangles, Raster::tiles, Raster::resident,
                                      Raster::cpu};
inline constexpr GlBackend kGlBackends[] = {GlBackend::automatic, GlBackend::egl, GlBackend::osmesa};
inline constexpr golden::Outcome kOutcomes[] = {golden::Outcome::passed, golden::Outcome::failed,
                                                golden::Outcome::missing, golden::Outcome::error};
// The module's enums: each member named as name() spells it (Raster.auto).
void bindChoices(py::module_& module);

// What pybind11 gives `Cls.__new__(Cls)`: a Python object whose C++ value no constructor made
// (pybind11 allocates its storage on first use, uninitialised), so that reading it crashes. Every
// class of this module is therefore a struct with this base, which keeps the address of each
// object from its constructor to its destructor, and every method first asks require(): an
// address no constructor made is refused with ArgumentError. Only addresses are compared.
class Registered {
 public:
  Registered();
  Registered(const Registered&);
  Registered& operator=(const Registered&) = default;
  ~Registered();
  // ArgumentError unless `self` is a constructed object; `cls` names its Python class.
  static void require(const void* self, const char* cls);
};

// A value the module hands to Python as a class of its own (a Scenario, an Energy, a golden check's
// results), behind the check above.
template <class T>
struct Object : Registered {
  T value;
  explicit Object(T v) : value(std::move(v)) {}
};
// The value of a constructed Object, else ArgumentError (Registered::require).
template <class T>
T& valueOf(Object<T>& object, const char* cls) {
  Registered::require(&object, cls);
  return object.value;
}
template <class T>
const T& valueOf(const Object<T>& object, const char* cls) {
  Registered::require(&object, cls);
  return object.value;
}

using ScenarioObject = Object<Scenario>;

// A Python Simulation: the C++ one, shared with the numpy views of its state (a view keeps the
// state's memory alive: one may outlive close()), and the renderer of its last render() call.
struct SimulationHandle : Registered {
  SimulationHandle(std::shared_ptr<Simulation> s) : simulation(std::move(s)) {}
  std::shared_ptr<Simulation> simulation;  // null after close()
  std::optional<std::pair<RenderSettings, Renderer>> lastRenderer;  // with the settings it was made with

  // The simulation, or ArgumentError when it was closed (or never made). `call` names the method.
  const std::shared_ptr<Simulation>& get(const char* call) const;
};

// A frame as Python gets it: a particles.Frame (an (h, w, 4) uint8 numpy array) owning the pixels.
py::object frameOf(Image&& image);
// A numpy-like (h, w, 4) or (h, w, 3) uint8 array as an Image; ArgumentError for another shape or
// dtype, MemoryError when numpy cannot make its contiguous copy. `call` names the method.
Image imageOf(const py::handle& frame, const char* call);

// Runs call() with the GIL released and returns what it returns. The GIL is taken back by a plain
// call, not by a destructor as py::gil_scoped_release does: at interpreter exit CPython ends a
// daemon thread that asks for the GIL back (pthread_exit, unwinding with abi::__forced_unwind), and
// that unwinding through a destructor, which is noexcept, aborted the process. Here the thread ends
// quietly (pybind11 passes the unwinding on too).
template <class Call>
auto withoutGil(Call&& call) -> decltype(call()) {
  using Result = decltype(call());
  PyThreadState* const state = PyEval_SaveThread();
  std::exception_ptr failure;
  std::optional<std::conditional_t<std::is_void_v<Result>, char, Result>> result;
  try {
    if constexpr (std::is_void_v<Result>) {
      call();
    } else {
      result.emplace(call());
    }
  }
#if defined(__GLIBCXX__)
  catch (abi::__forced_unwind&) {  // the thread is ending (InterruptCheck asked for the GIL): let it
    throw;
  }
#endif
  catch (...) {
    failure = std::current_exception();
  }
  PyEval_RestoreThread(state);
  if (failure) std::rethrow_exception(failure);
  if constexpr (!std::is_void_v<Result>) return std::move(*result);
}

// Stops a long call at Ctrl-C: made with the GIL held, asked without it between steps (from the
// main thread only, where Python runs signal handlers) at most every 50 ms. When a handler raised,
// the call stops at a whole step and raiseIfInterrupted() (with the GIL) raises that exception.
class InterruptCheck {
 public:
  InterruptCheck();
  bool keepGoing();
  void raiseIfInterrupted() const;

 private:
  bool mainThread_;
  bool interrupted_ = false;
  std::chrono::steady_clock::time_point next_;
};
// The main thread's id, taken when the module is imported (threading.main_thread()).
void rememberMainThread();

}  // namespace particles::python
