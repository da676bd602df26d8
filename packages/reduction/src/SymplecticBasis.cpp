#include "gphr/reduction/SymplecticBasis.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <cmath>
#include <complex>

#include "gphr/core/CacheKey.hpp"
#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/reduction/StreamingPod.hpp"

namespace gphr {

namespace {

// Complex triplets kept between steps when k comes from the energy tolerance.
constexpr int kAutoRank = 512;

using cplx = std::complex<double>;
using Dense = Teuchos::SerialDenseMatrix<int, double>;

// Real representation: a complex n-vector a + i b is the state-map vector [a; b]; multiplying
// by i is J^T, and the complex inner product is <x, y> = x^T y + i x^T J y.
//
// The real matrix X = [D, J^T D] of the data columns D spans a J-invariant space and its
// left singular vectors come in pairs {u, J^T u} with equal singular values, those of the complex
// data matrix. The streaming POD gives them (U, sigma); a complex Gram-Schmidt of U's columns in
// order, in U's coordinates with M = U^T J U, drops the partner of each accepted vector and keeps
// the leading `keep` complex left singular vectors E = U Xi.
void complexLeftVectors(const PhaseSpace& ps, const MultiVector& U, const std::vector<double>& S, int keep,
                        MultiVector& E, std::vector<double>& sigma) {
  const int mm = static_cast<int>(S.size());
  const auto& map = ps.map();
  MultiVector JU(map, std::max(mm, 1));
  ps.applyJ(U, JU);
  auto local = rcp(new Map(std::max(mm, 1), 0, ps.comm(), Tpetra::LocallyReplicated));
  MultiVector Mmv(local, std::max(mm, 1));
  Mmv.multiply(Teuchos::TRANS, Teuchos::NO_TRANS, 1.0, U, JU, 0.0);  // M = U^T J U (one GEMM + reduction)
  std::vector<double> Mv(static_cast<size_t>(mm) * mm);
  {
    auto mv = Mmv.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (int a = 0; a < mm; ++a)
      for (int b = 0; b < mm; ++b) Mv[a + static_cast<size_t>(mm) * b] = mv(a, b);
  }
  // <x, y> = x^T y + i x^T M y; i x <-> M^T x, computed once per accepted vector.
  std::vector<std::vector<double>> acc, accI;
  std::vector<double> accSigma;
  auto Mt = [&](const std::vector<double>& x) {
    std::vector<double> out(mm, 0.0);
    for (int a = 0; a < mm; ++a) {
      const double* col = &Mv[static_cast<size_t>(mm) * a];  // column a of M = row a of M^T
      double sum = 0.0;
      for (int b = 0; b < mm; ++b) sum += col[b] * x[b];
      out[a] = sum;
    }
    return out;
  };
  for (int j = 0; j < mm && static_cast<int>(acc.size()) < keep && S[j] > 0.0; ++j) {
    std::vector<double> xi(mm, 0.0);
    xi[j] = 1.0;
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
  MultiVector Xi(local, std::max(kept, 1));
  {
    auto xv = Xi.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (int j = 0; j < kept; ++j)
      for (int a = 0; a < mm; ++a) xv(a, j) = acc[j][a];
  }
  E = MultiVector(map, std::max(kept, 1));
  if (kept > 0) E.multiply(Teuchos::NO_TRANS, Teuchos::NO_TRANS, 1.0, U, Xi, 0.0);
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

RCP<const Map> basisPodMap(const PhaseSpace& space, const BasisOptions& opt) {
  return opt.method == "cotangent" ? space.dofMap() : space.map();
}

namespace {
// Triplets kept between steps: given, or 2k + 32 when k is given (margin for the leading k),
// or at most kAutoRank when k comes from the energy tolerance; at most n.
int keptTriplets(const BasisOptions& opt, GO n) {
  const int autoRank = opt.k > 0 ? 2 * opt.k + 32 : kAutoRank;
  return static_cast<int>(std::min<GO>(n, opt.maxRank > 0 ? opt.maxRank : std::max(autoRank, opt.k)));
}
}  // namespace

long basisRankBound(const BasisOptions& opt, GO n, long snapshots) {
  // psd PODs [D, J^T D], cotangent [Q, P]: 2 columns per state; beyond the states' own rank the
  // vectors are round-off directions, kept by design (k is the user's choice)
  return std::min<long>(2 * snapshots, keptTriplets(opt, n));
}

ReducedBasis computeSymplecticBasis(const SnapshotSet& snapshots, const PhaseSpace& space, const BasisOptions& opt,
                                    const BasisProgress* resume, const std::function<void(const BasisProgress&)>& save) {
  GPHR_REQUIRE(opt.method == "psd" || opt.method == "cotangent", InputError, "basis method '", opt.method,
               "' is not one of 'psd', 'cotangent'");
  GPHR_REQUIRE(!snapshots.empty(), InputError, "symplectic basis: no snapshots");
  GPHR_REQUIRE(opt.blockColumns >= 1, InputError, "symplectic basis: blockColumns = ", opt.blockColumns,
               " (allowed: >= 1)");
  const bool cot = opt.method == "cotangent";
  const LO nl = space.numLocalDofs();
  const int maxRank = keptTriplets(opt, space.n());
  // psd: the real POD of X = [D, J^T D], D = [q; p] per snapshot, carries both vectors of each
  // J-pair (2 maxRank). cotangent: the plain POD of [Q, P] on the n dofs (real vectors phi, so
  // A = blockdiag(Phi, Phi) holds exactly, round-off directions included).
  // Every nonzero sigma is kept (tolerance 0): k is the user's choice, even into round-off.
  StreamingPod pod(basisPodMap(space, opt), static_cast<int>(cot ? maxRank : 2 * maxRank), 2 * opt.blockColumns, 0.0,
                   podRouteFromName(opt.podRoute));
  double energy = 0.0;
  size_t first = 0;
  if (resume && resume->blocks > 0) {
    GPHR_REQUIRE(resume->blocks < snapshots.size(), InputError, "symplectic basis: resuming after ", resume->blocks,
                 " snapshot blocks of ", snapshots.size(), " (allowed: fewer than all)");
    pod.restore(resume->pod);
    energy = resume->energy, first = resume->blocks;
  }
  for (size_t block = first; block < snapshots.size(); ++block) {
    // One POD step per blockColumns snapshots, and only those read (a streamed set reads them from
    // the file): a trajectory of any length costs one chunk of memory.
    const size_t columns = snapshots.numColumns(block);
    for (size_t c0 = 0; c0 < columns; c0 += opt.blockColumns) {
      const size_t c1 = std::min(columns, c0 + static_cast<size_t>(opt.blockColumns));
      const int b = static_cast<int>(c1 - c0);
      const RCP<const MultiVector> Ys = snapshots.columns(block, 1, c0, c1 - c0);
      for (double x : columnSquaredNorms(*Ys)) energy += x;
      MultiVector X(pod.map(), 2 * b);
      auto x = X.getLocalViewHost(Tpetra::Access::OverwriteAll);
      auto sv = Ys->getLocalViewHost(Tpetra::Access::ReadOnly);
      for (int j = 0; j < b; ++j)
        for (LO i = 0; i < nl; ++i) {
          const double q = sv(i, j), p = sv(nl + i, j);
          if (cot) {
            x(i, 2 * j) = q, x(i, 2 * j + 1) = p;  // [Q, P]
          } else {  // (d, J^T d) with d = [q; p], J^T d = [-p; q]
            x(i, 2 * j) = q, x(nl + i, 2 * j) = p;
            x(i, 2 * j + 1) = -p, x(nl + i, 2 * j + 1) = q;
          }
        }
      try {
        pod.add(X);
      } catch (const InputError& e) {  // say how snapshots and triplets count as POD columns
        throw InputError(detail::concat("symplectic basis (", opt.method, ": 2 POD columns per snapshot",
                                        cot ? "" : " and per kept complex triplet", "): ", e.what()));
      }
    }
    if (save && block + 1 < snapshots.size()) save(BasisProgress{block + 1, energy, pod.state()});
  }
  MultiVector E(space.map(), 1);
  std::vector<double> sigma;
  if (cot) {
    sigma = pod.singularValues();
    E = MultiVector(space.map(), std::max(pod.rank(), 1));
    auto e = E.getLocalViewHost(Tpetra::Access::OverwriteAll);
    auto u = pod.leftVectors().getLocalViewHost(Tpetra::Access::ReadOnly);
    for (int j = 0; j < pod.rank(); ++j)
      for (LO i = 0; i < nl; ++i) e(i, j) = u(i, j), e(nl + i, j) = 0.0;  // [phi; 0]
  } else {
    complexLeftVectors(space, pod.leftVectors(), pod.singularValues(), maxRank, E, sigma);
  }
  ReducedBasis out;
  out.method = opt.method;
  out.singularValues = sigma;
  out.podSteps = pod.steps();
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

Teuchos::ParameterList basisValidParameters() {
  Teuchos::ParameterList red("reduction");
  setChoiceParameter(red, "method", "psd", Teuchos::tuple<std::string>("psd", "cotangent"),
                     "symplectic basis: psd (complex SVD, the paper's) or cotangent lift");
  setIntParameter(red, "k", 10, 0, 100000, "reduced size 2k; 0: smallest k meeting energyTolerance");
  setDoubleParameter(red, "energyTolerance", 1e-6, 0.0, 1.0, "discarded snapshot energy fraction when k = 0");
  setIntParameter(red, "blockColumns", 128, 1, 100000, "snapshot columns per incremental SVD step");
  setIntParameter(red, "maxRank", 0, 0, 1000000,
                  "singular triplets kept between incremental steps; 0: 2k + 32, or half the dofs per rank if k = 0");
  const auto names = podRouteNames();
  const Teuchos::Array<std::string> routes(names.begin(), names.end());
  setChoiceParameter(red, "podRoute", "auto", routes,
                     "incremental SVD step: auto (tree from 2 ranks: the faster measured), tsqr "
                     "(Tpetra's TSQR; refuses a step with more carried + new columns than rows on some rank), stacked "
                     "(a TSQR on LAPACK kernels: each rank's rows by a Householder QR in row chunks, the R factors "
                     "stacked on every rank and one SVD of the stack; any rank count, local work divides with the ranks), tree (as stacked, "
                     "the R factors reduced over a binary tree of ranks and one small SVD on rank 0: the work beyond "
                     "a rank's rows grows with log2 of the ranks, not with the ranks), replicated (each step's matrix "
                     "gathered on every rank, one LAPACK SVD: any rank count, no parallel speed-up)");
  return red;
}

std::string basisCacheKey(const BasisOptions& o) {
  CacheKey key("basis", 1);
  key.add("method", o.method).add("k", o.k).add("energyTolerance", o.energyTolerance);
  key.add("blockColumns", o.blockColumns).add("maxRank", o.maxRank);
  if (o.podRoute != "auto") key.add("podRoute", o.podRoute);
  return key.str();
}

BasisOptions basisOptionsFrom(const Teuchos::ParameterList& red, int k) {
  BasisOptions o;
  o.method = red.get<std::string>("method");
  o.k = k;
  o.energyTolerance = red.get<double>("energyTolerance");
  o.blockColumns = red.get<int>("blockColumns");
  o.maxRank = red.get<int>("maxRank");
  o.podRoute = red.get<std::string>("podRoute");
  return o;
}

RCP<MultiVector> leadingBasis(const ReducedBasis& basis, int k) {
  const int kb = basis.k;
  if (k == kb) return basis.A;
  Teuchos::Array<size_t> cols;
  for (int j = 0; j < k; ++j) cols.push_back(j);
  for (int j = 0; j < k; ++j) cols.push_back(kb + j);
  return rcp(new MultiVector(*basis.A->subCopy(cols())));
}

std::vector<int> basisSizes(const std::vector<int>& requested, const ReducedBasis& basis) {
  std::vector<int> ks;
  for (int k : requested) {
    if (k == 0) k = basis.k;
    GPHR_REQUIRE(k <= basis.k, InputError, "k = ", k, " is larger than the basis (k = ", basis.k, ")");
    ks.push_back(k);
  }
  return ks;
}

}  // namespace gphr
