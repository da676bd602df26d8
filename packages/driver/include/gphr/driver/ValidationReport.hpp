#pragma once
/// @file
/// The outputs of `gphr validate` (doc/model-file.md): DIR/validation.csv (a line per point and
/// model), DIR/validation.md and DIR/validation_summary.json (per model the max, mean and 95th
/// percentile of E_L2 over the points, the worst point, the online cost, the break-even number of
/// queries; the cheapest model whose largest error is below each level) and a plot of E_L2 over
/// the parameter (one parameter) or one map per model (two).
#include <string>
#include <vector>

#include "gphr/core/Types.hpp"
#include "gphr/driver/QueryList.hpp"

namespace gphr {

/// One line of validation.csv: one model at one test point.
struct ValidationRecord {
  /// Name of the test point, method of the model, status of the run.
  /// @{
  std::string point, method;
  RunStatus status = RunStatus::Ok;  ///< the run's status
  /// @}
  std::vector<double> mu;  ///< The parameter mu of the point.
  /// Reduced size k and DEIM size m.
  /// @{
  int k = 0, m = 0;
  /// @}
  /// Error E_L2, online and set-up wall seconds.
  /// @{
  double eL2 = NAN, onlineSeconds = NAN, setupSeconds = NAN;
  /// @}
  double errorEstimate = NAN;  ///< E_L2 estimated without the full model (ReducedEvaluation::errorEstimate)
  /// The query's own estimate (SimulationStats::errorEstimate: the online indicator, calibrated by
  /// the build); NaN for the ROM and where the file has none.
  double queryEstimate = NAN;
  bool extrapolated = false;  ///< Whether mu lies outside the box.
  std::string label() const;  ///< "gp-deim k=10 m=20", "rom k=10"
};

/// Statistics of a sample (NaN for an empty one). percentile: linear interpolation between the
/// order statistics at position p (N - 1), numpy's default.
double percentile(std::vector<double> x, double p);

/// Statistics of one model over the test points (a row of validation.md).
struct ModelStatistics {
  std::string label;   ///< The model's label (method, k, m).
  std::string method;  ///< its method (a registry name)
  /// Reduced size k and DEIM size m.
  /// @{
  int k = 0, m = 0;
  /// @}
  /// Number of points, and of those with status ok.
  /// @{
  long points = 0, ok = 0;
  /// @}
  /// Largest, mean and 95th percentile of E_L2, mean online seconds.
  /// @{
  double maxError = NAN, meanError = NAN, p95Error = NAN, meanOnline = NAN;
  /// @}
  std::string worstPoint;  ///< The point of the largest error.
};
/// Per model (in the records' first-seen order): a point that is not ok makes the maximum infinite.
std::vector<ModelStatistics> modelStatistics(const std::vector<ValidationRecord>& records);

/// One point's records as kept for resumption (rank 0 writes, every rank reads; collective).
void writePointRecords(const std::string& path, const std::string& key, const std::vector<ValidationRecord>& recs,
                       double fomSeconds, const RCP<const Comm>& comm);
/// Reads one point's records kept for resumption; false if absent or of another key. Collective.
bool readPointRecords(const std::string& path, const std::string& key, const RCP<const Comm>& comm,
                      std::vector<ValidationRecord>& recs, double& fomSeconds);

/// Writes validation.csv, validation.md, validation_summary.json and the plots to `dir` (the file's description).
void writeValidationReport(const std::string& dir, const class ReducedModel& model, const std::vector<Query>& points,
                           const std::vector<ValidationRecord>& records, const std::vector<double>& fomSeconds);

}  // namespace gphr
