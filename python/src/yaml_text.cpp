// particles._particles: Python values as the YAML text the library reads (python/src/bindings.hpp):
// Scenario.set's values and set_style's dicts.
#include <cmath>
#include <string>
#include <string_view>

#include "bindings.hpp"

namespace particles::python {

namespace {

// Where a value was given, for messages: the call and the key path (or argument) it is the value of.
struct Place {
  std::string call;
  std::string_view path;
};

// The deepest a value's lists and dicts may nest: a list that holds itself is
// refused instead of recursing until the stack runs out.
constexpr int kMostNesting = 64;

// A str as a YAML double-quoted scalar: `"` and `\` escaped, control characters as \xNN or \uNNNN,
// everything else as its UTF-8.
void appendQuoted(std::string& out, const py::handle& str, const Place& at) {
  Py_ssize_t size = 0;
  const char* utf8 = PyUnicode_AsUTF8AndSize(str.ptr(), &size);
  if (utf8 == nullptr) {
    PyErr_Clear();
    throw ArgumentError(at.call + ": a text in the value of " + std::string(at.path) +
                        " is not valid Unicode (a lone surrogate)");
  }
  out += '"';
  for (const char c : std::string_view(utf8, size_t(size))) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7F) {
      const char* const hex = "0123456789abcdef";
      out += "\\x";
      out += hex[byte >> 4];
      out += hex[byte & 0xF];
    } else {
      out += c;
    }
  }
  out += '"';
}

// A value Python gives Scenario.set as the YAML text --set would take, exactly: at the top a str
// is YAML text as written (`"[50, 2]"`), inside a list or dict a str is a string; bool, int (or
// anything with __index__), float (its repr, the shortest text that reads back as the same
// double), None, lists and tuples, dicts and other mappings, and numpy's scalars and arrays (as
// their .item() and .tolist(), which widen exactly). ArgumentError for anything else.
void appendYaml(std::string& out, const py::handle& value, const Place& at, int depth) {
  if (depth > kMostNesting) {
    throw ArgumentError(at.call + ": the value of " + std::string(at.path) + " nests more than " +
                        std::to_string(kMostNesting) + " lists or dicts deep");
  }
  static const py::handle numpyGeneric = py::object(py::module_::import("numpy").attr("generic")).release();
  static const py::handle numpyArray = py::object(py::module_::import("numpy").attr("ndarray")).release();
  static const py::handle mapping = py::object(py::module_::import("collections.abc").attr("Mapping")).release();
  if (value.is_none()) {
    out += depth == 0 ? "" : "null";  // at the top: no value, which the loader refuses by name
  } else if (py::isinstance<py::bool_>(value)) {
    out += value.ptr() == Py_True ? "true" : "false";
  } else if (py::isinstance<Integrator>(value)) {  // particles.Integrator.rk4: its name
    out += name(value.cast<Integrator>());
  } else if (py::isinstance(value, numpyGeneric)) {
    appendYaml(out, value.attr("item")(), at, depth);
  } else if (py::isinstance(value, numpyArray)) {
    appendYaml(out, value.attr("tolist")(), at, depth);
  } else if (py::isinstance<py::float_>(value)) {
    const double number = PyFloat_AsDouble(value.ptr());
    if (!std::isfinite(number)) {
      throw ArgumentError(at.call + ": " + std::string(at.path) + " must be finite, got " +
                          py::repr(value).cast<std::string>());
    }
    out += py::repr(value).cast<std::string>();
  } else if (PyIndex_Check(value.ptr())) {
    out += py::str(py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()))).cast<std::string>();
  } else if (py::isinstance<py::str>(value)) {
    if (depth == 0) {
      out += value.cast<std::string>();
    } else {
      appendQuoted(out, value, at);
    }
  } else if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    out += '[';
    bool first = true;
    for (const py::handle item : value) {
      if (!first) out += ", ";
      first = false;
      appendYaml(out, item, at, depth + 1);
    }
    out += ']';
  } else if (py::isinstance(value, mapping)) {
    out += '{';
    bool first = true;
    for (const py::handle item : value.attr("items")()) {
      const py::tuple pair = py::reinterpret_borrow<py::tuple>(item);
      if (!py::isinstance<py::str>(pair[0])) {
        throw ArgumentError(at.call + ": the keys of a dict in the value of " + std::string(at.path) +
                            " are str, not " + typeName(pair[0]));
      }
      if (!first) out += ", ";
      first = false;
      appendQuoted(out, pair[0], at);
      out += ": ";
      appendYaml(out, pair[1], at, depth + 1);
    }
    out += '}';
  } else {
    throw ArgumentError(at.call + ": the value of " + std::string(at.path) +
                        " must be a str, int, float, bool, None, a list, tuple or dict of those, or a numpy scalar or "
                        "array; not " +
                        typeName(value));
  }
}

}  // namespace

std::string yamlText(const py::handle& value, std::string_view call, std::string_view path) {
  std::string out;
  appendYaml(out, value, Place{std::string(call), path}, 0);
  return out;
}

}  // namespace particles::python
