#include "gphr/hyper/GradientDeimModel.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>

#include <algorithm>
#include <limits>

#include "gphr/core/Error.hpp"
#include "gphr/core/ReplicatedGather.hpp"
#include "gphr/reduction/Deim.hpp"
#include "gphr/reduction/StreamingPod.hpp"

namespace gphr {

GradientDeimPair makeGradientDeimPair(const MultiVector& Ug, int m, const MultiVector& A) {
  GradientDeimPair out;
  out.entries = selectDeimIndices(Ug, m, "deim");
  const int r = static_cast<int>(A.getNumVectors()), nc = static_cast<int>(Ug.getNumVectors());
  auto local = rcp(new Map(r, 0, A.getMap()->getComm(), Tpetra::LocallyReplicated));
  MultiVector AtU(local, nc);
  AtU.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, Ug, 0.0);
  const auto rows = gatherRows(Ug, out.entries);  // (P^T U)(i, j) = rows[i * nc + j]
  // B (P^T U) = A^T U  <=>  (P^T U)^T B^T = (A^T U)^T: LU of (P^T U)^T, r right-hand sides.
  std::vector<double> PtUt(static_cast<size_t>(m) * m), rhs(static_cast<size_t>(m) * r);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) PtUt[j + static_cast<size_t>(m) * i] = rows[static_cast<size_t>(i) * nc + j];
  auto a = AtU.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int c = 0; c < r; ++c)
    for (int j = 0; j < m; ++j) rhs[j + static_cast<size_t>(m) * c] = a(c, j);
  Teuchos::LAPACK<int, double> lapack;
  std::vector<int> piv(m);
  int info = 0;
  lapack.GETRF(m, m, PtUt.data(), m, piv.data(), &info);
  GPHR_REQUIRE(info == 0, InputError, "gradient DEIM: P^T U is singular (GETRF info = ", info, ")");
  lapack.GETRS('N', m, r, PtUt.data(), m, piv.data(), rhs.data(), m, &info);
  out.B.shape(r, m);
  for (int c = 0; c < r; ++c)
    for (int j = 0; j < m; ++j) out.B(c, j) = rhs[j + static_cast<size_t>(m) * c];
  out.conditionNumber = deimConditionNumber(Ug, out.entries);
  return out;
}

namespace {
// A A^T Y: states projected on the reduced basis (A orthonormal).
RCP<MultiVector> projectOnto(const MultiVector& A, const MultiVector& Y) {
  const int r = static_cast<int>(A.getNumVectors());
  auto local = rcp(new Map(r, 0, A.getMap()->getComm(), Tpetra::LocallyReplicated));
  MultiVector Z(local, Y.getNumVectors());
  Z.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, Y, 0.0);
  auto P = rcp(new MultiVector(Y.getMap(), Y.getNumVectors()));
  P->multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, A, Z, 0.0);
  return P;
}
}  // namespace

GradientDeimPair withReferenceGradient(GradientDeimPair pair, const HamiltonianSystem& system, const MultiVector& A) {
  const int r = static_cast<int>(A.getNumVectors()), m = static_cast<int>(pair.entries.size());
  GPHR_REQUIRE(pair.B.numRows() == r && pair.B.numCols() == m, InputError, "gradient DEIM: the pair is ",
               pair.B.numRows(), " x ", pair.B.numCols(), " for a basis of ", r, " columns and ", m, " entries");
  Vector zero(system.map()), g0(system.map());
  system.nonlinearGradient(zero, g0);
  auto local = rcp(new Map(r, 0, A.getMap()->getComm(), Tpetra::LocallyReplicated));
  MultiVector Atg(local, 1);
  Atg.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, g0, 0.0);
  const auto g0P = gatherRows(g0, pair.entries);
  auto a = Atg.getLocalViewHost(Tpetra::Access::ReadOnly);
  pair.offset.size(r);
  for (int i = 0; i < r; ++i) {
    double s = a(i, 0);
    for (int j = 0; j < m; ++j) s -= pair.B(i, j) * g0P[j];
    pair.offset(i) = s;
  }
  return pair;
}

