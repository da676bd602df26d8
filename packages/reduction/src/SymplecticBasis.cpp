#include "gphr/reduction/SymplecticBasis.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Tpetra_TsqrAdaptor.hpp>

#include <cmath>
#include <complex>

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {

using cplx = std::complex<double>;
using Dense = Teuchos::SerialDenseMatrix<int, double>;

// Real representation: a complex n-vector a + i b is the state-map vector [a; b]; multiplying
// by i is J^T, and the complex inner product is <x, y> = x^T y + i x^T J y.
//
// One incremental step on Y = [sigma_j e_j (carried), new columns] (2n x m):
//  1. X = [Y, J^T Y] spans a J-invariant space; TSQR: X = Qx Rx (needs 2m <= 2 n_local rows).
//  2. Real SVD Rx = W S Z^T: the left singular vectors Qx W of X come in pairs {u, J^T u} with
//     equal singular values (those of the complex data matrix).
//  3. Complex Gram-Schmidt of W's columns in order, in the 2m-dim coordinates, with
//     M = Qx^T J Qx: a column that is (the partner of) an accepted one is dropped, the others
//     are the complex left singular vectors. Keep the leading `keep`.
void svdStep(const PhaseSpace& ps, MultiVector& E, std::vector<double>& sigma, const MultiVector& Y, int keep) {
  const int m = static_cast<int>(Y.getNumVectors());
  const auto& map = ps.map();
  MultiVector X(map, 2 * m), Qx(map, 2 * m), JQ(map, 2 * m);
  {
    MultiVector JtY(map, m);
    ps.applyJT(Y, JtY);
    auto x = X.getLocalViewHost(Tpetra::Access::OverwriteAll);
    auto y = Y.getLocalViewHost(Tpetra::Access::ReadOnly);
    auto jy = JtY.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t i = 0; i < x.extent(0); ++i)
      for (int j = 0; j < m; ++j) x(i, j) = y(i, j), x(i, m + j) = jy(i, j);
  }
  Dense R(2 * m, 2 * m);
  Tpetra::TsqrAdaptor<MultiVector> tsqr;
  tsqr.factorExplicit(X, Qx, R);
  ps.applyJ(Qx, JQ);
  // M = Qx^T J Qx (replicated, one GEMM + reduction in Tpetra).
  const int mm = 2 * m;
  auto local = rcp(new Map(mm, 0, ps.comm(), Tpetra::LocallyReplicated));
  MultiVector Mmv(local, mm);
  Mmv.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, Qx, JQ, 0.0);
  std::vector<double> Mv(mm * mm);
  {
    auto mv = Mmv.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (int a = 0; a < mm; ++a)
      for (int b = 0; b < mm; ++b) Mv[a + mm * b] = mv(a, b);
  }
  // Real SVD of R: R = W S Z^T.
  std::vector<double> S(mm), W(mm * mm), work(1), Z(1);
  int info = 0;
  Teuchos::LAPACK<int, double> lapack;
  double wq = 0.0;
  lapack.GESVD('A', 'N', mm, mm, R.values(), R.stride(), S.data(), W.data(), mm, Z.data(), 1, &wq, -1, nullptr, &info);
  work.resize(std::max(1, static_cast<int>(wq)));
  lapack.GESVD('A', 'N', mm, mm, R.values(), R.stride(), S.data(), W.data(), mm, Z.data(), 1, work.data(),
               static_cast<int>(work.size()), nullptr, &info);
  GPHR_REQUIRE(info == 0, SolverError, "symplectic basis: LAPACK GESVD failed (info = ", info, ")");
  // Complex Gram-Schmidt in coordinates: <x, y> = x^T y + i x^T M y; i x <-> M^T x. M^T e of
  // each accepted e is computed once.
  std::vector<std::vector<double>> acc, accI;
  std::vector<double> accSigma;
  auto Mt = [&](const std::vector<double>& x) {
    std::vector<double> out(mm, 0.0);
    for (int a = 0; a < mm; ++a) {
      const double* col = &Mv[mm * a];  // column a of M = row a of M^T
      double sum = 0.0;
      for (int b = 0; b < mm; ++b) sum += col[b] * x[b];
      out[a] = sum;
    }
    return out;
  };
  for (int j = 0; j < mm && static_cast<int>(acc.size()) < keep && S[j] > 0.0; ++j) {
    std::vector<double> xi(W.begin() + mm * j, W.begin() + mm * (j + 1));
    for (int pass = 0; pass < 2; ++pass)  // twice is enough (Kahan-Parlett)
      for (size_t l = 0; l < acc.size(); ++l) {
        const auto& e = acc[l];
        const auto& ie = accI[l];
        double re = 0.0, im = 0.0;
        for (int a = 0; a < mm; ++a) re += e[a] * xi[a], im += ie[a] * xi[a];
        for (int a = 0; a < mm; ++a) xi[a] -= re * e[a] + im * ie[a];
      }
    double nrm = 0.0;
    for (double v : xi) nrm += v * v;
    nrm = std::sqrt(nrm);
    if (nrm < 0.5) continue;  // in the complex span of accepted vectors: a partner
    for (double& v : xi) v /= nrm;
    accI.push_back(Mt(xi));
    acc.push_back(std::move(xi));
    accSigma.push_back(S[j]);
  }
  const int kept = static_cast<int>(acc.size());
  sigma = accSigma;
  // E = Qx Xi (one GEMM).
  MultiVector Xi(local, std::max(kept, 1));
  {
    auto xv = Xi.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (int j = 0; j < kept; ++j)
      for (int a = 0; a < mm; ++a) xv(a, j) = acc[j][a];
  }
  E = MultiVector(map, std::max(kept, 1));
  E.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, Qx, Xi, 0.0);
}

