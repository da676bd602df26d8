// The contents of a reduced-model file from the offline results (ModelFileBuilder.hpp).
#include "gphr/offline/ModelFileBuilder.hpp"

#include <Trilinos_version.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>
#include <set>

#include "gphr/core/Error.hpp"
#include "gphr/core/ParameterValidation.hpp"
#include "gphr/core/ReplicatedGather.hpp"
#include "gphr/core/Provenance.hpp"
#include "gphr/hyper/SampleMesh.hpp"
#include "gphr/reduction/Deim.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {

namespace {

// Exact L_r, f_r, c and reference rows at mu (an O(n k) projection of the full system). The
// system at mu is built on the layout of `like` (Scene::rebuild): only its values are new.
OnlineParameterData exactAt(const Scene& scene, const HamiltonianSystem& like, const MultiVector& A,
                            const StoredBasisData& b, const std::vector<double>& mu) {
  const auto inst = scene.instantiate(like, mu, true);
  OnlineParameterData d;
  d.linear = reduceLinearPart(*inst.system, A);
  d.reference = gatherRows(*inst.system->reference(), b.referenceGids);
  if (!b.indicator.empty()) d.indicator = indicatorLinearRows(*inst.system, A, b.indicator.entries);
  return d;
}

// c = H(y0(mu)) of the shifted system (no projection needed).
double exactConstant(const Scene& scene, const HamiltonianSystem& like, const std::vector<double>& mu) {
  return scene.instantiate(like, mu, true).system->constant();
}

double relativeError(const std::vector<double>& a, const std::vector<double>& b, size_t i0, size_t i1) {
  double num = 0.0, den = 0.0;
  for (size_t i = i0; i < i1; ++i) num += (a[i] - b[i]) * (a[i] - b[i]), den += b[i] * b[i];
  return den > 0.0 ? std::sqrt(num / den) : std::sqrt(num);
}

// The interpolants' largest relative error per piece at points between the nodes of every
// parameter: a scene that declared a parameter's entries wrongly shows up here.
void checkInterpolant(const Scene& scene, const HamiltonianSystem& like, const MultiVector& A, StoredBasisData& b) {
  const size_t r = 2 * static_cast<size_t>(b.k), nL = r * r, nf = nL + r;
  const size_t nr = nf + b.referenceGids.size();
  for (const char* piece : {"L", "f", "c", "reference", "indicator"}) b.interpolationError[piece] = 0.0;
  for (const auto& mu : b.constant.checkPoints(8)) {
    const auto data = exactAt(scene, like, A, b, mu), interpolated = b.at(mu);
    const auto exact = b.pack(data), approx = b.pack(interpolated);
    auto worst = [&](const char* piece, size_t i0, size_t i1) {
      b.interpolationError[piece] = std::max(b.interpolationError[piece], relativeError(approx, exact, i0, i1));
    };
    worst("L", 0, nL), worst("f", nL, nf), worst("reference", nf, nr), worst("indicator", nr, exact.size());
    const double c = std::abs(interpolated.linear.c - data.linear.c) / std::max(std::abs(data.linear.c), 1e-300);
    b.interpolationError["c"] = std::max(b.interpolationError["c"], c);
  }
}

StoredBasisData basisData(const Scene& scene, const HamiltonianSystem& like, const MultiVector& A, int k,
                          const std::vector<StoredHyperModel>& models, const ModelFileOptions& opt) {
  StoredBasisData b;
  b.k = k;
  for (GO g : opt.probes)
    GPHR_REQUIRE(g >= 0 && static_cast<size_t>(g) < A.getGlobalLength(), InputError, "probe entry ", g,
                 " is not a state entry; allowed: 0 to ", A.getGlobalLength() - 1);
  b.probeGids = opt.probes;
  b.probeRows = gatherRows(A, b.probeGids);
  std::set<GO> gids(b.probeGids.begin(), b.probeGids.end());
  for (const auto& m : models) gids.insert(m.sample.stencil.gids.begin(), m.sample.stencil.gids.end());
  b.indicator = indicatorRows(like, A, opt.indicatorDofs);
  gids.insert(b.indicator.entries.begin(), b.indicator.entries.end());
  gids.insert(b.indicator.terms.stencil.gids.begin(), b.indicator.terms.stencil.gids.end());
  b.referenceGids.assign(gids.begin(), gids.end());
  const auto& box = scene.parameterBox();
  std::vector<std::pair<double, double>> sub;
  std::vector<double> centre;
  for (size_t p = 0; p < box.bounds.size(); ++p) {
    centre.push_back(0.5 * (box.bounds[p].first + box.bounds[p].second));
    if (box.enters.at(p) & (EntersLinearPart | EntersInitialState)) b.interpolated.push_back(p), sub.push_back(box.bounds[p]);
  }
  b.interpolant = ParameterInterpolant(sub, std::vector<int>(sub.size(), opt.interpolationNodes), b.valuesPerNode());
  // c at the points instantiated for the first interpolant: where every parameter enters L_r, f_r
  // or y0 (the SWE's two), the constant's nodes are the same points and need no instance of their
  // own (49 of the SWE 256^2 build's 106 instances).
  std::map<std::vector<double>, double> constantAt;
  for (size_t j = 0; j < b.interpolant.numNodes(); ++j) {
    auto mu = centre;  // the other parameters do not change these pieces (the scene's declaration)
    const auto node = b.interpolant.node(j);
    for (size_t i = 0; i < b.interpolated.size(); ++i) mu[b.interpolated[i]] = node[i];
    const OnlineParameterData data = exactAt(scene, like, A, b, mu);
    constantAt[mu] = data.linear.c;
    b.interpolant.setNodeValues(j, b.pack(data));
  }
  b.constant = ParameterInterpolant(box.bounds, std::vector<int>(box.bounds.size(), opt.interpolationNodes), 1);
  for (size_t j = 0; j < b.constant.numNodes(); ++j) {
    const std::vector<double> mu = b.constant.node(j);
    const auto known = constantAt.find(mu);  // the same doubles: both grids come from nodeCoordinate
    b.constant.setNodeValues(j, {known != constantAt.end() ? known->second : exactConstant(scene, like, mu)});
  }
  checkInterpolant(scene, like, A, b);
  return b;
}

}  // namespace

