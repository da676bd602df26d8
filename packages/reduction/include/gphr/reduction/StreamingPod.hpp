#pragma once
// A streaming POD (incremental thin SVD) of a tall matrix given block by block on any Tpetra
// map: only the current rank-r factor U diag(sigma) and one block are ever held.
//   add(X):   Y = [U diag(sigma), X];  TSQR  Y = Q R  (Tpetra::TsqrAdaptor);  R = W S Z^T (LAPACK);
//             U <- Q W(:, 1:r'),  sigma <- S(1:r'),  r' = min(maxRank, numerical rank).
// With every column in one block it is the exact thin SVD; truncating to maxRank between blocks
// is the incremental SVD of libROM / Brand 2002 (error bounded by the discarded sigma's).
// Steps take blockColumns columns each, on any rank count, so the truncations and the result are
// the same on 1, 2 or 3 ranks up to round-off. TSQR needs (carried + new columns) <= rows on
// every rank; a step where they do not fit (few rows per rank, or a rank close to d) gathers
// [U diag(sigma), X] on every rank and takes one LAPACK SVD there (d x columns numbers): the
// redistribution route, exact, for d up to ~1e5 at the paper's ranks.
#include <vector>

#include "gphr/core/Types.hpp"

namespace gphr {

class StreamingPod {
 public:
  // maxRank: singular triplets kept between steps; blockColumns: new columns per step;
  // rankTolerance: sigma_j <= rankTolerance * sigma_1 are dropped (< 0: columns * machine eps,
  // LAPACK's numerical rank; 0: keep every nonzero one).
  StreamingPod(RCP<const Map> map, int maxRank, int blockColumns, double rankTolerance = -1.0);

  void add(const MultiVector& X);  // collective; X on map()
  const RCP<const Map>& map() const { return map_; }
  int rank() const { return static_cast<int>(sigma_.size()); }
  // Left singular vectors (map x rank(); an empty MultiVector of one zero column while rank() == 0).
  const MultiVector& leftVectors() const { return *U_; }
  const std::vector<double>& singularValues() const { return sigma_; }
  double totalEnergy() const { return energy_; }  // ||all columns added||_F^2
  long columnsAdded() const { return columns_; }
  int blockColumns() const { return blockColumns_; }

 private:
  void step(const MultiVector& X, size_t c0, size_t c1);
  void replicatedStep(const MultiVector& Y);
  int truncate(const std::vector<double>& S, int nc);
  RCP<const Map> map_;
  int maxRank_, blockColumns_;
  double rankTolerance_;
  int cap_;
  RCP<MultiVector> U_;
  std::vector<double> sigma_;
  double energy_ = 0.0;
  long columns_ = 0;
};

}  // namespace gphr
