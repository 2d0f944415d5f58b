// particles._particles: Simulation and the numpy views of its state (python/src/bindings.hpp).
#include <pybind11/stl.h>

#include <climits>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bindings.hpp"

namespace particles::python {

using namespace pybind11::literals;

namespace {

using SharedSimulation = std::shared_ptr<Simulation>;

// An (n, 2) float64 view of `values` (n × 2 doubles that `simulation` owns), read-only, that keeps
// the simulation alive: its base is a capsule holding a share of it, and a capsule has no buffer
// of its own, so numpy refuses to make the view writeable again.
py::array stateView(const SharedSimulation& simulation, std::span<const double> values) {
  py::capsule keeper(new SharedSimulation(simulation), [](void* share) { delete static_cast<SharedSimulation*>(share); });
  const py::ssize_t rows = py::ssize_t(values.size() / 2);
  py::array view(py::dtype::of<double>(), {rows, py::ssize_t(2)},
                 {py::ssize_t(2 * sizeof(double)), py::ssize_t(sizeof(double))}, values.data(), keeper);
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

// A Python int as a C++ int for a call that checks its range: one beyond int's range becomes
// INT_MAX or INT_MIN, which is out of every range such a call takes.
int clampedToInt(const py::handle& value) {
  int overflow = 0;
  const long long n = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if (overflow > 0 || n > INT_MAX) return INT_MAX;
  if (overflow < 0 || n < INT_MIN) return INT_MIN;
  return int(n);
}

// A particle named by its index or its name (the --trace names).
int particleOf(const Simulation& simulation, const py::handle& particle) {
  if (py::isinstance<py::str>(particle)) return simulation.particleIndex(particle.cast<std::string>());
  if (py::isinstance<py::int_>(particle) && !py::isinstance<py::bool_>(particle)) {
    return clampedToInt(particle);  // the C++ call checks the range and says it
  }
  throw ArgumentError("a particle is named by its index (int) or its name (str), not " +
                      py::str(py::type::handle_of(particle).attr("__name__")).cast<std::string>());
}

Point pointOf(const py::handle& value, const char* what) {
  const auto xy = py::reinterpret_borrow<py::object>(value);
  if (!py::isinstance<py::sequence>(xy) || py::isinstance<py::str>(xy) || py::len(xy) != 2) {
    throw ArgumentError(std::string(what) + " takes (x, y): a sequence of two numbers");
  }
  const py::sequence pair = xy.cast<py::sequence>();
  try {
    return Point{pair[0].cast<double>(), pair[1].cast<double>()};
  } catch (const py::cast_error&) {
    throw ArgumentError(std::string(what) + " takes (x, y): a sequence of two numbers");
  }
}

py::tuple tupleOf(Point p) { return py::make_tuple(p.x, p.y); }

// A thread count: None is default_threads(); the C++ call checks the range and says it.
int threadsOf(const py::object& threads, const char* call) {
  if (threads.is_none()) return defaultThreads();
  if (!py::isinstance<py::int_>(threads) || py::isinstance<py::bool_>(threads)) {
    throw ArgumentError(std::string(call) + ": threads is a whole number, or None for default_threads()");
  }
  return clampedToInt(threads);
}

// Runs a stepping call with the GIL released, stopping at Ctrl-C (InterruptCheck).
template <class Call>
void stepInterruptibly(const SharedSimulation& simulation, Call&& call) {
  InterruptCheck check;
  {
    py::gil_scoped_release released;
    call(*simulation, [&check] { return check.keepGoing(); });
  }
  check.raiseIfInterrupted();
}

std::string describeSimulation(const SimulationHandle& handle) {
  if (!handle.simulation) return "<particles.Simulation, closed>";
  const Simulation& s = *handle.simulation;
  return "<particles.Simulation t = " + py::repr(py::float_(s.time())).cast<std::string>() + " s after " +
         std::to_string(s.steps()) + " steps: " + s.integrator() + ", dt = " + py::repr(py::float_(s.dt())).cast<std::string>() +
         " s, " + std::to_string(s.particleCount()) + " particles, " + std::to_string(s.bodyCount()) + " bodies, " +
         std::to_string(s.threads()) + " threads>";
}

}  // namespace

const std::shared_ptr<Simulation>& SimulationHandle::get(const char* call) const {
  if (!simulation) throw ArgumentError(std::string("Simulation.") + call + ": the simulation was closed");
  return simulation;
}

void bindSimulation(py::module_& module) {
  PYBIND11_NUMPY_DTYPE(BodyState, x, y, angle, omega);  // sim.bodies' fields
  py::class_<Energy>(module, "Energy", "The energy now, J: kinetic, potential (gravity, springs, the mouse's spring, "
                                       "the colliders' penalty) and their total.")
      .def_readonly("kinetic", &Energy::kinetic, "The particles' and the rigid bodies' kinetic energy, J.")
      .def_readonly("potential", &Energy::potential, "Gravity, springs, the mouse's spring, the colliders' penalty, J.")
      .def_readonly("total", &Energy::total, "kinetic + potential, J.")
      .def("__repr__", [](const Energy& e) {
        return "Energy(kinetic=" + py::repr(py::float_(e.kinetic)).cast<std::string>() +
               ", potential=" + py::repr(py::float_(e.potential)).cast<std::string>() +
               ", total=" + py::repr(py::float_(e.total)).cast<std::string>() + ")";
      });

  module.def("default_threads", &defaultThreads,
             "The thread count a Simulation takes with threads=None, as `particles run` without --threads: "
             "PARTICLES_THREADS when set, else the CPUs this process may use.");

  py::class_<SimulationHandle>(module, "Simulation", R"doc(A simulation made from a Scenario, at t = 0: steps it with the scenario's
integrator and time step, reads and changes its state, and draws it. The steps give the same bits
as `particles run` for the same scenario, on any number of threads.

    sim = particles.Simulation(particles.Scenario.load("scenarios/cloth.yaml"), threads=2)
    sim.advance(1.0)
    sim.positions[0]          # x, y of the first particle, m

Stepping and rendering release the GIL: Python threads can drive simulations of their own at
once. One Simulation is driven by one thread at a time; a second thread's call while one is under
way raises particles.Error. Ctrl-C stops a long step() or advance() at a whole step.
A Simulation is a context manager: `with particles.Simulation(s) as sim:` closes it at the end.)doc")
      .def(py::init([](const Scenario& scenario, const py::object& threads) {
             return SimulationHandle{std::make_shared<Simulation>(scenario, threadsOf(threads, "Simulation")), {}};
           }),
           "scenario"_a, "threads"_a = py::none(),
           "A simulation of `scenario` at t = 0 on `threads` threads (1 to 1024; None: default_threads()).")
      .def(
          "step",
          [](SimulationHandle& handle, long n) {
            const SharedSimulation simulation = handle.get("step");
            stepInterruptibly(simulation, [n](Simulation& s, auto keepGoing) { s.step(n, keepGoing); });
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
          "Steps until t is the last multiple of dt at or before t + seconds (finite, >= 0).")
      .def_property_readonly(
          "t", [](const SimulationHandle& h) { return h.get("t")->time(); },
          "The simulated time, s: t0 + k*dt after k steps.")
      .def_property_readonly(
          "steps", [](const SimulationHandle& h) { return h.get("steps")->steps(); }, "Steps taken so far.")
      .def_property_readonly(
          "dt", [](const SimulationHandle& h) { return h.get("dt")->dt(); }, "The time step, s.")
      .def_property_readonly(
          "integrator", [](const SimulationHandle& h) { return h.get("integrator")->integrator(); },
          "The integrator, as scenarios name it.")
      .def_property(
          "threads", [](const SimulationHandle& h) { return h.get("threads")->threads(); },
          [](SimulationHandle& h, const py::object& threads) {
            h.get("threads")->setThreads(threadsOf(threads, "Simulation.threads"));
          },
          "The threads a step runs on (1 to 1024; the bits do not depend on it).")
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
            py::array_t<BodyState> out(py::ssize_t(bodies.size()));
            std::copy(bodies.begin(), bodies.end(), out.mutable_data());
            return out;
          },
          "The rigid bodies now: a structured array (a copy) with fields x, y (m), angle (rad) and omega (rad/s).")
      .def(
          "position", [](const SimulationHandle& h, const py::handle& p) {
            const Simulation& s = *h.get("position");
            return tupleOf(s.position(particleOf(s, p)));
          },
          "particle"_a, "A particle's (x, y), m; the particle by index or name.")
      .def(
          "velocity", [](const SimulationHandle& h, const py::handle& p) {
            const Simulation& s = *h.get("velocity");
            return tupleOf(s.velocity(particleOf(s, p)));
          },
          "particle"_a, "A particle's (vx, vy), m/s; the particle by index or name.")
      .def(
          "set_position",
          [](SimulationHandle& h, const py::handle& p, const py::handle& xy) {
            Simulation& s = *h.get("set_position");
            s.setPosition(particleOf(s, p), pointOf(xy, "Simulation.set_position"));
          },
          "particle"_a, "xy"_a,
          "Moves a particle (by index or name) to (x, y) where the next step starts; constraints pull it back.")
      .def(
          "set_velocity",
          [](SimulationHandle& h, const py::handle& p, const py::handle& v) {
            Simulation& s = *h.get("set_velocity");
            s.setVelocity(particleOf(s, p), pointOf(v, "Simulation.set_velocity"));
          },
          "particle"_a, "velocity"_a, "Sets a particle's velocity (vx, vy), m/s.")
      .def_property_readonly(
          "mouse_count", [](const SimulationHandle& h) { return h.get("mouse_count")->mouseCount(); },
          "How many mice the scenario has (its `mouse` section).")
      .def(
          "set_mouse_target",
          [](SimulationHandle& h, const py::handle& xy, int mouse) {
            h.get("set_mouse_target")->setMouseTarget(pointOf(xy, "Simulation.set_mouse_target"), mouse);
          },
          "xy"_a, "mouse"_a = 0,
          R"doc(Takes over a mouse of the scenario: from now on it pulls its grabbed point towards
(x, y), its scripted path and time window replaced, until release_mouse(). A scenario without a
mouse can be given one: Scenario.set("mouse", "[{grab: 'cloth[24][12]', from: 0, to: 1, path: [[0, 0]], ks: 2}]").)doc")
      .def(
          "release_mouse", [](SimulationHandle& h, int mouse) { h.get("release_mouse")->releaseMouse(mouse); },
          "mouse"_a = 0, "Lets the mouse go: it pulls no more.")
      .def(
          "mouse_target",
          [](const SimulationHandle& h, int mouse) -> py::object {
            const std::optional<Point> at = h.get("mouse_target")->mouseTarget(mouse);
            if (!at) return py::none();
            return tupleOf(*at);
          },
          "mouse"_a = 0, "Where the mouse pulls now, (x, y); None while it holds no point.")
      .def("energy", [](const SimulationHandle& h) { return h.get("energy")->energy(); }, "The energy now (Energy).")
      .def(
          "constraint_error", [](const SimulationHandle& h) { return h.get("constraint_error")->constraintError(); },
          "The largest violation of a constraint now, m.")
      .def(
          "penetration", [](const SimulationHandle& h) { return h.get("penetration")->penetration(); },
          "How deep the deepest point is inside a collider now, m.")
      .def_property_readonly(
          "names", [](const SimulationHandle& h) { return h.get("names")->particleNames(); },
          "The particles' names, in index order: the names `particles run --trace` writes.")
      .def_property_readonly(
          "body_names", [](const SimulationHandle& h) { return h.get("body_names")->bodyNames(); },
          "The rigid bodies' names, in index order.")
      .def(
          "index", [](const SimulationHandle& h, const std::string& name) { return h.get("index")->particleIndex(name); },
          "name"_a, "The index of the particle of that name; ArgumentError (with the closest names) otherwise.")
      .def(
          "body_index",
          [](const SimulationHandle& h, const std::string& name) { return h.get("body_index")->bodyIndex(name); },
          "name"_a, "The index of the rigid body of that name.")
      .def(
          "close",
          [](SimulationHandle& h) {
            h.lastRenderer.reset();
            h.simulation.reset();
          },
          "Frees the simulation (views of its state keep their memory). Later calls raise ArgumentError.")
      .def_property_readonly(
          "closed", [](const SimulationHandle& h) { return !h.simulation; }, "Whether close() was called.")
      .def("__enter__", [](py::object self) { return self; })
      .def(
          "__exit__",
          [](SimulationHandle& h, const py::handle&, const py::handle&, const py::handle&) {
            h.lastRenderer.reset();
            h.simulation.reset();
            return false;
          },
          "exc_type"_a, "exc"_a, "traceback"_a)
      .def("__repr__", &describeSimulation);
}

}  // namespace particles::python