ModelFileOptions modelFileOptionsFrom(const Teuchos::ParameterList& build) {
  ModelFileOptions o;
  for (int g : build.get<Teuchos::Array<int>>("probes")) o.probes.push_back(g);
  o.interpolationNodes = build.get<int>("interpolationNodes");
  o.indicatorDofs = build.get<int>("indicatorDofs");
  o.targetError = build.get<double>("targetError");
  return o;
}

Teuchos::ParameterList modelFileValidParameters() {
  Teuchos::ParameterList bld("build");
  bld.set("withBasis", false,
          "gphr build: also store the full basis A (2n x 2k numbers per k) in the model file, for the exact "
          "set-up route and for lifting whole states; without it the file holds nothing of size n or d");
  bld.set("probes", Teuchos::Array<int>(),
          "gphr build: state entries (global ids 0..2n-1, q then p) whose lifted values queries can report "
          "(only these rows of A are stored)");
  setIntParameter(bld, "interpolationNodes", 7, 2, 33,
                  "gphr build: Chebyshev-Lobatto nodes per parameter of the interpolant of L_r, f_r, c and the "
                  "reference rows over the box (the n-independent set-up route of a query; its error is reported)");
  setIntParameter(bld, "indicatorDofs", 16, 0, 4096,
                  "gphr build: degrees of freedom (spread evenly over the n) whose q and p entries carry the online "
                  "error indicator of every query (doc/error-estimate.md): its cost per step grows with them, "
                  "not with n; 0: no indicator, no error estimate");
  setDoubleParameter(bld, "targetError", 0.0, 0.0, 0.999,
                     "gphr build: train greedily until the best model's estimated E_L2 over the candidates is below "
                     "it (the training section's set is then not used; doc/model-file.md); stored in the file, where a "
                     "query whose error estimate exceeds it is marked and counted; 0: the training set as given");
  setIntParameter(bld, "candidates", 64, 1, 100000,
                  "gphr build with targetError: candidate points of the box (uniform at random) where the error is "
                  "estimated each round");
  setIntParameter(bld, "candidateSeed", 1, 0, 2147483647, "gphr build with targetError: the candidates' seed");
  setIntParameter(bld, "maxTrainingPoints", 40, 1, 10000,
                  "gphr build with targetError: training points at most (greedyStart's first, the confirmations' "
                  "joined points included)");
  setChoiceParameter(bld, "greedyStart", "corners", Teuchos::tuple<std::string>("corners", "centre"),
                     "gphr build with targetError: the first training set: the box's corners and centre (2^p + 1 "
                     "points), or its centre alone (the fewest full solves; every further point by the estimate)");
  setIntParameter(bld, "pointsPerRound", 1, 1, 1000,
                  "gphr build with targetError: candidates added per round (the worst, then the next worst apart "
                  "from it); more than one: the training's rank groups integrate them side by side");
  setIntParameter(bld, "confirmPoints", 3, 0, 1000,
                  "gphr build with targetError: fresh points of the box (seeded, not candidates) where full solves "
                  "confirm each query default's error (E_L2 max in the file); where they find the target missed, "
                  "they join the training and the rounds go on; 0: none");
  return bld;
}

