#pragma once
/// @file
/// The queries file of `gphr query` (doc/model-file.md): YAML with one top-level key `queries`,
/// sections `defaults` (keys every query inherits), `points` (named queries, each a mapping of
/// parameters and keys) and `grid` (per parameter [from, to, count]: the tensor grid of those values,
/// named grid-0000, ...). Every key, type and value is checked against the model file before any
/// query runs (so no rank fails alone later).
#include <memory>
#include <string>
#include <vector>

#include "gphr/online/ReducedModel.hpp"

namespace gphr {

/// Limits of a queries or validation file, checked before anything is run or allocated.
/// @{
constexpr size_t kMaxQueryName = 64;        ///< characters of a query's name (it names its result files)
constexpr long kMaxQuerySteps = 10000000;   ///< T / dt of one query (H_hr is kept at every step: 80 MB)
constexpr size_t kMaxQueries = 100000;      ///< queries in one file (points and grid together)
/// @}

/// One query: a model of the file (method, k, m) at parameter mu over [0, T] with step dt.
struct Query {
  std::string name;  ///< Name of the query (of its point, or grid-NNNN).
  std::vector<double> mu;  ///< The parameter mu.
  std::string method = "gp-deim";  ///< Method of the model (rom | gp-deim).
  /// Reduced size k and DEIM size m of the model.
  /// @{
  int k = 0, m = 0;
  /// @}
  /// Final time T and time step dt.
  /// @{
  double T = 0.0, dt = 0.0;
  /// @}
  long saveEvery = 10;  ///< Keep every saveEvery-th step.
  bool probes = true;  ///< Report the lifted state at the file's probe entries.
  SetupRoute setup = SetupRoute::Interpolated;  ///< How the parameter's pieces are set up (interpolated or exact).
  bool extrapolate = false;  ///< Allow a parameter outside the box (result marked extrapolated).
  bool states = false;  ///< also the lifted states y0 + A z at the saved steps (needs the basis in the file)
  /// Everything that determines the result, as text (a finished query is reused only if it matches).
  std::string key() const;
};

/// Queries (top-level key `queries`) or the test points of `gphr validate` (top-level key
/// `validate`: the same sections; each point runs every model of the file, so method, k, m and
/// probes are not keys there, and points outside the box are allowed and marked).
enum class QueryFileKind { Queries, Validation };

/// What a finished result of query q is keyed by: the query (Query::key()), the model file's
/// checksum and the gphr version. A result is reused only when all three match.
std::string resultKey(const Query& q, const ReducedModelData& data);
/// Reads the stored bases these queries lift with (every k of a validation; a query's k with setup
/// exact, states: true or an adaptive method), so that a damaged basis -- outside the file's
/// checksum, checked where it is read (OpenModelFile::basis) -- is an InputError before any output
/// is written. Collective.
void checkLiftingBases(const ReducedModel& model, const std::vector<Query>& queries, QueryFileKind kind,
                       const RCP<const Comm>& comm);
/// The model file loaded on every rank (collective): a load that fails on some ranks only (a
/// file one node does not see) names the disagreement, and ranks that read different contents at
/// the path (checksums) are refused: one InputError on every rank, before any work.
std::unique_ptr<ReducedModel> loadOnEveryRank(const std::string& path, const RCP<const Comm>& comm);
/// readQueries() on every rank (collective), with loadOnEveryRank's agreement: the same queries
/// on every rank, or one InputError naming the disagreement.
std::vector<Query> readQueriesOnEveryRank(const std::string& path, const ReducedModel& model, QueryFileKind kind,
                                          const RCP<const Comm>& comm);
/// Reads and checks a queries (or validation) file against `model`; InputError on any problem.
std::vector<Query> readQueries(const std::string& path, const ReducedModel& model,
                               QueryFileKind kind = QueryFileKind::Queries);

}  // namespace gphr