// Fix the free phase of each complex singular vector (a sign for the cotangent lift): rotate
// e_j so that sum_g w_g (a + i b)_g is real and positive, with fixed weights w_g = 1 + sin(g)/2
// of the global dof id. The weighted sum is a continuous function of e_j, so the result is the
// same on any rank count (an argmax-based rule could flip under round-off).
void normalizePhase(const PhaseSpace& ps, MultiVector& E, int k, bool cotangent) {
  const LO nl = ps.numLocalDofs();
  auto e = E.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (int j = 0; j < k; ++j) {
    double loc[2] = {0.0, 0.0}, glob[2] = {0.0, 0.0};
    for (LO i = 0; i < nl; ++i) {
      const double w = 1.0 + 0.5 * std::sin(static_cast<double>(ps.firstLocalDof() + i));
      loc[0] += w * e(i, j);
      loc[1] += w * e(nl + i, j);
    }
    Teuchos::reduceAll(*ps.comm(), Teuchos::REDUCE_SUM, 2, loc, glob);
    cplx rot = std::conj(cplx(glob[0], glob[1]));
    rot = std::abs(rot) > 0 ? rot / std::abs(rot) : cplx(1.0, 0.0);
    for (LO i = 0; i < nl; ++i) {
      const cplx u = cplx(e(i, j), e(nl + i, j)) * rot;
      e(i, j) = u.real();
      e(nl + i, j) = cotangent ? 0.0 : u.imag();  // cotangent: e_j = [phi; 0] up to round-off
    }
  }
}

}  // namespace

