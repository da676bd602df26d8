#pragma once
/// @file
/// Greedy training to a target error (libROM's greedy sampler, pyMOR's weak greedy):
/// start from the box's corners and centre, build the reduced-model file, estimate every stored
/// sample-mesh model's error at a seeded set of candidate points of the box with the query's own
/// error estimate (hyper/ErrorIndicator.hpp: no full solve; the candidates spread over the ranks),
/// and while the best model's largest estimate exceeds the target add its worst candidate (or
/// GreedyOptions::pointsPerRound of them) to the training set and build again. The
/// artifacts cache keeps every finished parameter's states (trainingStatesKey), so a round trains
/// its new parameters only; the bases are recomputed from the grown set.
#include <map>
#include <string>
#include <vector>

#include "gphr/offline/ModelFileBuild.hpp"

namespace gphr {

/// What the greedy training aims at and may spend.
struct GreedyOptions {
  double targetError = 0.0;  ///< EPS: the best model's estimated max E_L2 over the candidates to reach (> 0)
  int candidates = 64;       ///< candidate points of the box, uniform at random from `seed`
  unsigned long seed = 1;    ///< of the candidates: the same seed, the same points (and rounds)
  int maxPoints = 40;        ///< training points at most (the build stops there, target met or not)
  /// Fresh points where full solves confirm the query defaults (0: none). Where they show a default
  /// that met the target by its estimate above it, they join the training and the rounds go on
  /// (then the next confirmPoints of the fresh stream confirm), while maxPoints allow.
  int confirmPoints = 3;
  /// The first training set: "corners" (the box's corners and centre, 2^p + 1 points: every edge
  /// of the box trained from the start) or "centre" (the centre alone: the fewest full solves,
  /// every further point chosen by the estimate).
  std::string start = "corners";
  /// Candidates added per round: the worst, then the next worst each at least a cell of a
  /// pointsPerRound-point grid away from the round's others (pointsToAdd); only candidates whose
  /// estimate exceeds the target. More than one: the training's rank groups integrate them side by
  /// side (TrainingOptions::groupSize), and a round's bases serve more points.
  int pointsPerRound = 1;
};

/// One round: the training set's size, the best model and its largest estimate over the
/// candidates left, and the candidate added (empty in the last round): TrainingRound, as the file records it.
using GreedyRound = TrainingRound;

/// The greedy training's result: the last build (its file at `path`) and the rounds.
struct GreedyResult {
  ModelBuildResult build;           ///< the last round's build
  std::vector<GreedyRound> rounds;  ///< in order
  bool met = false;                 ///< the target was reached
};

/// The box's corners and centre (2^p + 1 points; the centre alone for p = 0).
std::vector<std::vector<double>> cornersAndCentre(const ParameterBox& box);
/// The greedy training's first set for `start` (GreedyOptions::start); InputError for another word.
std::vector<std::vector<double>> greedyStart(const ParameterBox& box, const std::string& start);
/// `count` points uniform in the box from `seed` (std::mt19937_64, the same on every rank and machine).
std::vector<std::vector<double>> candidatePoints(const ParameterBox& box, int count, unsigned long seed);

/// The candidates a round adds (indices into `candidates`, the worst first): by `estimates`
/// descending, those above `target`, each at least 0.5 / ceil(count^(1/p)) from the others chosen
/// (the box scaled to the unit cube), at most `count`; the worst alone where none exceeds the target.
std::vector<size_t> pointsToAdd(const ParameterBox& box, const std::vector<std::vector<double>>& candidates,
                                const std::vector<double>& estimates, double target, int count);

/// The online cost of a model of sizes (k, m) per Newton iteration, for choosing between models
/// (deterministic, unlike a timing): the reduced Jacobian assembled from m sampled rows, 2 m (2k)^2
/// flops, and its LU, (2k)^3 / 3.
double onlineCostProxy(int k, int m);
/// Per method of `models` with an estimate in `largest` (model key -> largest estimate over the
/// candidates): the cheapest model meeting `target` (ties: smaller k, then m), else the one with
/// the smallest estimate. verifiedMax NaN (confirmQueryDefaults fills it).
std::vector<QueryDefault> chooseQueryDefaults(const std::vector<StoredHyperModel>& models,
                                              const std::map<std::string, double>& largest, double target);
/// `count` points of the box from a stream of their own (seeded by `seed`, not the candidates'):
/// where full solves confirm the query defaults.
std::vector<std::vector<double>> freshPoints(const ParameterBox& box, int count, unsigned long seed);

/// Trains greedily to g.targetError (see the file's description), confirms the query defaults with
/// full solves at fresh points (a confirmation that misses the target trains those points and
/// goes on: GreedyOptions::confirmPoints) and writes the model file at
/// `path`; the file records the target, the rounds and the estimate reached (ReducedModelData::
/// greedy). options.training.parameters is replaced by the greedy set. Collective over `comm`.
GreedyResult buildToTargetError(const Scene& scene, const RCP<const Comm>& comm, ModelBuildOptions options,
                                const std::string& path, const GreedyOptions& g, const ArtifactsCache* cache = nullptr,
                                const OfflineSequence::StageHook& hook = {});

}  // namespace gphr
