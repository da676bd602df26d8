// NOX::Thyra + Stratimikos + Ifpack2 adapters are instantiated in this one file only (PLATFORM.md:
// a Thyra ModelEvaluator over Tpetra is a heavy translation unit; nothing here is in a header).
#include "gphr/timeint/NoxNewton.hpp"

#include <NOX_Solver_Factory.H>
#include <NOX_Solver_Generic.H>
#include <NOX_SolverStats.hpp>
#include <NOX_StatusTest_Combo.H>
#include <NOX_StatusTest_FiniteValue.H>
#include <NOX_StatusTest_MaxIters.H>
#include <NOX_StatusTest_NormF.H>
#include <NOX_Thyra_Group.H>
#include <NOX_Thyra_Vector.H>
#include <NOX_Utils.H>
#include <Ifpack2_Preconditioner.hpp>
#include <Stratimikos_DefaultLinearSolverBuilder.hpp>
#include <Teuchos_AbstractFactoryStd.hpp>
#include <Thyra_DefaultLinearOpSource.hpp>
#include <Thyra_DefaultPreconditioner.hpp>
#include <Thyra_Ifpack2PreconditionerFactory.hpp>
#include <Thyra_StateFuncModelEvaluatorBase.hpp>
#include <Thyra_TpetraThyraWrappers.hpp>
#include <functional>
#include <limits>

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {

using Scheme = AveragedGradientScheme<FullModelBackend>;
using TOE = Thyra::TpetraOperatorVectorExtraction<Scalar, LO, GO, Node>;
using MEB = Thyra::ModelEvaluatorBase;

// The step's equation R(y1) = 0 for given (y0, dt): f = scheme.residual, W = scheme's Newton matrix
// (the backend's CrsMatrix, assembled in place). Refactors the preconditioner on the backend's
// schedule (preconditionerRefreshDue) through `refresh`.
class StepEquation : public Thyra::StateFuncModelEvaluatorBase<double> {
 public:
  StepEquation(Scheme& scheme, RCP<const Thyra::VectorSpaceBase<double>> space, RCP<Thyra::LinearOpBase<double>> W,
               RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> lows, std::function<void()> refresh)
      : scheme_(scheme), space_(space), W_(W), lows_(lows), refresh_(std::move(refresh)) {
    MEB::InArgsSetup<double> in;
    in.setModelEvalDescription("gphr step equation");
    in.setSupports(MEB::IN_ARG_x);
    inArgs_ = in;
    MEB::OutArgsSetup<double> out;
    out.setModelEvalDescription("gphr step equation");
    out.setSupports(MEB::OUT_ARG_f);
    out.setSupports(MEB::OUT_ARG_W_op);
    outArgs_ = out;
  }

  // chord: assemble W only at the first Jacobian evaluation of the step (integrator.jacobianReuse).
  void setStep(const Vector& y0, double dt, bool chord) {
    y0_ = &y0;
    dt_ = dt;
    chord_ = chord;
    assembledThisStep_ = false;
  }

  RCP<const Thyra::VectorSpaceBase<double>> get_x_space() const override { return space_; }
  RCP<const Thyra::VectorSpaceBase<double>> get_f_space() const override { return space_; }
  MEB::InArgs<double> getNominalValues() const override { return inArgs_; }
  RCP<Thyra::LinearOpBase<double>> create_W_op() const override { return W_; }
  RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> get_W_factory() const override { return lows_; }
  MEB::InArgs<double> createInArgs() const override { return inArgs_; }

 private:
  MEB::OutArgs<double> createOutArgsImpl() const override { return outArgs_; }

  void evalModelImpl(const MEB::InArgs<double>& in, const MEB::OutArgs<double>& out) const override {
    const RCP<const Vector> x = TOE::getConstTpetraVector(in.get_x());
    if (const auto f = out.get_f(); !f.is_null()) scheme_.residual(*y0_, *x, dt_, *TOE::getTpetraVector(f));
    if (!out.get_W_op().is_null() && !(chord_ && assembledThisStep_)) {
      scheme_.assembleNewtonMatrix(*y0_, *x, dt_);
      assembledThisStep_ = true;
      refresh_();
    }
  }

  Scheme& scheme_;
  RCP<const Thyra::VectorSpaceBase<double>> space_;
  RCP<Thyra::LinearOpBase<double>> W_;
  RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> lows_;
  std::function<void()> refresh_;
  MEB::InArgs<double> inArgs_;
  MEB::OutArgs<double> outArgs_;
  const Vector* y0_ = nullptr;
  double dt_ = 0.0;
  bool chord_ = false;
  mutable bool assembledThisStep_ = false;
};

// Stratimikos' names of the Belos solver managers FullModelBackend uses for linearSolver.method.
std::string stratimikosBelosName(const std::string& method) {
  if (method == "GMRES") return "Block GMRES";
  if (method == "TFQMR") return "TFQMR";
  return "BiCGStab";
}

// Stratimikos: Belos configured from the linearSolver section; Ifpack2 registered by hand.
Teuchos::RCP<Teuchos::ParameterList> stratimikosParameters(const Teuchos::ParameterList& ls) {
  auto pl = Teuchos::parameterList("Stratimikos");
  pl->set("Linear Solver Type", "Belos");
  auto& belos = pl->sublist("Linear Solver Types").sublist("Belos");
  const std::string solver = stratimikosBelosName(ls.get<std::string>("method"));
  belos.set("Solver Type", solver);
  auto& sp = belos.sublist("Solver Types").sublist(solver);
  sp.set("Convergence Tolerance", ls.get<double>("tolerance"));
  sp.set("Maximum Iterations", ls.get<int>("maxIterations"));
  if (ls.get<std::string>("method") == "GMRES") {
    sp.set("Num Blocks", FullModelBackend::krylovVectors(ls));
    sp.set("Orthogonalization", ls.get<std::string>("orthogonalization"));
  }
  // The preconditioner is built by the Ifpack2 factory below and handed to NOX, which keeps it
  // between refactorisations; the Belos factory itself has none.
  pl->set("Preconditioner Type", "None");
  auto& ifp = pl->sublist("Preconditioner Types").sublist("Ifpack2");
  ifp.set("Prec Type", ls.get<std::string>("preconditioner"));
  ifp.sublist("Ifpack2 Settings") = FullModelBackend::preconditionerParameters(ls);
  return pl;
}

// The nox section handed to NOX, with GPHR's defaults where the user gave none.
Teuchos::RCP<Teuchos::ParameterList> noxParametersFor(const Teuchos::ParameterList& integrator) {
  auto pl = Teuchos::rcp(new Teuchos::ParameterList(integrator.sublist("nox")));
  auto& newton = pl->sublist("Direction").sublist("Newton");
  newton.sublist("Linear Solver").get("Tolerance", integrator.sublist("linearSolver").get<double>("tolerance"));
  auto& printing = pl->sublist("Printing");
  if (!printing.isParameter("Output Information")) printing.set("Output Information", int(NOX::Utils::Error));
  return pl;
}

}  // namespace

