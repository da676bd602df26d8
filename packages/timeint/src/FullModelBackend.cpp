// Belos and Ifpack2 are instantiated in this one file only (PLATFORM.md: heavy instantiations
// stay out of widely included headers).
#include "gphr/timeint/FullModelBackend.hpp"

#include <algorithm>

#include <BelosLinearProblem.hpp>
#include <BelosSolverFactory.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Ifpack2_Factory.hpp>

#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"

namespace gphr {

using BelosProblem = Belos::LinearProblem<Scalar, MultiVector, Operator>;
using BelosSolver = Belos::SolverManager<Scalar, MultiVector, Operator>;
using Preconditioner = Ifpack2::Preconditioner<Scalar, LO, GO, Node>;

// A Newton direction from a linear solve with this relative residual still contracts Newton.
constexpr double kUsefulTolerance = 1e-6;

// The loosest relative residual the forcing term asks of a linear solve: a Newton direction this
// far off still contracts (inexact Newton, Eisenstat and Walker's eta_max is 0.9; 0.1 keeps the
// Newton iteration count of a tight solve).
constexpr double kLoosestForcing = 0.1;

struct FullModelBackend::Solver {
  RCP<BelosSolver> belos;
  RCP<BelosProblem> problem;
  RCP<Preconditioner> prec;
  double tolerance = 1e-12;  ///< linearSolver.tolerance
  double forcing = 1e-3;     ///< linearSolver.forcing
  double current = 0.0;      ///< the tolerance Belos holds now
  /// The one key a per-solve tolerance change passes to Belos (owned: a solver manager may keep it).
  RCP<Teuchos::ParameterList> tolerancePatch = Teuchos::parameterList();
};

Teuchos::ParameterList FullModelBackend::validParameters() {
  Teuchos::ParameterList pl("linearSolver");
  setChoiceParameter(pl, "method", "GMRES", Teuchos::tuple<std::string>("GMRES", "TFQMR", "BICGSTAB"),
                     "Belos solver for the Newton systems of the full model");
  setDoubleParameter(pl, "tolerance", 1e-12, 1e-16, 1e-2,
                     "relative residual tolerance of each linear solve");
  setDoubleParameter(pl, "forcing", 1e-3, 0.0, 1.0,
                     "inexact Newton: each linear solve may stop once its residual is below forcing x "
                     "integrator.newtonTolerance, at most 0.1 relative and never tighter than 'tolerance'; 0: every "
                     "solve to 'tolerance'. The default keeps the linear error three orders below the Newton "
                     "tolerance: same Newton iterations and AVF energy drift as tight solves (GPHR's Newton only; "
                     "the NOX driver has its own Forcing Term Method)");
  setIntParameter(pl, "maxIterations", 500, 1, 100000, "iteration limit of each linear solve");
  setIntParameter(pl, "krylovVectors", 30, 1, 1000,
                  "GMRES restart length (Krylov vectors of length 2n kept per solve; at most maxIterations); "
                  "the preconditioned solves take 2-10 iterations");
  setChoiceParameter(pl, "orthogonalization", "IMGS", Teuchos::tuple<std::string>("IMGS", "ICGS", "DGKS"),
                     "Gram-Schmidt of GMRES's Krylov basis (Belos' orthogonalization manager): IMGS, modified "
                     "Gram-Schmidt in one pass, backward stable for GMRES (Paige, Rozloznik and Strakos, 2006) "
                     "and faster here than Belos' default ICGS (classical, two passes) on 1 and 2 ranks (doc/design.md, "
                     "'GMRES accuracy'); ICGS and DGKS take fewer all-reduces per iteration at many ranks per "
                     "system. GPHR's Newton and the NOX driver alike");
  setChoiceParameter(pl, "preconditioner", "RILUK",
                     Teuchos::tuple<std::string>("RILUK", "ILUT", "RELAXATION", "AMESOS2", "none"),
                     "Ifpack2 preconditioner, per rank (block Jacobi); AMESOS2 = exact KLU2 solve of each "
                     "rank's block (a direct solve on one rank)");
  setIntParameter(pl, "iluFill", 1, 0, 10, "level of fill of RILUK");
  setChoiceParameter(pl, "relaxation", "Gauss-Seidel",
                     Teuchos::tuple<std::string>("Gauss-Seidel", "Symmetric Gauss-Seidel", "Jacobi"),
                     "sweep of RELAXATION (one per application). GMRES needs no symmetric preconditioner: the "
                     "forward sweep costs half the symmetric one and, on more than one rank, takes about as "
                     "few iterations (doc/design.md, 'Preconditioner')");
  setIntParameter(pl, "preconditionerRecomputeEvery", 20, 1, 1000000,
                  "refactor the preconditioner every N Newton-matrix assemblies (GMRES always solves with "
                  "the current matrix; a stale factor only costs iterations)");
  return pl;
}

Teuchos::ParameterList FullModelBackend::preconditionerParameters(const Teuchos::ParameterList& ls) {
  const std::string pt = ls.get<std::string>("preconditioner");
  Teuchos::ParameterList pp;
  if (pt == "RILUK") pp.set("fact: iluk level-of-fill", ls.get<int>("iluFill"));
  if (pt == "RELAXATION") pp.set("relaxation: type", ls.get<std::string>("relaxation"));
  if (pt == "AMESOS2") {
    pp.set("Amesos2 solver name", "KLU2");
    pp.sublist("Amesos2");  // Amesos2 insists on a sublist of this name
  }
  return pp;
}

// Ifpack2 13.2's Amesos2Wrapper, on a matrix of several ranks, copies its LocalFilter into a new
// CrsMatrix in initialize() and compute() refactors that copy: with compute() alone every refresh
// would factor the matrix of the first initialize() (here the identity), and GMRES ran as if
// unpreconditioned (NLS n = 2048, AVF, 2 ranks: 333 GMRES per step, none's count, against 8.3
// with RILUK). RILUK, ILUT and RELAXATION read the matrix's current values in compute().
bool FullModelBackend::refreshReinitializes(const Teuchos::ParameterList& ls, int ranks) {
  return ranks > 1 && ls.get<std::string>("preconditioner") == "AMESOS2";
}

int FullModelBackend::krylovVectors(const Teuchos::ParameterList& ls) {
  return std::min(ls.get<int>("krylovVectors"), ls.get<int>("maxIterations"));
}

FullModelBackend::FullModelBackend(RCP<const HamiltonianSystem> system, Teuchos::ParameterList ls,
                                   bool ownLinearSolver)
    : system_(system) {
  validateParameters(ls, validParameters(), "linearSolver");
  newtonMatrix_ = rcp(new CrsMatrix(system_->hessianGraph(true)));
  newtonMatrix_->fillComplete(system_->map(), system_->map());  // packed storage (LocalScatter)
  {
    const auto& map = *system_->map();
    std::vector<GO> diag(map.getNodeNumElements());
    for (size_t i = 0; i < diag.size(); ++i) diag[i] = map.getGlobalElement(static_cast<LO>(i));
    identity_ = LocalScatter(*newtonMatrix_->getCrsGraph(), diag, diag);
    ones_.assign(diag.size(), 1.0);
  }
  recomputeEvery_ = ls.get<int>("preconditionerRecomputeEvery");
  reinitialize_ = refreshReinitializes(ls, system_->map()->getComm()->getSize());
  if (!ownLinearSolver) return;
  solver_.reset(new Solver);
  solver_->tolerance = solver_->current = ls.get<double>("tolerance");
  solver_->forcing = ls.get<double>("forcing");
  auto belosParams = Teuchos::parameterList();
  belosParams->set("Convergence Tolerance", solver_->tolerance);
  belosParams->set("Maximum Iterations", ls.get<int>("maxIterations"));
  if (ls.get<std::string>("method") == "GMRES") {
    belosParams->set("Num Blocks", krylovVectors(ls));
    belosParams->set("Orthogonalization", ls.get<std::string>("orthogonalization"));
  }
  belosParams->set("Implicit Residual Scaling", "Norm of RHS");
  belosParams->set("Explicit Residual Scaling", "Norm of RHS");
  Belos::SolverFactory<Scalar, MultiVector, Operator> factory;
  // GPHR's driver: "GMRES" is Belos::SolverFactory's Pseudo Block GMRES on Tpetra (measured 20%
  // faster here than Block GMRES for these single right-hand sides: NLS n = 2048, 500 AVF steps,
  // 3.0 s against 3.6 s, same iterations). NOX's Stratimikos solver is configured in NoxNewton.cpp.
  solver_->belos = factory.create(ls.get<std::string>("method"), belosParams);
  solver_->problem = rcp(new BelosProblem());
  const std::string pt = ls.get<std::string>("preconditioner");
  if (pt != "none") {
    // Ifpack2 needs a fill-complete matrix to set up; assemble I once for the structure.
    beginNewtonMatrix();
    newtonMatrix_->fillComplete(system_->map(), system_->map());
    solver_->prec = Ifpack2::Factory::create<Tpetra::RowMatrix<Scalar, LO, GO, Node>>(pt, newtonMatrix_);
    solver_->prec->setParameters(preconditionerParameters(ls));
    solver_->prec->initialize();
  }
}

FullModelBackend::~FullModelBackend() = default;

void FullModelBackend::beginNewtonMatrix() {
  auto& M = *newtonMatrix_;
  if (M.isFillComplete()) M.resumeFill();
  M.setAllToScalar(0.0);
  identity_.add(M, ones_.data());  // M = I
}

void FullModelBackend::endNewtonMatrix() {
  newtonMatrix_->fillComplete(system_->map(), system_->map());
  refreshDue_ = assemblies_++ % recomputeEvery_ == 0;
  if (!solver_ || solver_->prec.is_null() || !refreshDue_) return;
  if (reinitialize_) solver_->prec->initialize();  // see refreshReinitializes
  solver_->prec->compute();
}

int FullModelBackend::solveNewton(const Vector& rhs, Vector& dx, double newtonRelative) {
  GPHR_REQUIRE(solver_ != nullptr, SolverError, "FullModelBackend::solveNewton: this backend was built without "
               "a linear solver (the NOX driver solves with Stratimikos)");
  // Inexact Newton: the solve stops once its residual is below forcing x newtonTolerance
  // (newtonRelative is that tolerance over ||rhs||), not at 'tolerance' relative whatever ||rhs||.
  // `gphr run`, 1 rank, this VM: SWE 256^2 IMR with the lagged Jacobian, 80 steps, symmetric
  // Gauss-Seidel (the SWE's sweep then), GMRES iterations per step 8.29 -> 3.70 at forcing 1e-3
  // (3.09 at 1e-2, 2.71 at 0.1), time stepping 5.8-7.4 -> 3.5-4.3 s, Newton iterations unchanged,
  // the trajectory to 1e-12; NLS n = 2048, AVF, T = 2: relative energy drift 4.0e-13 with tight
  // solves, 3.7e-13 at 1e-3, 1.3e-11 at 1e-2, 1.0e-10 at 0.1 (AVF conserves H to the Newton
  // residual, which a loose solve leaves larger).
  const double loose = std::min(kLoosestForcing, solver_->forcing * newtonRelative);
  const double wanted = solver_->forcing > 0.0 ? std::max(solver_->tolerance, loose) : solver_->tolerance;
  if (wanted != solver_->current) {  // Belos updates its status tests' tolerance alone
    solver_->tolerancePatch->set("Convergence Tolerance", wanted);
    solver_->belos->setParameters(solver_->tolerancePatch);
    solver_->current = wanted;
  }
  dx.putScalar(0.0);
  auto& p = *solver_->problem;
  p.setOperator(newtonMatrix_);
  p.setLHS(Teuchos::rcpFromRef(static_cast<MultiVector&>(dx)));
  p.setRHS(Teuchos::rcpFromRef(static_cast<const MultiVector&>(rhs)));
  // dx starts at 0, so the initial residual is rhs itself (rhs - A 0, to the bit): handed to Belos,
  // setProblem() skips the mat-vec it would spend on it, one per Newton solve (134 of 698
  // mat-vecs, 5 % of the time stepping: `gphr run --verbose`, SWE 256^2 IMR, 80 steps, this VM).
  p.setInitResVec(Teuchos::rcpFromRef(static_cast<const MultiVector&>(rhs)));
  if (!solver_->prec.is_null()) p.setRightPrec(solver_->prec);
  p.setProblem();
  solver_->belos->setProblem(solver_->problem);
  const Belos::ReturnType ret = solver_->belos->solve();
  const int iters = solver_->belos->getNumIters();
  // Near round-off GMRES can stop short of a very tight tolerance (implicit and explicit residuals
  // part ways); Newton checks the true residual anyway, so only a useless direction is an error.
  double achieved = ret == Belos::Converged ? 0.0 : 1.0;
  try {
    achieved = solver_->belos->achievedTol();
  } catch (const std::exception&) {  // not implemented by every Belos solver
  }
  GPHR_REQUIRE(ret == Belos::Converged || achieved <= kUsefulTolerance, SolverError,
               "linear solve of the Newton system reached only relative residual ", achieved,
               " (tolerance ", solver_->current, ") in ", iters,
               " iterations (raise linearSolver.maxIterations or change linearSolver.preconditioner)");
  return iters;
}

}  // namespace gphr