RCP<MultiVector> gradientDeimBasis(const SystemSet& systems,
                                   const SnapshotSet& states, const MultiVector& A,
                                   int maxRank, int snapshotEvery, GradientSnapshots kind,
                                   std::vector<double>* singularValues) {
  GPHR_REQUIRE(snapshotEvery >= 1, InputError, "gradient DEIM: snapshotEvery = ", snapshotEvery, " (need >= 1)");
  const auto& map = systems[0]->map();
  const bool projected = kind == GradientSnapshots::Projected;
  constexpr int kPodColumns = 64;  // per POD step
  static_assert(kSnapshotReadColumns % kPodColumns == 0, "a read must end on a POD step");
  StreamingPod pod(map, static_cast<int>(std::min<GO>(maxRank, map->getGlobalNumElements())), kPodColumns);
  Vector zero(map), g0(map);
  for (size_t j = 0; j < systems.size(); ++j) {
    if (!projected) systems[j]->nonlinearGradient(zero, g0);  // grad N at the training system's y0
    const size_t every = static_cast<size_t>(snapshotEvery), usedInBlock = (states.numColumns(j) + every - 1) / every;
    // Only the used states are read, kSnapshotReadColumns at a time (a multiple of the POD's
    // columns per step, so its steps are those of the whole block).
    for (size_t u0 = 0; u0 < usedInBlock; u0 += kSnapshotReadColumns) {
      RCP<const MultiVector> Y = states.columns(j, every, u0, std::min(kSnapshotReadColumns, usedInBlock - u0));
      if (projected) Y = projectOnto(A, *Y);
      const size_t used = Y->getNumVectors();
      MultiVector G(map, used);
      for (size_t c = 0; c < used; ++c) systems[j]->nonlinearGradient(*Y->getVector(c), *G.getVectorNonConst(c));
      if (!projected)  // minus grad N at y0
        for (size_t c = 0; c < used; ++c) G.getVectorNonConst(c)->update(-1.0, g0, 1.0);
      pod.add(G);
    }
  }
  GPHR_REQUIRE(pod.rank() > 0, InputError, "gradient DEIM: every grad N snapshot is zero (nothing to hyper-reduce)");
  if (singularValues) *singularValues = pod.singularValues();
  return rcp(new MultiVector(pod.leftVectors(), Teuchos::Copy));
}

GradientDeimModel::GradientDeimModel(const HamiltonianSystem& system, const MultiVector& A,
                                     const GradientDeimPair& pair, ReducedLinearPart linear)
    : linear_(std::move(linear)), B_(pair.B), offset_(pair.offset) {
  GPHR_REQUIRE(offset_.length() == 0 || offset_.length() == linear_.L.numRows(), InputError,
               "gradient DEIM: an offset of ", offset_.length(), " entries for a reduced dimension of ",
               linear_.L.numRows());
  const NonlinearTerm& term = system.nonlinearTerm();
  std::vector<GO> sorted(pair.entries);
  std::sort(sorted.begin(), sorted.end());
  const auto rows = rowsTouching(term, sorted);
  const auto v = gatherWeights(term, rows);
  SampleMesh mesh = buildSampleMesh(system, A, rows, v, ReducedLinearPart());
  for (GO gid : mesh.sample.stencil.gids) {
    const auto it = std::find(pair.entries.begin(), pair.entries.end(), gid);
    entrySlot_.push_back(it == pair.entries.end() ? -1 : static_cast<int>(it - pair.entries.begin()));
  }
  rows_ = rcp(new ReducedRowKernel(system.nonlinearTermPtr(), mesh.sample, Teuchos::null));
  gP_.resize(pair.entries.size());
  hP_.resize(pair.entries.size() * static_cast<size_t>(dim()));
}

double GradientDeimModel::hamiltonian(const DenseVector&) { return std::numeric_limits<double>::quiet_NaN(); }

void GradientDeimModel::gradient(const DenseVector& z, DenseVector& g) {
  rows_->evaluate(z, true, false);
  rows_->entryGradients(entrySlot_, static_cast<int>(gP_.size()), gP_.data());
  g.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, linear_.L, z, 0.0);
  g += linear_.f;
  if (offset_.length() > 0) g += offset_;
  for (int i = 0; i < dim(); ++i)
    for (size_t j = 0; j < gP_.size(); ++j) g(i) += B_(i, static_cast<int>(j)) * gP_[j];
}

void GradientDeimModel::addHessian(const DenseVector& z, double scale, DenseMatrix& H) {
  rows_->evaluate(z, false, true);
  const int r = dim(), m = static_cast<int>(gP_.size());
  rows_->entryHessianRows(entrySlot_, m, hP_.data());
  for (int c = 0; c < r; ++c)
    for (int i = 0; i < r; ++i) {
      double s = linear_.L(i, c);
      for (int j = 0; j < m; ++j) s += B_(i, j) * hP_[static_cast<size_t>(j) * r + c];
      H(i, c) += scale * s;
    }
}

}  // namespace gphr