struct NoxNewtonSolver::Impl {
  Scheme& scheme;
  NewtonOptions opts;
  RCP<StepEquation> model;
  RCP<Teuchos::ParameterList> params;
  RCP<NOX::Solver::Generic> solver;
  RCP<const Thyra::VectorSpaceBase<double>> space;
  Impl(Scheme& s) : scheme(s), opts(s.options()) {}
};

NoxNewtonSolver::NoxNewtonSolver(Scheme& scheme, FullModelBackend& backend, const Teuchos::ParameterList& integrator)
    : impl_(new Impl(scheme)) {
  auto& m = *impl_;
  const auto& ls = integrator.sublist("linearSolver");
  m.space = Thyra::createVectorSpace<Scalar, LO, GO, Node>(backend.system().map());
  const RCP<Thyra::LinearOpBase<double>> W =
      Thyra::tpetraLinearOp<Scalar, LO, GO, Node>(m.space, m.space, RCP<Operator>(backend.newtonMatrix()));

  Stratimikos::DefaultLinearSolverBuilder builder;
  using Ifpack2Factory = Thyra::Ifpack2PreconditionerFactory<CrsMatrix>;
  builder.setPreconditioningStrategyFactory(
      Teuchos::abstractFactoryStd<Thyra::PreconditionerFactoryBase<double>, Ifpack2Factory>(), "Ifpack2");
  builder.setParameterList(stratimikosParameters(ls));
  const RCP<const Thyra::LinearOpWithSolveFactoryBase<double>> lows = builder.createLinearSolveStrategy("");

  RCP<Thyra::PreconditionerFactoryBase<double>> precFactory;
  RCP<Thyra::PreconditionerBase<double>> prec;
  if (ls.get<std::string>("preconditioner") != "none") {
    precFactory = builder.createPreconditioningStrategy("Ifpack2");
    prec = precFactory->createPrec();
  }
  // The first refresh builds the Ifpack2 preconditioner through the Stratimikos factory (initialize
  // + compute); later ones only recompute its factors for the new values of the same matrix, as
  // FullModelBackend does (the factory would rebuild the symbolic factorisation every time).
  const auto source = Thyra::defaultLinearOpSource<double>(W);
  FullModelBackend* be = &backend;
  auto ifpack = Teuchos::rcp(new RCP<Ifpack2::Preconditioner<Scalar, LO, GO, Node>>());
  const bool reinitialize = FullModelBackend::refreshReinitializes(ls, backend.system().map()->getComm()->getSize());
  auto refresh = [be, precFactory, prec, source, ifpack, reinitialize]() {
    if (prec.is_null() || !be->preconditionerRefreshDue()) return;
    if (!ifpack->is_null()) {
      if (reinitialize) (*ifpack)->initialize();  // FullModelBackend::refreshReinitializes
      return (*ifpack)->compute();
    }
    precFactory->initializePrec(source, prec.get());
    const auto op = Teuchos::rcp_dynamic_cast<Thyra::TpetraLinearOp<Scalar, LO, GO, Node>>(
        prec->getNonconstUnspecifiedPrecOp(), true);
    *ifpack = Teuchos::rcp_dynamic_cast<Ifpack2::Preconditioner<Scalar, LO, GO, Node>>(op->getTpetraOperator(), true);
  };
  m.model = Teuchos::rcp(new StepEquation(scheme, m.space, W, lows, refresh));

  NOX::Thyra::Vector guess(Thyra::createMember(m.space));
  // updatePreconditioner = false: NOX solves with `prec` as it is; the model refactors it.
  auto group = Teuchos::rcp(new NOX::Thyra::Group(guess, m.model, W, lows, prec, Teuchos::null, Teuchos::null,
                                                  Teuchos::null, Teuchos::null, false, false));
  using namespace NOX::StatusTest;
  auto tests = Teuchos::rcp(new Combo(Combo::OR));
  tests->addStatusTest(Teuchos::rcp(new FiniteValue));
  tests->addStatusTest(Teuchos::rcp(new NormF(m.opts.tolerance, NOX::Abstract::Vector::TwoNorm, NormF::Unscaled)));
  tests->addStatusTest(Teuchos::rcp(new MaxIters(m.opts.maxIterations)));
  m.params = noxParametersFor(integrator);
  m.solver = NOX::Solver::buildSolver(group, tests, m.params);
}

