#include "core/implicit_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/implicit_assembly.hpp"
#include "core/parallel_sparse.hpp"

namespace particles {

namespace {

// A constraint row that fixes one coordinate by itself: one particle, J with one non-zero
// component (a horizontal line's J = (0, 1)). Returns that coordinate, or −1.
int axisAlignedCoordinate(const ConstraintRow& row) {
  if (row.count != 1) return -1;
  const Vec2& j = row.J[0];
  if (j.x() != 0.0 && j.y() == 0.0) return 2 * row.particle[0];
  if (j.x() == 0.0 && j.y() != 0.0) return 2 * row.particle[0] + 1;
  return -1;
}

// The constraint rows for the solve, J Δv = c with c = −J v₀. CG keeps every row and every
// column (a pinned coordinate's G⁻¹ is 0). The direct path leaves out the eliminated rows, and
// the pinned columns, whose known Δv moves into c.
void gatherRows(const std::vector<ConstraintRow>& from, const std::vector<int>& keep,
                const Eigen::Ref<const Eigen::VectorXd>& v0, const std::vector<char>* pinned,
                const Eigen::VectorXd* known, ConstraintRowsJ& to) {
  const int m = int(keep.size());
  to.columns.assign(size_t(m), {-1, -1, -1, -1});
  to.values.assign(size_t(m), {0.0, 0.0, 0.0, 0.0});
  to.c.setZero(m);
  for (int r = 0; r < m; ++r) {
    const ConstraintRow& row = from[size_t(keep[size_t(r)])];
    for (int k = 0; k < row.count; ++k) {
      for (int d = 0; d < 2; ++d) {
        const int col = 2 * row.particle[size_t(k)] + d;
        const double value = row.J[size_t(k)][d];
        to.c[r] -= value * v0[col];
        if (pinned && (*pinned)[size_t(col)]) {
          to.c[r] -= value * (*known)[col];
          continue;
        }
        to.columns[size_t(r)][size_t(2 * k + d)] = col;
        to.values[size_t(r)][size_t(2 * k + d)] = value;
      }
    }
  }
}

// The step's stages besides A and b (core/implicit_assembly.hpp): which constraint rows each solve
// takes, and the two solves, over the scratch they fill.
class StepStages {
 public:
  StepStages(const Model& model, WorkerPool* pool, ImplicitStep::Scratch& w)
      : model_(model), pool_(pool), w_(w), n_(2 * Eigen::Index(model.layout.numPoints())) {}

  // Sorts the constraint rows: dropped (nothing free), eliminable (an axis-aligned rail on a
  // coordinate not yet railed), general (the rest). Marks fixed points' coordinates pinned.
  // Returns how many coordinates the rails would eliminate.
  int classifyRows();
  // The direct path's reduced coordinates: each rail's coordinate pinned, its Δv known.
  void eliminateRails(const Eigen::VectorXd& y);
  // Δv into w.dv, by either solve; direct falls back to CG if A cannot be factored.
  void solveByCg(const Eigen::Ref<const Eigen::VectorXd>& v0, double tolerance);
  void solveDirect(const Eigen::Ref<const Eigen::VectorXd>& v0, double cgTolerance);

 private:
  bool fixedDof(Eigen::Index i) const { return model_.invMass[i / 2] == 0.0; }

