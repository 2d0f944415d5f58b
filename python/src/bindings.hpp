#pragma once
// The Python module particles._particles (pybind11), built on the public C++ API alone
// (include/particles/): what Python sees of it is described in python/particles/_particles.pyi and
// docs/api.md. One file per part: module.cpp (the module, errors, Scenario), simulation.cpp
// (Simulation and its numpy views), rendering.cpp (Renderer, frames, VideoWriter), golden.cpp
// (golden checks).

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include <particles/particles.hpp>

namespace particles::python {

namespace py = pybind11;

void bindErrors(py::module_& module);
void bindScenario(py::module_& module);
void bindSimulation(py::module_& module);
void bindRendering(py::module_& module);
void bindGolden(py::module_& module);

// A Python Simulation: the C++ one, shared with the numpy views of its state (a view keeps the
// state's memory alive: one may outlive close()), and the renderer of its last render() call.
struct SimulationHandle {
  std::shared_ptr<Simulation> simulation;  // null after close()
  std::optional<std::pair<RenderSettings, Renderer>> lastRenderer;  // with the settings it was made with

  // The simulation, or particles.Error when it was closed. `call` names the method.
  const std::shared_ptr<Simulation>& get(const char* call) const;
};

// A frame as Python gets it: a particles.Frame (an (h, w, 4) uint8 numpy array) owning the pixels.
py::object frameOf(Image&& image);
// A numpy-like (h, w, 4) or (h, w, 3) uint8 array as an Image; ArgumentError for another shape or
// dtype. `call` names the method in the message.
Image imageOf(const py::handle& frame, const char* call);

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
