#pragma once
/// @file
/// The small dense types of the reduced and hyper-reduced models (replicated on every rank, of
/// size 2k): Teuchos' serial dense vector and matrix, and the canonical symplectic J_{2k}.
#include <Teuchos_SerialDenseMatrix.hpp>
#include <Teuchos_SerialDenseVector.hpp>

namespace gphr {

using DenseVector = Teuchos::SerialDenseVector<int, double>;  ///< Small dense vector (Teuchos), a reduced state z.
using DenseMatrix = Teuchos::SerialDenseMatrix<int, double>;  ///< Small dense matrix (Teuchos, column-major).

/// out = J_{2k} x: out_q = x_p, out_p = -x_q.
void applyCanonicalJ(const DenseVector& x, DenseVector& out);

}  // namespace gphr
