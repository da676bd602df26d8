#include "gphr/driver/RunMetrics.hpp"

#include <cmath>
#include <stdexcept>

namespace gphr {

namespace {

// The value's alternative of each kind, in the variant's order.
enum Kind : int { Number = 0, Integer = 1, Flag = 2, Text = 3, Numbers = 4 };

struct MetricInfo {
  const char* key;
  int kind;
};

// One row per Metric, in the enum's order: the JSON key and the kind.
const MetricInfo kMetrics[] = {
    {"method", Text},
    {"n", Integer},
    {"fullDim", Integer},
    {"numTerms", Integer},
    {"k", Integer},
    {"reducedDim", Integer},
    {"m", Integer},
    {"steps", Integer},
    {"dt", Number},
    {"ranks", Integer},
    {"E_L2", Number},
    {"E_fin", Number},
    {"E_L2_estimate", Number},
    {"H0", Number},
    {"H_err_max", Number},
    {"H_err_final", Number},
    {"H_err_max_rel", Number},
    {"t_online_s", Number},
    {"t_online_runs_s", Numbers},
    {"newton_iters_avg", Number},
    {"newton_matrices", Integer},
    {"linear_iters_avg", Number},
    {"linear_iters_per_newton", Number},
    {"newton_residual_max", Number},
    {"H_drift_bound", Number},
    {"errors_at", Text},
    {"unbounded_at_step", Integer},
    {"unbounded_reason", Text},
    {"status", Text},
    {"reason", Text},
    {"H_model_err_max", Number},
    {"diverged_at_step", Integer},
    {"diverged_reason", Text},
    {"basis", Text},
    {"energy_captured", Number},
    {"training_parameters", Integer},
    {"training_reused", Integer},
    {"basis_cached", Flag},
    {"hess_min_eig_hr", Number},
    {"hess_min_eig_rom", Number},
    {"convexity_lost", Flag},
    {"kernel_rows_per_evaluation", Integer},
    {"online_numbers_held", Integer},
    {"cond_PtU", Number},
    {"deim_weight_min", Number},
    {"deim_weight_max", Number},
    {"deim_snapshots", Text},
    {"deim_basis_cached", Flag},
    {"deim_pod_steps_tsqr", Integer},
    {"deim_pod_steps_stacked", Integer},
    {"deim_pod_steps_replicated", Integer},
    {"deim_pod_steps_tree", Integer},
    {"eqp_terms", Integer},
    {"eqp_fit_residual", Number},
    {"eqp_fit_residual_exact_rows", Number},
    {"eqp_weight_min", Number},
    {"eqp_weight_max", Number},
    {"eqp_stop", Text},
    {"eqp_selections", Integer},
    {"eqp_cached", Flag},
    {"updates", Integer},
    {"updates_skipped", Integer},
    {"update_rank_mean", Number},
    {"num_samples_mean", Number},
    {"initial_basis", Text},
    {"sampling", Text},
    {"delta0", Integer},
    {"delta", Integer},
    {"window", Integer},
    {"gamma", Integer},
    {"t_training_s", Number},
    {"t_basis_s", Number},
    {"t_basis_cpu_s", Number},
    {"t_deim_basis_s", Number},
    {"t_deim_basis_compute_s", Number},
    {"t_deim_pair_s", Number},
    {"t_eqp_training_s", Number},
    {"t_eqp_fit_s", Number},
    {"t_eqp_mesh_s", Number},
    {"t_initial_basis_s", Number},
    {"t_updates_s", Number},
    {"t_offline_s", Number},
    {"t_hyper_offline_s", Number},
    {"t_total_s", Number},
    {"pod_route", Text},
    {"pod_steps_tsqr", Integer},
    {"pod_steps_replicated", Integer},
    {"pod_steps_stacked", Integer},
    {"pod_steps_tree", Integer},
};
constexpr int kCount = sizeof(kMetrics) / sizeof(kMetrics[0]);
static_assert(kCount == static_cast<int>(Metric::PodStepsTree) + 1, "one table row per Metric");

const MetricInfo& info(Metric m) { return kMetrics[static_cast<int>(m)]; }

}  // namespace

const char* RunMetrics::key(Metric m) { return info(m).key; }

RunMetrics& RunMetrics::put(Metric m, Value v, int kind) {
  if (info(m).kind != kind)
    throw std::logic_error(std::string("run metric '") + info(m).key + "' set with a value of another kind");
  for (auto& [key, value] : values_)
    if (key == m) {
      value = std::move(v);
      return *this;
    }
  values_.emplace_back(m, std::move(v));
  return *this;
}

RunMetrics& RunMetrics::merge(const RunMetrics& later) {
  for (const auto& [m, v] : later.values_) put(m, v, info(m).kind);  // a kind later holds is its table's
  return *this;
}

const RunMetrics::Value* RunMetrics::find(Metric m) const {
  for (const auto& [key, value] : values_)
    if (key == m) return &value;
  return nullptr;
}

RunMetrics& RunMetrics::set(Metric m, double value) { return put(m, value, Number); }
RunMetrics& RunMetrics::set(Metric m, long value) { return put(m, value, Integer); }
RunMetrics& RunMetrics::set(Metric m, bool value) { return put(m, value, Flag); }
RunMetrics& RunMetrics::set(Metric m, const std::string& value) { return put(m, value, Text); }
RunMetrics& RunMetrics::set(Metric m, const std::vector<double>& values) { return put(m, values, Numbers); }

double RunMetrics::number(Metric m) const {
  const Value* v = find(m);
  if (const double* x = v ? std::get_if<double>(v) : nullptr) return *x;
  if (const long* i = v ? std::get_if<long>(v) : nullptr) return static_cast<double>(*i);
  return NAN;
}

bool RunMetrics::flag(Metric m) const {
  const Value* v = find(m);
  return v && std::holds_alternative<bool>(*v) && std::get<bool>(*v);
}

JsonObject RunMetrics::json() const {
  JsonObject o;
  for (const auto& [m, v] : values_)
    std::visit([&o, m = m](const auto& x) { o.set(key(m), x); }, v);
  return o;
}

}  // namespace gphr
