#pragma once
/// @file
/// The reduced-model file (doc/model-file.md): what `gphr build` writes and `gphr query`, the
/// ReducedModel class and an embedding code read. It holds the ONLINE data only: per reduced size
/// k the parameter interpolant of L_r, f_r, c and the shift's reference rows, probe rows of the
/// basis, optionally the basis itself; per hyper-reduced model (method, k, m) its sample mesh
/// (rows, stencils, basis rows under them, weights). Nothing of size n or d unless the basis is
/// asked for. Replicated data are stored as 1-D / 2-D double datasets (global ids as doubles:
/// exact below 2^53), readable with h5dump or h5py.
#include <sys/types.h>

#include <map>
#include <memory>
#include <mutex>
#include <limits>
#include <string>
#include <vector>

#include "gphr/core/Method.hpp"
#include "gphr/core/PhaseSpace.hpp"
#include "gphr/hyper/ErrorIndicator.hpp"
#include "gphr/hyper/ParameterInterpolant.hpp"
#include "gphr/reduction/ReducedHamiltonian.hpp"

namespace gphr {

constexpr int kReducedModelSchema = 4;  ///< Version of the reduced-model file's layout (doc/model-file.md).

/// One hyper-reduced model: its sample mesh without the parameter-dependent reference rows.
struct StoredHyperModel {
  std::string method;  ///< gp-deim, gp-eqp, gp-eqp-refit
  /// Reduced size k, and m: gp-deim's rows, the term budget of gp-eqp (which may use fewer).
  /// @{
  int k = 0, m = 0;
  /// @}
  RowSample sample;    ///< reference left empty: it comes from the basis' interpolant per query
  double conditionNumber = 0.0;  ///< cond_2(P^T U) of the DEIM pair
  /// Its error indicator's calibration (ErrorIndicator.hpp): E_L2 ~ scale eta^exponent, fitted on
  /// the build's training parameters; not calibrated where the build could not (no indicator rows).
  IndicatorCalibration calibration;
  /// gp-adeim: its config section (YAML). It samples the full residual online, so it stores no
  /// sample mesh and its queries build the full system (`onlineNeedsFullSystem()`).
  std::string adeimConfig;
  /// True for models whose online phase needs the full system (gp-adeim).
  bool onlineNeedsFullSystem() const { return methodInfo(method).needsFullResidual; }
  /// The model's name in the file: `method/k<k>/m<m>`.
  std::string key() const { return method + "/k" + std::to_string(k) + "/m" + std::to_string(m); }
};

/// What a query at parameter mu needs of the reduced basis of one k (exactly, or interpolated).
struct OnlineParameterData {
  ReducedLinearPart linear;        ///< L_r, f_r, c = H(y0(mu))
  std::vector<double> reference;   ///< y0(mu) at StoredBasisData::referenceGids
  IndicatorLinearRows indicator;   ///< the error indicator's rows of L A and f (empty without one)
};

/// What the file holds for one reduced size k: the parameter interpolants, probe rows, optionally A.
struct StoredBasisData {
  int k = 0;  ///< Reduced size k.
  std::vector<GO> referenceGids;   ///< union of the models' and the indicator's stencil entries and the probes
  /// L_r, f_r and y0 depend only on the parameters that enter the linear part or the initial state
  /// (ParameterEntry): the interpolant spans those (`interpolated`, indices into mu; none: one node),
  /// per node [L_r (2k x 2k, column-major) | f_r (2k) | y0 at referenceGids | the indicator's rows
  /// of L A (s x 2k, row-major) and f (s)]. c = H(y0) depends on
  /// every parameter (through N(y0) on the row kernel's): its own interpolant over the whole box.
  std::vector<size_t> interpolated;
  /// Interpolant of [L_r | f_r | y0 at referenceGids | indicator rows] over the `interpolated` parameters.
  ParameterInterpolant interpolant;
  ParameterInterpolant constant;  ///< Interpolant of c = H(y0) over the whole box.
  std::map<std::string, double> interpolationError;  ///< relative error at the check points, per piece
  std::vector<GO> probeGids;       ///< state entries whose lifted values a query can report
  std::vector<double> probeRows;   ///< the rows of A at probeGids (probes x 2k, row-major)
  bool hasBasis = false;           ///< `/k<k>/basis` holds A (2k rows of 2n)
  IndicatorRows indicator;         ///< the online error indicator's sample (empty: none)
  /// Values per interpolation node: 4k^2 + 2k + reference entries + s (2k + 1) for s indicator entries.
  size_t valuesPerNode() const;
  OnlineParameterData at(const std::vector<double>& mu) const;  ///< the interpolants, unpacked
  /// Exact data at one point as the interpolant's values ([L_r | f_r | y0 | indicator rows], without c).
  std::vector<double> pack(const OnlineParameterData& data) const;
  std::vector<double> restrict(const std::vector<double>& mu) const;  ///< mu at `interpolated`
};

/// One round of a greedy training (offline/GreedyTraining.hpp), as the file records it.
struct TrainingRound {
  long fullSolves = 0;        ///< training points (full-model runs) of the round's build
  std::string model;          ///< the model with the smallest largest estimate over the candidates
  double maxEstimate = 0.0;   ///< that largest estimate
  std::vector<double> added;  ///< the candidate added next (empty in the last round)
};

/// The model a query of a method runs where it leaves k or m open (gphr build --target-error):
/// the method's cheapest model (onlineCostProxy) whose largest error estimate over the greedy
/// candidates met the target, or, where none did, the one with the smallest.
struct QueryDefault {
  std::string method;  ///< gp-deim, gp-eqp, gp-eqp-refit
  /// the model's sizes
  /// @{
  int k = 0, m = 0;
  /// @}
  double estimatedMax = 0.0;  ///< its largest error estimate over the greedy candidates
  double verifiedMax = std::numeric_limits<double>::quiet_NaN();  ///< its largest E_L2 at fresh points (full solves); NaN: not confirmed
  bool met = false;           ///< estimatedMax <= the file's target error
};

/// The contents of a reduced-model file (doc/model-file.md).
struct ReducedModelData {
  int schemaVersion = kReducedModelSchema;  ///< Layout version (kReducedModelSchema).
  std::string sceneName;  ///< The scene the file was built for.
  std::string sceneConfig;       ///< YAML of the scene section (sizes: the file's scene)
  std::string integratorConfig;  ///< YAML of the integrator section the models were built for
  std::string config;            ///< the whole validated build configuration, with defaults (YAML)
  /// Provenance: gphr and Trilinos versions, creation time.
  /// @{
  std::string gphrVersion, trilinosVersion, created;
  /// @}
  int buildRanks = 1;  ///< MPI ranks of the build.
  std::string checksum;  ///< the file's checksum of its model data (modelDataChecksum), as read and verified
  double offlineSeconds = 0.0;   ///< the build's wall time (training, bases, DEIM pairs, interpolants)
  /// The offline stages the build took from its artifacts cache (their seconds in offlineSeconds
  /// are a read's, not the computation's). Provenance, outside the checksum.
  std::vector<std::string> cachedStages;
  /// The build's training parameters (validate marks them). Provenance, outside the checksum.
  std::vector<std::vector<double>> trainingParameters;
  /// the build configuration's time section (query defaults)
  /// @{
  double T = 0.0, dt = 0.0;
  /// @}
  int polynomialDegree = 0;      ///< of G (AVF's quadrature)
  std::vector<std::string> parameterNames;  ///< Names of the parameters mu.
  std::vector<std::pair<double, double>> box;  ///< The parameter box, [lower, upper] per parameter.
  std::vector<unsigned> enters;  ///< ParameterEntry flags per parameter
  std::vector<StoredBasisData> bases;  ///< Per reduced size k, its data.
  std::vector<StoredHyperModel> models;  ///< The hyper-reduced models.
  /// The error a query is held to (build.targetError): a query whose estimate exceeds it is marked;
  /// 0: none set.
  double targetError = 0.0;
  /// Per method, the model a query takes where it gives no k or m (empty: none; a greedy build's).
  std::vector<QueryDefault> queryDefaults;
  const QueryDefault* queryDefault(const std::string& method) const;  ///< the method's, or null
  /// The rounds of the greedy training that built the file (empty: a training set given whole).
  /// Provenance, outside the checksum: no query reads it.
  std::vector<TrainingRound> greedy;
  const StoredBasisData& basis(int k) const;                      ///< InputError naming the ks held
  const StoredHyperModel& model(const std::string& method, int k, int m) const;  ///< InputError naming the models held
  std::string modelList() const;  ///< "gp-deim k=10 m=20, ..." for messages
  /// True if some parameter of mu lies outside the training box (an extrapolated query or point).
  bool outsideBox(const std::vector<double>& mu) const;
};

/// Writes the file (collective over comm: rank 0 writes the replicated data; bases[i], where not
/// null, is A of bases[i].k on space's map, written distributed). Write-then-rename: the file
/// appears complete or not at all.
void writeReducedModelFile(const std::string& path, const RCP<const Comm>& comm, const ReducedModelData& data,
                           const std::vector<RCP<const MultiVector>>& bases, const PhaseSpace* space = nullptr);
/// Reads everything but the bases, on the calling process alone (no collective), and validates it
/// whole before anything uses it: every dataset's shape and type, indices whole and in range,
/// stencil offsets consistent with the stencils, counts consistent between datasets, every value
/// finite, every attribute of its type, and the checksum. InputError, one line naming the file, the
/// dataset and what is allowed, for a file that is missing, truncated, of another format or schema,
/// or changed after gphr build wrote it. (OpenModelFile(path).data(), for a caller that reads no basis.)
ReducedModelData readReducedModelFile(const std::string& path);
/// The fingerprint of the model data (FNV-1a over every dataset and attribute a query reads, but the
/// basis A and the provenance: versions, date, ranks, seconds), as the file's `checksum` holds it.
std::string modelDataChecksum(const ReducedModelData& data);

class Hdf5File;

/// A reduced-model file held open, read-only, on the calling process alone, for as long as it is
/// used: its model data are read and validated (readReducedModelFile's checks) once, at open, and
/// every later read -- a basis, to lift states or to set a query up exactly -- comes from that same
/// open file. A file replaced at its path meanwhile (write-then-rename, as gphr build writes) is
/// not seen: the open file is the one whose data were checked; one changed in place (its size or
/// modification time differ from those at open) is an InputError naming it. So a run never mixes
/// two files' data, and what it is keyed by (data().checksum) is the data it used.
class OpenModelFile {
 public:
  /// Opens and reads the file at `path` (InputError as readReducedModelFile()).
  explicit OpenModelFile(const std::string& path);
  ~OpenModelFile();
  OpenModelFile(const OpenModelFile&) = delete;
  OpenModelFile& operator=(const OpenModelFile&) = delete;
  const std::string& path() const { return path_; }  ///< The path it was opened at.
  const ReducedModelData& data() const { return data_; }  ///< Its model data, read and checked at open.
  /// A of reduced size k on space's map, from the open file (collective over space's communicator;
  /// thread-safe against other reads of this file, not against other HDF5 calls: Debian's HDF5 is
  /// not thread-safe). InputError if the file holds no basis of k, the basis fails its checks
  /// (finite values, its fingerprint), or the file was changed in place since it was opened.
  RCP<MultiVector> basis(int k, const PhaseSpace& space) const;

 private:
  /// The file's identity and state at open: device, inode, size, modification time (ns).
  struct Stamp {
    dev_t device = 0;
    ino_t inode = 0;
    long long size = -1, modifiedNs = -1;
    bool operator==(const Stamp& o) const {
      return device == o.device && inode == o.inode && size == o.size && modifiedNs == o.modifiedNs;
    }
  };
  static Stamp stampOf(int fd);
  void requireUnchanged() const;
  std::string path_;
  int fd_ = -1;  ///< a descriptor of the opened file: its stamp is compared before each later read
  Stamp opened_;
  std::unique_ptr<Hdf5File> file_;
  ReducedModelData data_;
  mutable std::mutex read_;
};

}  // namespace gphr
