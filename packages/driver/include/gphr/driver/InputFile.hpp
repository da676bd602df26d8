#pragma once
/// @file
/// Reading the parameter files a user names on the command line (the run config, queries and
/// validation files) with errors that name the real cause: a missing file, a directory, an empty
/// or binary file, a duplicate key, or malformed YAML with its line.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <string>

namespace gphr {

/// The largest parameter file read (a queries file of 100,000 points is ~3 MB).
constexpr std::size_t kMaxParameterFileBytes = std::size_t(64) << 20;

/// Reads the YAML (or, with xml, XML) file at `path`, which the messages call "<what> file".
/// InputError naming the file and the cause unless it is a regular, non-empty text file of at most
/// kMaxParameterFileBytes that parses; a duplicate key of a block mapping is named with its lines.
Teuchos::RCP<Teuchos::ParameterList> readParameterFile(const std::string& path, const std::string& what,
                                                       bool xml = false);

/// The first duplicate key of a block-style YAML mapping in `text`, as "key 'K' at line L (first at
/// line F)"; empty if there is none (flow mappings {a: 1} are not scanned).
std::string duplicateYamlKey(const std::string& text);

}  // namespace gphr
