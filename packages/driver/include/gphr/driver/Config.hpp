#pragma once
/// @file
/// The `gphr` configuration: a ParameterList read from YAML or XML with one top-level key
/// `gphr`, validated key by key (unknown keys, types and ranges) and completed with defaults.
#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "gphr/core/Provenance.hpp"
#include "gphr/offline/Training.hpp"

namespace gphr {

/// The valid list for a given scene (the scene decides its size key and parameters), assembled
/// from the sections' own validators: each options struct's package declares its keys, defaults
/// and documentation beside the reader of its options (trainingValidParameters beside
/// trainingOptionsFrom, ...); only `pipeline` and `output`, which the application alone reads, are
/// declared here.
Teuchos::ParameterList validConfig(const std::string& sceneName);
/// The training options of a validated config: its training section's, with the time step, the
/// steps and the integrator of its time and integrator sections.
TrainingOptions trainingOptionsOf(const Teuchos::ParameterList& cfg, const ParameterBox& box);
/// Read (by extension: .yaml/.yml or .xml) and validate. InputError on any problem, one line.
Teuchos::ParameterList loadConfig(const std::string& path);
/// Validate a list already in memory (e.g.\ the built-in default) and return it completed.
Teuchos::ParameterList validateConfig(Teuchos::ParameterList cfg);
/// The small default scene `gphr` runs without arguments (NLS, n = 256, T = 5).
Teuchos::ParameterList defaultConfig();
/// The most time steps a config may ask for (T / dt): the paper's runs take at most 5,000.
constexpr long kMaxRunSteps = 10000000;
/// Number of time steps T / dt; InputError unless T >= dt, T is a whole number of steps and there
/// are at most kMaxRunSteps.
long numSteps(const Teuchos::ParameterList& cfg);
/// The training parameters: training.values (flattened) or the tensor grid training.points.
std::vector<std::vector<double>> trainingParameters(const Teuchos::ParameterList& cfg);
/// The reduced models to evaluate (pipeline.methods, plus rom if pipeline.rom), checked; and the
/// k values (pipeline.k, else reduction.k).
std::vector<std::string> pipelineMethods(const Teuchos::ParameterList& cfg);
/// The k values of the reduced models: pipeline.k, else reduction.k.
std::vector<int> pipelineK(const Teuchos::ParameterList& cfg);
/// `gphr --help` text: usage and every key with default, allowed values and description.
std::string helpText();

}  // namespace gphr
