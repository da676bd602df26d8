#pragma once
/// @file
/// A `gphr run` / `gphr build` configuration read once into typed options: every section through
/// the reader of its package (trainingOptionsFrom, basisOptionsFrom, deimBasisOptionsFrom, ...),
/// the application's own sections (pipeline, output) through the readers below, beside their
/// validators. Nothing below the application reads the configuration itself; what a report
/// stores of the configuration as text (config.yaml, summary.json's provenance) is kept here too.
#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>
#include <vector>

#include "gphr/driver/Json.hpp"
#include "gphr/evaluation/EvaluationSettings.hpp"
#include "gphr/hyper/GpAdeimModel.hpp"
#include "gphr/hyper/GradientDeimModel.hpp"
#include "gphr/models/Scene.hpp"
#include "gphr/offline/GreedyTraining.hpp"
#include "gphr/offline/ModelFileBuilder.hpp"
#include "gphr/offline/OfflineSequence.hpp"

namespace gphr {

/// The `pipeline` section: the reduced models `gphr run` evaluates (and `gphr build` stores).
struct PipelineOptions {
  std::vector<std::string> methods;  ///< pipeline.methods (+ rom with pipeline.rom), each once, checked
  std::vector<int> ks;               ///< pipeline.k, else reduction.k
  std::vector<int> ms;               ///< pipeline.m (every k not in msByK)
  std::map<int, std::vector<int>> msByK;  ///< pipeline.mPerK: a k's own m list
  /// The m list of reduced size k (pipeline.mPerK's where it names k, else pipeline.m).
  const std::vector<int>& msOf(int k) const { return deimSizesOf(ms, msByK, k); }
  std::vector<int> allMs() const { return allDeimSizes(ms, msByK); }  ///< every m of any k, ascending
};
/// The keys of a `pipeline` section with their defaults and documentation.
Teuchos::ParameterList pipelineValidParameters();
/// The options of a validated `pipeline` section; reductionK stands for an empty pipeline.k.
PipelineOptions pipelineOptionsFrom(const Teuchos::ParameterList& pipeline, int reductionK);

/// The `output` section: what `gphr run` writes besides summary.json.
struct OutputOptions {
  int saveEvery = 10;               ///< every N-th state in artifacts.h5 (and the error's steps)
  double progressSeconds = 2.0;     ///< between progress lines (0: none)
  double checkpointSeconds = 60.0;  ///< between a stage's checkpoints
  bool syncArtifacts = false;       ///< MPI_File_sync before each complete mark
  bool plots = true;                ///< PNG plots with gnuplot
  bool xdmf = false;                ///< fields.xdmf
  std::vector<std::string> fieldModels;  ///< checked: registry methods or "best", each once
  std::vector<double> fieldTimes;        ///< resolved: the given times, else 0, T/2, T
  /// The models whose field states the run keeps: fieldModels where fields are drawn or written.
  std::vector<std::string> fieldStateModels() const { return plots || xdmf ? fieldModels : std::vector<std::string>{}; }
};
/// The keys of an `output` section with their defaults and documentation.
Teuchos::ParameterList outputValidParameters();
/// The options of a validated `output` section; T, the run's horizon, bounds output.fieldTimes.
OutputOptions outputOptionsFrom(const Teuchos::ParameterList& output, double T);

/// The configuration as the reports store it.
struct ConfigRecord {
  std::string yaml;          ///< re-readable by gphr (config.yaml): empty arrays left out
  std::string fullYaml;      ///< every key as validated (artifacts.h5's "config" attribute)
  std::string integratorYaml;///< the integrator section (a model file's)
  JsonObject provenance;     ///< summary.json's: solvers, build, the configuration as JSON
};

/// The most time steps a config may ask for (T / dt): the paper's runs take at most 5,000.
constexpr long kMaxRunSteps = 10000000;
/// Number of time steps T / dt; InputError unless T >= dt, T is a whole number of steps and there
/// are at most kMaxRunSteps.
long numSteps(const Teuchos::ParameterList& cfg);
/// A configuration's typed options (see the file's description).
struct RunOptions {
  std::shared_ptr<Scene> scene;  ///< scene.name and its keys
  std::vector<double> mu;        ///< the test parameter (section parameters)
  double T = 0.0;                ///< time.T
  std::string scheme;            ///< integrator.scheme
  PipelineOptions pipeline;       ///< the models evaluated (stored), their k and m
  EvaluationSettings evaluation;  ///< time loop, saved steps, repeats, progress
  OfflineOptions offline;         ///< training, basis (k: the largest asked), DEIM basis, fits
  std::string indices = "deim";   ///< hyper.indices: the DEIM interpolation rows
  GradientSnapshots deimSnapshots = GradientSnapshots::Full;  ///< hyper.deimSnapshots (classic DEIM)
  AdeimOptions adeim;             ///< the adeim section (per m: adeimOptionsFor)
  ModelFileOptions file;          ///< the build section's file options, indices and integrator
  bool withBasis = false;         ///< build.withBasis
  GreedyOptions greedy;           ///< build.targetError, candidates, candidateSeed, maxTrainingPoints (gphr build)
  OutputOptions output;           ///< what the run writes
  ConfigRecord record;            ///< the configuration as text, for the reports
};

/// Reads a validated configuration (Config.hpp) once; InputError on a value its sections'
/// readers refuse (the training set against the box, the method, k and m lists, adeim's
/// constraints that involve m, output.fieldModels and fieldTimes).
RunOptions runOptionsFrom(const Teuchos::ParameterList& config);

}  // namespace gphr
