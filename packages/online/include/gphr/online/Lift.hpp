#pragma once
/// @file
/// The lift of reduced states to physical ones, y = y0 + A z: at a few probe entries (dense, what
/// a query holds) and whole states in batches (one GEMM per batch of saved states; O(n k) each,
/// only where whole states are asked for).
#include <vector>

#include "gphr/core/DenseTypes.hpp"
#include "gphr/core/Types.hpp"

namespace gphr {

/// The lifted physical state at probe entries: out = reference + rows z (rows: probes x 2k, row-major).
void liftProbes(const std::vector<double>& reference, const std::vector<double>& rows, const DenseVector& z,
                std::vector<double>& out);

/// Y(:, c) = A z_c (+ reference, when given) for c < count, z_c the c-th run of 2k numbers in z.
/// Z is a work MultiVector of at least `count` columns on a locally replicated map of 2k rows, Y one
/// of at least `count` columns on A's map. Collective over A's communicator.
void liftStates(const MultiVector& A, const Vector* reference, const double* z, int count, MultiVector& Z,
                MultiVector& Y);

/// A locally replicated work MultiVector for liftStates: 2k rows (A's columns), `columns` columns.
RCP<MultiVector> liftWorkspace(const MultiVector& A, int columns);

}  // namespace gphr
