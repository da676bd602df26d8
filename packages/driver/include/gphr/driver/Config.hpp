#pragma once
/// @file
/// The `gphr` configuration: a ParameterList read from YAML or XML with one top-level key
/// `gphr`, validated key by key (unknown keys, types and ranges) and completed with defaults.
#include <Teuchos_ParameterList.hpp>
#include <string>
#include <vector>

#include "gphr/core/Provenance.hpp"

namespace gphr {

/// The valid list for a given scene (the scene decides its size key and parameters), assembled
/// from the sections' own validators: each options struct's package declares its keys, defaults
/// and documentation beside the reader of its options (trainingValidParameters beside
/// trainingOptionsFrom, ...); only `pipeline` and `output`, which the application alone reads, are
/// declared beside their options (RunOptions.hpp). A validated config is read once, by
/// runOptionsFrom (RunOptions.hpp).
Teuchos::ParameterList validConfig(const std::string& sceneName);
/// Read (by extension: .yaml/.yml or .xml) and validate. InputError on any problem, one line.
Teuchos::ParameterList loadConfig(const std::string& path);
/// Validate a list already in memory (e.g.\ the built-in default) and return it completed.
Teuchos::ParameterList validateConfig(Teuchos::ParameterList cfg);
/// The small default scene `gphr` runs without arguments (NLS, n = 256, T = 5).
Teuchos::ParameterList defaultConfig();
/// `gphr --help` text: usage and every key with default, allowed values and description.
std::string helpText();

}  // namespace gphr
