#include "gphr/online/Lift.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

void liftProbes(const std::vector<double>& reference, const std::vector<double>& rows, const DenseVector& z,
                std::vector<double>& out) {
  const size_t r = static_cast<size_t>(z.length());
  out.assign(reference.begin(), reference.end());
  for (size_t i = 0; i < out.size(); ++i)
    for (size_t j = 0; j < r; ++j) out[i] += rows[i * r + j] * z(static_cast<int>(j));
}

RCP<MultiVector> liftWorkspace(const MultiVector& A, int columns) {
  const auto local = rcp(new Map(A.getNumVectors(), 0, A.getMap()->getComm(), Tpetra::LocallyReplicated));
  return rcp(new MultiVector(local, static_cast<size_t>(columns)));
}

void liftStates(const MultiVector& A, const Vector* reference, const double* z, int count, MultiVector& Z,
                MultiVector& Y) {
  const int r = static_cast<int>(A.getNumVectors());
  GPHR_REQUIRE(count >= 1 && static_cast<size_t>(count) <= Z.getNumVectors() &&
                   static_cast<size_t>(count) <= Y.getNumVectors() && Z.getLocalLength() == static_cast<size_t>(r),
               std::logic_error, "liftStates: ", count, " states into work spaces of ", Z.getNumVectors(), " and ",
               Y.getNumVectors(), " columns");
  {
    auto v = Z.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (int c = 0; c < count; ++c)
      for (int i = 0; i < r; ++i) v(i, c) = z[static_cast<size_t>(c) * r + i];
  }
  const auto Zc = Z.subView(Teuchos::Range1D(0, count - 1));
  auto Yc = Y.subViewNonConst(Teuchos::Range1D(0, count - 1));
  Yc->multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, A, *Zc, 0.0);
  if (reference)
    for (int c = 0; c < count; ++c) Yc->getVectorNonConst(c)->update(1.0, *reference, 1.0);
}

}  // namespace gphr