ReducedModelData modelFileHeader(const Scene& scene, const SceneInstance& inst, const ModelFileOptions& opt) {
  ReducedModelData d;
  d.sceneName = scene.name();
  d.integratorConfig = opt.integratorConfig.empty() ? toYaml(Teuchos::ParameterList("integrator")) : opt.integratorConfig;
  d.gphrVersion = gphrVersion();
  d.trilinosVersion = TRILINOS_VERSION_STRING;
  char when[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  d.created = when;
  d.buildRanks = inst.system->space().comm()->getSize();
  d.polynomialDegree = inst.system->nonlinearTerm().polynomialDegree();
  const auto& box = scene.parameterBox();
  d.parameterNames = box.names, d.box = box.bounds, d.enters = box.enters;
  return d;
}

StoredHyperModel termModel(const SceneInstance& inst, const MultiVector& A, const std::string& method, int k, int m,
                           const std::vector<GO>& rows, const std::vector<double>& weights) {
  StoredHyperModel sm;
  sm.method = method, sm.k = k, sm.m = m;
  sm.sample = gatherRowSample(*inst.system, A, rows, weights);
  sm.sample.reference.clear();  // parameter-dependent: from the interpolant per query
  return sm;
}

std::vector<StoredHyperModel> gpDeimModels(const SceneInstance& inst, const MultiVector& A, int k, const MultiVector& U,
                                           const std::vector<int>& ms, const std::string& indices) {
  std::vector<StoredHyperModel> out;
  for (int m : ms) {
    GPHR_REQUIRE(m >= 1 && m <= static_cast<int>(U.getNumVectors()), InputError, "gp-deim k = ", k, ", m = ", m,
                 ": the DEIM basis has ", U.getNumVectors(),
                 " vectors (numerical rank of the snapshots or hyper.maxRank); allowed: 1 <= m <= that");
    const auto idx = selectDeimIndices(U, m, indices);
    const auto w = computeDeimWeights(U, idx, *inst.system->nonlinearTerm().weights());
    out.push_back(termModel(inst, A, method::kGpDeim, k, m, idx, w.weights));
    out.back().conditionNumber = w.conditionNumber;
  }
  return out;
}

void addReducedBasis(ReducedModelData& data, const Scene& scene, const SceneInstance& inst, const MultiVector& A,
                     int k, std::vector<StoredHyperModel> models, const ModelFileOptions& opt) {
  GPHR_REQUIRE(opt.interpolationNodes >= 2 && opt.interpolationNodes <= 33, InputError, "interpolation nodes ",
               opt.interpolationNodes, "; allowed: 2 to 33");
  GPHR_REQUIRE(!models.empty(), InputError, "reduced-model file: no model for k = ", k);
  data.bases.push_back(basisData(scene, *inst.system, A, k, models, opt));
  for (auto& m : models) data.models.push_back(std::move(m));
}

void addReducedBasis(ReducedModelData& data, const Scene& scene, const SceneInstance& inst, const MultiVector& A,
                     int k, const MultiVector& U, const std::vector<int>& ms, const ModelFileOptions& opt) {
  addReducedBasis(data, scene, inst, A, k, gpDeimModels(inst, A, k, U, ms, opt.indices), opt);
}

}  // namespace gphr