ReducedBasis computeSymplecticBasis(const std::vector<RCP<const MultiVector>>& snapshots, const PhaseSpace& space,
                                    const BasisOptions& opt) {
  GPHR_REQUIRE(opt.method == "psd" || opt.method == "cotangent", InputError, "basis method '", opt.method,
               "' is not one of 'psd', 'cotangent'");
  GPHR_REQUIRE(!snapshots.empty(), InputError, "symplectic basis: no snapshots");
  const bool cot = opt.method == "cotangent";
  const LO nl = space.numLocalDofs();
  // TSQR needs 2m <= 2 n_local rows on every rank, m = carried + new columns.
  LO minLocal = 0;
  Teuchos::reduceAll(*space.comm(), Teuchos::REDUCE_MIN, nl, Teuchos::outArg(minLocal));
  const int perSnap = cot ? 2 : 1;
  const int cap = static_cast<int>(minLocal);
  // Kept between steps: given, or 2k + 32 when k is given (margin for the leading k), at most
  // half the smallest rank's dofs (room for new columns).
  const int autoRank = opt.k > 0 ? std::min(std::max(1, cap / 2), 2 * opt.k + 32) : std::max(1, cap / 2);
  const int maxRank = std::min(opt.maxRank > 0 ? opt.maxRank : std::max(autoRank, opt.k), cap);
  GPHR_REQUIRE(cap >= perSnap, InputError, "symplectic basis: ", cap,
               " degrees of freedom on the smallest rank are too few (use fewer ranks)");

  MultiVector E(space.map(), 1);
  std::vector<double> sigma;
  double energy = 0.0;
  for (const auto& Ys : snapshots) {
    std::vector<double> nrm(Ys->getNumVectors());
    Ys->norm2(Teuchos::ArrayView<double>(nrm));
    for (double x : nrm) energy += x * x;
    for (size_t c0 = 0; c0 < Ys->getNumVectors();) {
      // Columns this step may take: carried + new <= cap; make room by dropping the smallest
      // carried singular triplets when needed (the truncation of the incremental SVD).
      if (static_cast<int>(sigma.size()) + perSnap > cap) sigma.resize(cap - perSnap);
      const int room = (cap - static_cast<int>(sigma.size())) / perSnap;
      const size_t c1 = std::min(Ys->getNumVectors(), c0 + std::min(opt.blockColumns, room));
      const int r = static_cast<int>(sigma.size()), b = static_cast<int>(c1 - c0) * perSnap;
      MultiVector Y(space.map(), r + b);
      {
        auto y = Y.getLocalViewHost(Tpetra::Access::OverwriteAll);
        auto ev = E.getLocalViewHost(Tpetra::Access::ReadOnly);
        auto sv = Ys->getLocalViewHost(Tpetra::Access::ReadOnly);
        for (int j = 0; j < r; ++j)
          for (LO i = 0; i < 2 * nl; ++i) y(i, j) = sigma[j] * ev(i, j);
        for (size_t c = c0; c < c1; ++c) {
          const int j = r + static_cast<int>(c - c0) * perSnap;
          for (LO i = 0; i < nl; ++i) {
            if (!cot) {
              y(i, j) = sv(i, c), y(nl + i, j) = sv(nl + i, c);  // [q; p]  <->  q + i p
            } else {
              y(i, j) = sv(i, c), y(i, j + 1) = sv(nl + i, c);  // [q; 0], [p; 0]  <->  [Q, P]
              y(nl + i, j) = y(nl + i, j + 1) = 0.0;
            }
          }
        }
      }
      svdStep(space, E, sigma, Y, maxRank);
      c0 = c1;
    }
  }
  ReducedBasis out;
  out.method = opt.method;
  out.singularValues = sigma;
  int k = opt.k;
  if (k <= 0) {  // smallest k whose discarded energy fraction is <= tolerance
    double captured = 0.0;
    for (k = 0; k < static_cast<int>(sigma.size()) && 1.0 - captured / energy > opt.energyTolerance; ++k)
      captured += sigma[k] * sigma[k];
  }
  GPHR_REQUIRE(k >= 1 && k <= static_cast<int>(sigma.size()), InputError, "symplectic basis: k = ", k,
               " is not available: the snapshots give ", sigma.size(), " singular vectors (at most ", maxRank,
               " are kept)");
  double captured = 0.0;
  for (int j = 0; j < k; ++j) captured += sigma[j] * sigma[j];
  out.energyCaptured = energy > 0 ? captured / energy : 1.0;
  out.k = k;
  normalizePhase(space, E, k, cot);
  out.A = rcp(new MultiVector(space.map(), 2 * k));
  auto a = out.A->getLocalViewHost(Tpetra::Access::OverwriteAll);
  auto e = E.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (int j = 0; j < k; ++j)
    for (LO i = 0; i < nl; ++i) {
      a(i, j) = e(i, j);            // column j     = [Phi; Psi]
      a(nl + i, j) = e(nl + i, j);
      a(i, k + j) = -e(nl + i, j);  // column k + j = J^T [Phi; Psi] = [-Psi; Phi]
      a(nl + i, k + j) = e(i, j);
    }
  return out;
}

}  // namespace gphr