NoxNewtonSolver::~NoxNewtonSolver() = default;

const Teuchos::ParameterList& NoxNewtonSolver::noxParameters() const { return *impl_->params; }

StepReport NoxNewtonSolver::step(const Vector& y0, Vector& y1, double dt, long stepNo, double time) {
  auto& m = *impl_;
  m.model->setStep(y0, dt, m.opts.reuseJacobian);
  m.solver->reset(NOX::Thyra::Vector(Thyra::createVector(Teuchos::rcpFromRef(y1), m.space)));
  NOX::StatusTest::StatusType status = NOX::StatusTest::Unevaluated;
  std::string raised;
  try {
    status = m.solver->solve();
  } catch (const SolverError&) {
    throw;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {  // e.g. Belos on a non-finite Newton matrix
    raised = e.what();
    raised = "; NOX raised: " + raised.substr(0, raised.find('\n', raised.find_first_not_of("\n")));
  }
  const auto& group = m.solver->getSolutionGroup();
  StepReport rep;
  rep.newtonIterations = m.solver->getNumIterations();
  rep.linearIterations = m.solver->getSolverStatistics()->linearSolve.lastNonlinearSolve_NumLinearIterations;
  rep.residualNorm = group.isF() ? group.getNormF() : std::numeric_limits<double>::quiet_NaN();
  GPHR_REQUIRE(status == NOX::StatusTest::Converged, SolverError,
               newtonFailureMessage(m.opts, stepNo, time, rep, "NOX Newton"), raised);
  const auto& x = dynamic_cast<const NOX::Thyra::Vector&>(group.getX());
  Tpetra::deep_copy(y1, *TOE::getConstTpetraVector(x.getThyraRCPVector()));
  rep.gradientNorm = m.scheme.averageGradient().norm2();  // of the last residual NOX evaluated: the accepted y1's
  return rep;
}

}  // namespace gphr
