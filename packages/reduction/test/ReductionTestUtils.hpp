#pragma once
// Snapshot and basis helpers shared by the reduction tests.
#include <Teuchos_DefaultMpiComm.hpp>
#include <mpi.h>

#include "TestUtils.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/timeint/FullModelIntegrator.hpp"

namespace gphr::test {

// Every state of a full-model run (the system's own, e.g. shifted, coordinates).
inline RCP<const MultiVector> fomSnapshots(const SceneInstance& s, const std::string& scheme, double dt, long steps) {
  Teuchos::ParameterList pl("integrator");
  pl.set("scheme", scheme);
  pl.set("newtonTolerance", 1e-12);
  FullModelIntegrator integ(s.system, pl);
  Vector y(*s.y0, Teuchos::Copy);
  auto snaps = rcp(new MultiVector(s.system->map(), steps + 1));
  integ.run(y, dt, steps, [&](long j, double, const Vector& yj, const StepReport&) {
    Tpetra::deep_copy(*snaps->getVectorNonConst(j), yj);
  });
  return snaps;
}

// A^T X as a dense replicated array (row-major i*cols + j).
inline std::vector<double> transposeTimes(const MultiVector& A, const MultiVector& X) {
  auto local = rcp(new Map(A.getNumVectors(), 0, A.getMap()->getComm(), Tpetra::LocallyReplicated));
  MultiVector C(local, X.getNumVectors());
  C.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, A, X, 0.0);
  auto c = C.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<double> out(A.getNumVectors() * X.getNumVectors());
  for (size_t i = 0; i < A.getNumVectors(); ++i)
    for (size_t j = 0; j < X.getNumVectors(); ++j) out[i * X.getNumVectors() + j] = c(i, j);
  return out;
}

// max |U^T U - I| (collective, the same on every rank): subspaceDistance below measures angles
// only for orthonormal bases (it is 0 for any U_a inside span U_b, scaled or not), so the tests
// check this beside it.
inline double orthonormalityError(const MultiVector& U) {
  const int m = static_cast<int>(U.getNumVectors());
  auto local = rcp(new Map(m, 0, U.getMap()->getComm(), Tpetra::LocallyReplicated));
  MultiVector G(local, m);
  G.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, U, U, 0.0);
  auto g = G.getLocalViewHost(Tpetra::Access::ReadOnly);
  double e = 0.0;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) e = std::max(e, std::abs(g(i, j) - (i == j ? 1.0 : 0.0)));
  return e;
}

// ||U_a - U_b (U_b^T U_a)||_F = ||sin Theta(U_a, U_b)||_F for orthonormal U_a, U_b with as many
// columns (collective, the same on every rank). Formed from the residual, not from the cosines,
// so that angles down to round-off are resolved.
inline double subspaceDistance(const MultiVector& Ua, const MultiVector& Ub) {
  auto local = rcp(new Map(Ub.getNumVectors(), 0, Ua.getMap()->getComm(), Tpetra::LocallyReplicated));
  MultiVector C(local, Ua.getNumVectors());
  C.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, Ub, Ua, 0.0);
  MultiVector R(Ua, Teuchos::Copy);
  R.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, -1.0, Ub, C, 1.0);
  std::vector<double> nrm(R.getNumVectors());
  R.norm2(Teuchos::ArrayView<double>(nrm));
  double sum = 0.0;
  for (double x : nrm) sum += x * x;
  return std::sqrt(sum);
}

// All columns of X gathered to rank 0 in global-id order (row-major: column j at j*N).
inline std::vector<double> gatherColumns(const MultiVector& X) {
  const GO N = X.getGlobalLength();
  auto comm = X.getMap()->getComm();
  auto root = rcp(new Map(N, comm->getRank() == 0 ? N : 0, 0, comm));
  MultiVector all(root, X.getNumVectors());
  all.doImport(X, Import(X.getMap(), root), Tpetra::INSERT);
  std::vector<double> out;
  auto v = all.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t j = 0; j < X.getNumVectors(); ++j)
    for (size_t i = 0; i < v.extent(0); ++i) out.push_back(v(i, j));
  return out;
}

// A communicator holding rank 0 alone (null on the other ranks).
inline RCP<const Comm> serialComm() {
  MPI_Comm sub;
  const int rank = comm()->getRank();
  MPI_Comm_split(MPI_COMM_WORLD, rank == 0 ? 0 : MPI_UNDEFINED, 0, &sub);
  if (rank != 0) return Teuchos::null;
  return rcp(new Teuchos::MpiComm<int>(Teuchos::opaqueWrapper(sub, MPI_Comm_free)));
}

}  // namespace gphr::test
