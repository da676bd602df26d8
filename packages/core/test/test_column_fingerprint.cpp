// columnFingerprint / fingerprintMatches: X^T w against the sum written out over all global rows
// (every rank knows X and w by formula), on 1, 2 and 3 ranks; a changed entry is refused, a
// round-off perturbation is not.
#include <gtest/gtest.h>

#include <Tpetra_Core.hpp>
#include <cmath>

#include "gphr/core/ColumnFingerprint.hpp"
#include "gphr/core/IndexHash.hpp"

namespace gphr {
namespace {

constexpr GO kRows = 257;  // uneven rows per rank on 2 and 3 ranks
double entry(GO i, size_t j) { return std::sin(0.37 * static_cast<double>(i) + 1.3 * static_cast<double>(j)); }
double weight(GO i) {  // w_i as ColumnFingerprint.hpp defines it
  return static_cast<double>(hashIndex(0, static_cast<unsigned long long>(i)) >> 11) * 0x1.0p-52 - 1.0;
}

MultiVector columns() {
  auto map = rcp(new Map(kRows, 0, Tpetra::getDefaultComm()));
  MultiVector X(map, 3);
  for (LO l = 0; l < static_cast<LO>(map->getNodeNumElements()); ++l)
    for (size_t j = 0; j < 3; ++j) X.replaceLocalValue(l, j, entry(map->getGlobalElement(l), j));
  return X;
}

// The sums have 257 terms of size <= 1: in another order they differ by ~sqrt(257) eps ~ 4e-15.
TEST(ColumnFingerprint, IsXTransposeWOnAnyRankCount) {
  const MultiVector X = columns();
  double wNorm = 0.0;
  const auto f = columnFingerprint(X, &wNorm);
  ASSERT_EQ(f.size(), 3u);
  double w2 = 0.0;
  for (GO i = 0; i < kRows; ++i) w2 += weight(i) * weight(i);
  EXPECT_NEAR(wNorm, std::sqrt(w2), 1e-13);
  for (size_t j = 0; j < 3; ++j) {
    double expected = 0.0;
    for (GO i = 0; i < kRows; ++i) expected += entry(i, j) * weight(i);
    EXPECT_NEAR(f[j], expected, 1e-13) << "column " << j;
  }
  EXPECT_TRUE(fingerprintMatches(f, X));
}

TEST(ColumnFingerprint, RefusesAChangedEntryNotRoundOff) {
  MultiVector X = columns();
  const auto f = columnFingerprint(X);
  const GO i = 200;  // owned by the last rank on 2 and 3 ranks
  const LO l = X.getMap()->getLocalElement(i);
  const double x = entry(i, 1);
  // 1e-13 relative to the entry: round-off of a sum of this size; 1e-6: a changed value
  // (w_200 = -0.325 moves the fingerprint by 3.2e-7, against the tolerance 1e-9 ||w|| ||x_1|| = 1.05e-7).
  if (l != Teuchos::OrdinalTraits<LO>::invalid()) X.replaceLocalValue(l, 1, x * (1.0 + 1e-13));
  EXPECT_TRUE(fingerprintMatches(f, X));
  if (l != Teuchos::OrdinalTraits<LO>::invalid()) X.replaceLocalValue(l, 1, x + 1e-6);
  EXPECT_FALSE(fingerprintMatches(f, X));
  EXPECT_FALSE(fingerprintMatches(std::vector<double>(f.begin(), f.end() - 1), X));  // a column missing
}

}  // namespace
}  // namespace gphr