  const Model& model_;
  WorkerPool* pool_;
  ImplicitStep::Scratch& w_;
  const Eigen::Index n_;
};

int StepStages::classifyRows() {
  w_.pinned.assign(size_t(n_), 0);
  for (Eigen::Index i = 0; i < n_; ++i) w_.pinned[size_t(i)] = fixedDof(i) ? 1 : 0;
  w_.known.setZero(n_);
  w_.allRows.clear();
  w_.generalRows.clear();
  w_.railRows.clear();
  w_.railed.assign(size_t(n_), 0);
  int eliminated = 0;
  for (size_t r = 0; r < w_.constraintRows.size(); ++r) {
    w_.allRows.push_back(int(r));
    const ConstraintRow& row = w_.constraintRows[r];
    bool touchesFree = false;
    for (int k = 0; k < row.count; ++k) touchesFree = touchesFree || model_.invMass[row.particle[size_t(k)]] != 0.0;
    if (!touchesFree) continue;  // nothing can meet it: dropped
    const int coordinate = axisAlignedCoordinate(row);
    if (coordinate >= 0 && !w_.railed[size_t(coordinate)]) {
      w_.railed[size_t(coordinate)] = 1;
      w_.railRows.push_back(int(r));
      ++eliminated;
    } else {
      w_.generalRows.push_back(int(r));
    }
  }
  return eliminated;
}

void StepStages::eliminateRails(const Eigen::VectorXd& y) {
  const Eigen::Index vOff = model_.layout.velocityOffset();
  for (int r : w_.railRows) {
    const int coordinate = axisAlignedCoordinate(w_.constraintRows[size_t(r)]);
    // J_i Δv_i = c = −J_i v₀ᵢ: the rail's coordinate ends the step at rest (Ċ = 0).
    w_.known[coordinate] = -y[vOff + coordinate];
    w_.pinned[size_t(coordinate)] = 1;
  }
}

void StepStages::solveByCg(const Eigen::Ref<const Eigen::VectorXd>& v0, double tolerance) {
  ImplicitStepStats& stats = w_.stats;
  gatherRows(w_.constraintRows, w_.allRows, v0, nullptr, nullptr, w_.rows);
  w_.jacobi.setMatrix(pool_, w_.matrix, w_.pinned);
  w_.jacobi.prepareRows(w_.rows);
  const int maxIterations = int(std::max<Eigen::Index>(2 * n_, 10));
  stats.solver = ImplicitSolver::cg;
  stats.schurRows = 0;
  stats.iterations =
      solveProjectedPcg(pool_, w_.matrix, w_.rhs, w_.rows, w_.jacobi, w_.dv, tolerance, maxIterations, w_.pcg)
          .iterations;
}

void StepStages::solveDirect(const Eigen::Ref<const Eigen::VectorXd>& v0, double cgTolerance) {
  ImplicitStepStats& stats = w_.stats;
  gatherRows(w_.constraintRows, w_.generalRows, v0, &w_.pinned, &w_.known, w_.rows);
  stats.solver = ImplicitSolver::direct;
  stats.schurRows = w_.rows.size();
  auto refactor = [&] {
    if (!w_.ldltValid) w_.ldlt.analyze(w_.matrix);
    w_.ldltValid = w_.ldlt.factorize(w_.matrix);
    w_.reuseDebt = 0.0;
    stats.factorized = true;
    ++w_.factorizations;
    return w_.ldltValid;
  };
  // Refactor when the stale factors' extra iterations have cost as much as a factorisation
  // (the rent-or-buy rule: never more than twice the cheaper of the two choices in hindsight).
  bool ok = w_.ldltValid && w_.reuseDebt < w_.ldlt.factorCost() ? true : refactor();
  if (ok) {
    w_.ldlt.prepareRows(w_.rows);
    // A's own factors give the answer in one solve; an earlier step's iterate from there.
    ProjectedPcgResult r =
        solveProjectedPcg(pool_, w_.matrix, w_.rhs, w_.rows, w_.ldlt, w_.dv, kDirectTolerance, kMaxReuseIterations,
                          w_.pcg, stats.factorized ? PcgStart::exact : PcgStart::preconditioned);
    stats.iterations = r.iterations;
    if (!r.converged && !stats.factorized) {
      // Factors too far from A to converge soon: A's own, and on from here.
      ok = refactor();
      if (ok) {
        w_.ldlt.prepareRows(w_.rows);
        r = solveProjectedPcg(pool_, w_.matrix, w_.rhs, w_.rows, w_.ldlt, w_.dv, kDirectTolerance, kMaxReuseIterations,
                              w_.pcg, PcgStart::exact);
        stats.iterations += r.iterations;
      }
    }
    // What reuse cost beyond A's own factors' one solve: the residual's check and the iterations.
    if (ok && !stats.factorized) w_.reuseDebt += double(r.iterations + 1) * w_.ldlt.iterationCost();
  }
  if (!ok) {
    // Not positive definite (cannot happen with the forces' negative semi-definite blocks; a
    // guard): this step by CG, which needs no factors.
    w_.ldltValid = false;
    solveByCg(v0, cgTolerance);
  } else {
    w_.dv += w_.known;
  }
}

}  // namespace

double autoDirectIterations(long freeCoordinates) {
  return 14.0 * std::pow(double(std::max(freeCoordinates, 1L)) / 1250.0, 0.3);
}

ImplicitStep::ImplicitStep() : w_(std::make_unique<Scratch>()) {}
ImplicitStep::~ImplicitStep() = default;
ImplicitStep::ImplicitStep(ImplicitStep&&) noexcept = default;
ImplicitStep& ImplicitStep::operator=(ImplicitStep&&) noexcept = default;

const ImplicitStepStats& ImplicitStep::stats() const {
  return w_->stats;
}
long ImplicitStep::factorizations() const {
  return w_->factorizations;
}

ImplicitStep::LinearSystem ImplicitStep::lastSystem() const {
  return {w_->matrix, w_->rhs, w_->dv, w_->constraintRows};
}

void ImplicitStep::step(System& system, Eigen::VectorXd& y, double t, double h, const ImplicitTarget& target,
                        double cgTolerance) {
  Scratch& w = *w_;
  const Model& model = system.model();
  const StateLayout& layout = model.layout;
  const Eigen::Index n = 2 * Eigen::Index(layout.numPoints());
  const Eigen::Index vOff = layout.velocityOffset();
  const double eta = target.eta;
  WorkerPool* pool = system.pool();
  StepStages stages(model, pool, w);
  ImplicitAssembly assembly(model, pool, w);

  system.derivEval(y, t, w.k1, System::ConstraintForces::skip);  // [v₀ | f₀/m | ω₀ | τ₀/I]
  system.forceJacobians(y, t, w.jacobians);
  w.constraintRows.clear();
  const StateView s0(layout, y);
  for (const auto& c : system.constraints()) w.constraintRows.push_back(c->evaluate(s0));

  // Which solve: the direct one eliminates axis-aligned rails and takes the other rows through
  // its Schur complement, so it needs those to be few.
  const int eliminated = stages.classifyRows();
  const int generalRows = int(w.generalRows.size());
  const long freeCoordinates = long(std::count(w.pinned.begin(), w.pinned.end(), 0)) - eliminated;
  const ImplicitSolver requested = system.implicitSolver();
  const bool automatic = requested == ImplicitSolver::automatic;
  ImplicitSolver solver = requested;
  if (automatic) {
    solver = w.autoDirect && generalRows <= kMaxSchurRows ? ImplicitSolver::direct : ImplicitSolver::cg;
  }
  if (solver == ImplicitSolver::direct && generalRows > kMaxSchurRows) {
    throw ImplicitSolverError(fmt::format(
        "implicit_solver: direct: {} constraint rows are neither fixed points nor axis-aligned rails, and the direct "
        "solve takes at most {} such rows (their Schur complement is dense); use implicit_solver: cg or auto",
        generalRows, kMaxSchurRows));
  }
  const bool direct = solver == ImplicitSolver::direct && n > 0;
  if (direct) stages.eliminateRails(y);

  // A = M − η D − η² K over the free coordinates; a pinned one's row and column are the identity.
  // The Jacobians' pattern only changes when a contact or a mouse spring starts or ends, so A's
  // pattern is built once and its values are filled into it while the Jacobians' (row, column)
  // sequence is the one it was built from (a full setFromTriplets sorts and merges every triplet
  // again).
  if (assembly.patternChanged()) assembly.buildPattern();
  assembly.fillMatrix(eta);
  assembly.fillRightHandSide(y, eta, target);

  // Δv with J Δv = −J v₀, so that v₁ keeps every constraint's Ċ = 0 (J at x₀).
  const Eigen::Ref<const Eigen::VectorXd> v0 = y.segment(vOff, n);
  if (w.dv.size() != n) w.dv.setZero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (w.pinned[size_t(i)]) w.dv[i] = 0.0;  // the last step's Δv is the first guess
  }
  ImplicitStepStats& stats = w.stats;
  stats = {};
  stats.eliminated = direct ? eliminated : 0;
  if (direct) {
    stages.solveDirect(v0, cgTolerance);
  } else {
    stages.solveByCg(v0, cgTolerance);
    // auto: CG steps dearer than the direct solve at this size, on average, move the run to it.
    if (automatic && generalRows <= kMaxSchurRows) {
      std::vector<int>& window = w.cgIterationsWindow;
      if (int(window.size()) == kAutoWindow) window.erase(window.begin());
      window.push_back(stats.iterations);
      const double mean = double(std::accumulate(window.begin(), window.end(), 0)) / double(window.size());
      if (int(window.size()) == kAutoWindow && mean > autoDirectIterations(freeCoordinates)) w.autoDirect = true;
    }
  }

  const Eigen::VectorXd* xShift = target.xShift;
  forSegments(pool, n, [&](long i, long len) {
    y.segment(vOff + i, len) += w.dv.segment(i, len);
    if (xShift) y.segment(i, len) += xShift->segment(i, len);
    y.segment(i, len) += eta * y.segment(vOff + i, len);
  });
  // Rotation: explicit (see the header).
  const int bodies = layout.numBodies;
  if (target.rotationStart) {
    y.segment(layout.omegaOffset(), bodies) = target.rotationStart->segment(layout.omegaOffset(), bodies);
    y.segment(layout.angleOffset(), bodies) = target.rotationStart->segment(layout.angleOffset(), bodies);
  }
  y.segment(layout.omegaOffset(), bodies) += h * w.k1.segment(layout.omegaOffset(), bodies);
  y.segment(layout.angleOffset(), bodies) += h * y.segment(layout.omegaOffset(), bodies);
}

}  // namespace particles
