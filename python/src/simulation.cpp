// particles._particles: Simulation and the numpy views of its state (python/src/bindings.hpp).
#include <pybind11/stl.h>

#include <climits>
#include <cstring>
#include <type_traits>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"

namespace particles::python {

using namespace pybind11::literals;

namespace {

using SharedSimulation = std::shared_ptr<Simulation>;

py::handle bodyDtype;  // x, y, angle, omega as float64: BodyState's layout

// An (n, 2) float64 view of `values` (n × 2 doubles that `simulation` owns), read-only, that keeps
// the simulation alive: its base is a capsule holding a share of it, and a capsule has no buffer
// of its own, so numpy refuses to make the view writeable again.
py::array stateView(const SharedSimulation& simulation, std::span<const double> values) {
  py::capsule keeper(new SharedSimulation(simulation), [](void* share) { delete static_cast<SharedSimulation*>(share); });
  const py::ssize_t rows = py::ssize_t(values.size() / 2);
  py::array view(py::dtype::of<double>(), {rows, py::ssize_t(2)},
                 {py::ssize_t(2 * sizeof(double)), py::ssize_t(sizeof(double))}, values.data(), keeper);
  view.attr("setflags")("write"_a = false);
  return view;
}

// A particle named by its index or its name (the --trace names).
int particleOf(const Simulation& simulation, const py::handle& particle, const char* call) {
  if (py::isinstance<py::str>(particle)) return simulation.particleIndex(particle.cast<std::string>());
  if (py::isinstance<py::bool_>(particle) || !PyIndex_Check(particle.ptr())) {
    throw ArgumentError(std::string(call) +
                        ": a particle is named by its index (an int, numpy's too) or its name "
                        "(str), not " +
                        typeName(particle));
  }
  return wholeInt(particle, call, "a particle's index");  // the C++ call checks the range and says it
}

Point pointOf(const py::handle& value, const char* what) {
  const auto xy = py::reinterpret_borrow<py::object>(value);
  if (!py::isinstance<py::sequence>(xy) || py::isinstance<py::str>(xy) || py::len(xy) != 2) {
    throw ArgumentError(std::string(what) + " takes (x, y): a sequence of two numbers");
  }
  const py::sequence pair = xy.cast<py::sequence>();
  const auto number = [&](const py::handle& v) {
    if (py::isinstance<py::bool_>(v) || py::isinstance<py::str>(v)) throw py::cast_error();
    return v.cast<double>();  // a float, an int, numpy's scalars: anything with __float__
  };
  try {
    return Point{number(pair[0]), number(pair[1])};
  } catch (const py::cast_error&) {
    throw ArgumentError(std::string(what) + " takes (x, y): a sequence of two numbers");
  }
}

py::tuple tupleOf(Point p) { return py::make_tuple(p.x, p.y); }

// A thread count: None is default_threads(); the C++ call checks the range and says it.
int threadsOf(const py::object& threads, const char* call) {
  if (threads.is_none()) return defaultThreads();
  return wholeInt(threads, call, "threads (or None for default_threads())");
}

// Runs a stepping call with the GIL released, stopping at Ctrl-C (InterruptCheck).
template <class Call>
void stepInterruptibly(const SharedSimulation& simulation, Call&& call) {
  InterruptCheck check;
  withoutGil([&] { call(*simulation, [&check] { return check.keepGoing(); }); });
  check.raiseIfInterrupted();
}

std::string describeSimulation(const SimulationHandle& handle) {
  Registered::require(&handle, "Simulation");
  if (!handle.simulation) return "<particles.Simulation, closed>";
  const Simulation& s = *handle.simulation;
  return "<particles.Simulation time = " + py::repr(py::float_(s.time())).cast<std::string>() + " s after " +
         std::to_string(s.steps()) + " steps: " + std::string(name(s.integrator())) +
         ", dt = " + py::repr(py::float_(s.dt())).cast<std::string>() + " s, " + std::to_string(s.particleCount()) +
         " particles, " + std::to_string(s.bodyCount()) + " bodies, " + std::to_string(s.threads()) + " threads>";
}

void bindEnergy(py::module_& module) {
  py::class_<Object<Energy>>(module, "Energy",
                             "The energy now, J: kinetic, potential (gravity, springs, the mouse's spring, the "
                             "colliders' penalty) and their total.")
      .def_property_readonly(
          "kinetic", [](const Object<Energy>& e) { return valueOf(e, "Energy").kinetic; },
          "The particles' and the rigid bodies' kinetic energy, J.")
      .def_property_readonly(
          "potential", [](const Object<Energy>& e) { return valueOf(e, "Energy").potential; },
          "Gravity, springs, the mouse's spring, the colliders' penalty, J.")
      .def_property_readonly(
          "total", [](const Object<Energy>& e) { return valueOf(e, "Energy").total; }, "kinetic + potential, J.")
      .def("__repr__", [](const Object<Energy>& object) {
        const Energy& e = valueOf(object, "Energy");
        return "Energy(kinetic=" + py::repr(py::float_(e.kinetic)).cast<std::string>() +
               ", potential=" + py::repr(py::float_(e.potential)).cast<std::string>() +
               ", total=" + py::repr(py::float_(e.total)).cast<std::string>() + ")";
      });
}

// Stepping and the clock: step(), advance(), advance_to(), time, dt, the integrator and the threads.
void addSimulationClock(py::class_<SimulationHandle>& simulationClass) {
  simulationClass
      .def(
          "step",
          [](SimulationHandle& handle, const py::handle& count) {
            const SharedSimulation simulation = handle.get("step");
            const long long n = wholeNumber(count, "Simulation.step", "n");
            const long steps = n > LONG_MAX ? LONG_MAX : n < LONG_MIN ? LONG_MIN : long(n);
            stepInterruptibly(simulation, [steps](Simulation& s, auto keepGoing) { s.step(steps, keepGoing); });
          },
          "n"_a = 1,
          "Takes n steps of dt (n >= 0). Raises SimulationError when a step blows up; the simulation stays at the "
          "last good state.")
      .def(
          "advance",
          [](SimulationHandle& handle, double seconds) {
            const SharedSimulation simulation = handle.get("advance");
            stepInterruptibly(simulation, [seconds](Simulation& s, auto keepGoing) { s.advance(seconds, keepGoing); });
          },
          "seconds"_a,
          R"doc(Moves the simulation's clock on by `seconds` (finite, >= 0) and steps to the last
multiple of dt at or before it. The clock keeps what a step could not cover, so advance(1 / fps)
once per frame gives the frames of `particles render` at that fps, whatever dt is.)doc")
      .def(
          "advance_to",
          [](SimulationHandle& handle, double t) {
            const SharedSimulation simulation = handle.get("advance_to");
            stepInterruptibly(simulation, [t](Simulation& s, auto keepGoing) { s.advanceTo(t, keepGoing); });
          },
          "t"_a,
          "Steps to the last multiple of dt at or before time t, s (finite, not behind .time): the step "
          "`particles render` draws at t, so advance_to(k / fps) is its frame k.")
      .def_property_readonly(
          "time", [](const SimulationHandle& h) { return h.get("time")->time(); },
          "The simulated time, s: t0 + k*dt after k steps.")
      .def_property_readonly(
          "steps", [](const SimulationHandle& h) { return h.get("steps")->steps(); }, "Steps taken so far.")
      .def_property_readonly(
          "dt", [](const SimulationHandle& h) { return h.get("dt")->dt(); }, "The time step, s.")
      .def_property_readonly(
          "integrator", [](const SimulationHandle& h) { return std::string(name(h.get("integrator")->integrator())); },
          "The integrator, as scenarios name it.")
      .def_property(
          "threads", [](const SimulationHandle& h) { return h.get("threads")->threads(); },
          [](SimulationHandle& h, const py::object& threads) {
            h.get("threads")->setThreads(threadsOf(threads, "Simulation.threads"));
          },
          "The threads a step runs on (1 to 1024; the bits do not depend on it).")
      .def(
          "set_threads",
          [](SimulationHandle& h, const py::object& threads) {
            h.get("set_threads")->setThreads(threadsOf(threads, "Simulation.set_threads"));
          },
          "threads"_a, "The threads the next steps run on (1 to 1024; None: default_threads()), as .threads = n.");
}

// The particles' and bodies' state: numpy views, copies, one point at a time, and names.
void addSimulationState(py::class_<SimulationHandle>& simulationClass) {
  simulationClass
      .def_property_readonly(
          "particle_count", [](const SimulationHandle& h) { return h.get("particle_count")->particleCount(); },
          "How many particles it has.")
      .def_property_readonly(
          "body_count", [](const SimulationHandle& h) { return h.get("body_count")->bodyCount(); },
          "How many rigid bodies it has.")
      .def_property_readonly(
          "positions",
          [](const SimulationHandle& h) {
            const SharedSimulation& s = h.get("positions");
            return stateView(s, s->positions());
          },
          R"doc(The particles' positions, m: a read-only (N, 2) float64 numpy view of the state,
not a copy. It shows the state as the simulation steps (np.array(sim.positions) keeps a copy). The
view keeps the state's memory alive: after close() it still reads the last state.)doc")
      .def_property_readonly(
          "velocities",
          [](const SimulationHandle& h) {
            const SharedSimulation& s = h.get("velocities");
            return stateView(s, s->velocities());
          },
          "The particles' velocities, m/s: a read-only (N, 2) float64 view, as positions.")
      .def_property_readonly(
          "bodies",
          [](const SimulationHandle& h) {
            const std::vector<BodyState> bodies = h.get("bodies")->bodies();
            py::array out = py::module_::import("numpy").attr("zeros")(bodies.size(), bodyDtype);
            if (!bodies.empty()) std::memcpy(out.mutable_data(), bodies.data(), bodies.size() * sizeof(BodyState));
            return out;
          },
          "The rigid bodies now: a structured array (a copy) with fields x, y (m), angle (rad) and omega (rad/s).")
      .def(
          "body",
          [](const SimulationHandle& h, const py::handle& index) {
            const BodyState b = h.get("body")->body(wholeInt(index, "Simulation.body", "a body's index"));
            return py::make_tuple(b.x, b.y, b.angle, b.omega);
          },
          "body"_a, "A rigid body's (x, y, angle, omega): m, m, rad, rad/s.")
      .def(
          "position",
          [](const SimulationHandle& h, const py::handle& p) {
            const Simulation& s = *h.get("position");
            return tupleOf(s.position(particleOf(s, p, "Simulation.position")));
          },
          "particle"_a, "A particle's (x, y), m; the particle by index or name.")
      .def(
          "velocity",
          [](const SimulationHandle& h, const py::handle& p) {
            const Simulation& s = *h.get("velocity");
            return tupleOf(s.velocity(particleOf(s, p, "Simulation.velocity")));
          },
          "particle"_a, "A particle's (vx, vy), m/s; the particle by index or name.")
      .def(
          "set_position",
          [](SimulationHandle& h, const py::handle& p, const py::handle& xy) {
            Simulation& s = *h.get("set_position");
            s.setPosition(particleOf(s, p, "Simulation.set_position"), pointOf(xy, "Simulation.set_position"));
          },
          "particle"_a, "xy"_a,
          "Moves a particle (by index or name) to (x, y) where the next step starts; constraints pull it back.")
      .def(
          "set_velocity",
          [](SimulationHandle& h, const py::handle& p, const py::handle& v) {
            Simulation& s = *h.get("set_velocity");
            s.setVelocity(particleOf(s, p, "Simulation.set_velocity"), pointOf(v, "Simulation.set_velocity"));
          },
          "particle"_a, "velocity"_a, "Sets a particle's velocity (vx, vy), m/s.")
      .def_property_readonly(
          "particle_names",
          [](const SimulationHandle& h) { return textList(h.get("particle_names")->particleNames()); },
          "The particles' names, in index order: the names `particles run --trace` writes.")
      .def_property_readonly(
          "body_names", [](const SimulationHandle& h) { return textList(h.get("body_names")->bodyNames()); },
          "The rigid bodies' names, in index order.")
      .def(
          "particle_index",
          [](const SimulationHandle& h, const std::string& name) {
            return h.get("particle_index")->particleIndex(name);
          },
          "name"_a, "The index of the particle of that name; ArgumentError (with the closest name) otherwise.")
      .def(
          "body_index",
          [](const SimulationHandle& h, const std::string& name) { return h.get("body_index")->bodyIndex(name); },
          "name"_a, "The index of the rigid body of that name.");
}

// The scenario's mice, taken over from Python.
void addSimulationMice(py::class_<SimulationHandle>& simulationClass) {
  simulationClass
      .def_property_readonly(
          "mouse_count", [](const SimulationHandle& h) { return h.get("mouse_count")->mouseCount(); },
          "How many mice the scenario has (its `mouse` section).")
      .def(
          "set_mouse_target",
          [](SimulationHandle& h, const py::handle& xy, const py::handle& mouse) {
            h.get("set_mouse_target")
                ->setMouseTarget(pointOf(xy, "Simulation.set_mouse_target"),
                                 wholeInt(mouse, "Simulation.set_mouse_target", "mouse"));
          },
          "xy"_a, "mouse"_a = 0,
          R"doc(Takes over a mouse of the scenario: from now on it pulls its grabbed point towards
(x, y), its scripted path and time window replaced, until release_mouse(). A scenario without a
mouse can be given one: Scenario.set("mouse", "[{grab: 'cloth[24][12]', from: 0, to: 1, path: [[0, 0]], ks: 2}]").)doc")
      .def(
          "release_mouse",
          [](SimulationHandle& h, const py::handle& mouse) {
            h.get("release_mouse")->releaseMouse(wholeInt(mouse, "Simulation.release_mouse", "mouse"));
          },
          "mouse"_a = 0, "Lets the mouse go: it pulls no more.")
      .def(
          "mouse_target",
          [](const SimulationHandle& h, const py::handle& mouse) -> py::object {
            const std::optional<Point> at =
                h.get("mouse_target")->mouseTarget(wholeInt(mouse, "Simulation.mouse_target", "mouse"));
            if (!at) return py::none();
            return tupleOf(*at);
          },
          "mouse"_a = 0, "Where the mouse pulls now, (x, y); None while it holds no point.");
}

// What `particles run --stats` reports: the energy, the constraint error, the penetration.
void addSimulationMeasures(py::class_<SimulationHandle>& simulationClass) {
  simulationClass
      .def(
          "energy", [](const SimulationHandle& h) { return Object<Energy>(h.get("energy")->energy()); },
          "The energy now (Energy).")
      .def(
          "constraint_error", [](const SimulationHandle& h) { return h.get("constraint_error")->constraintError(); },
          "The largest violation of a constraint now, m.")
      .def(
          "penetration", [](const SimulationHandle& h) { return h.get("penetration")->penetration(); },
          "How deep the deepest point is inside a collider now, m.");
}

// close(), the context manager, repr().
void addSimulationLifetime(py::class_<SimulationHandle>& simulationClass) {
  simulationClass
      .def(
          "close",
          [](SimulationHandle& h) {
            Registered::require(&h, "Simulation");
            h.lastRenderer.reset();
            h.simulation.reset();
          },
          "Frees the simulation (views of its state keep their memory). Later calls raise ArgumentError.")
      .def_property_readonly(
          "closed",
          [](const SimulationHandle& h) {
            Registered::require(&h, "Simulation");
            return !h.simulation;
          },
          "Whether close() was called.")
      .def("__enter__", [](py::object self) { return self; })
      .def(
          "__exit__",
          [](SimulationHandle& h, const py::handle&, const py::handle&, const py::handle&) {
            Registered::require(&h, "Simulation");
            h.lastRenderer.reset();
            h.simulation.reset();
            return false;
          },
          "exc_type"_a, "exc"_a, "traceback"_a)
      .def("__repr__", &describeSimulation);
}

}  // namespace

const std::shared_ptr<Simulation>& SimulationHandle::get(const char* call) const {
  Registered::require(this, "Simulation");
  if (!simulation) throw ArgumentError(std::string("Simulation.") + call + ": the simulation was closed");
  return simulation;
}

void bindSimulation(py::module_& module) {
  // sim.bodies' fields, as a numpy dtype made from Python (PYBIND11_NUMPY_DTYPE reaches into pybind11's detail).
  static_assert(sizeof(BodyState) == 4 * sizeof(double) && std::is_standard_layout_v<BodyState>);
  py::list fields;
  for (const char* field : {"x", "y", "angle", "omega"}) fields.append(py::make_tuple(field, "f8"));
  bodyDtype = py::module_::import("numpy").attr("dtype")(fields).release();
  bindEnergy(module);

  module.def("default_threads", &defaultThreads,
             "The thread count a Simulation takes with threads=None, as `particles run` without --threads: "
             "PARTICLES_THREADS when set, else the CPUs this process may use.");

  py::class_<SimulationHandle> simulation(
      module, "Simulation",
      R"doc(A simulation made from a Scenario, at t = 0: steps it with the scenario's
integrator and time step, reads and changes its state, and draws it. The steps give the same bits
as `particles run` for the same scenario, on any number of threads.

    sim = particles.Simulation(particles.Scenario.load("scenarios/cloth.yaml"), threads=2)
    sim.advance(1.0)
    sim.positions[0]          # x, y of the first particle, m

Stepping and rendering release the GIL: Python threads can drive simulations of their own at
once. One Simulation is driven by one thread at a time; a second thread's call while one is under
way raises particles.Error. Ctrl-C stops a long step() or advance() at a whole step.
A Simulation is a context manager: `with particles.Simulation(s) as sim:` closes it at the end.)doc");
  simulation.def(py::init([](const ScenarioObject& scenario, const py::object& threads) {
                   const Scenario& s = valueOf(scenario, "Scenario");
                   return SimulationHandle(std::make_shared<Simulation>(s, threadsOf(threads, "Simulation")));
                 }),
                 "scenario"_a, "threads"_a = py::none(),
                 "A simulation of `scenario` at t = 0 on `threads` threads (1 to 1024; None: default_threads()).");
  addSimulationClock(simulation);
  addSimulationState(simulation);
  addSimulationMice(simulation);
  addSimulationMeasures(simulation);
  addSimulationLifetime(simulation);
}

}  // namespace particles::python
