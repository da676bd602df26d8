#pragma once
/// @file
/// Reading the parameter files a user names on the command line (the run config, queries and
/// validation files) with errors that name the real cause: a missing file, a directory, an empty
/// or binary file, a text over the limits of bounded parsing (gphr/core/YamlText.hpp), a duplicate
/// key, or malformed YAML or XML with its line.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <string>

namespace gphr {

/// Reads the YAML (or, with xml, XML) file at `path`, which the messages call "<what> file".
/// InputError naming the file and the cause unless it is a regular, non-empty text file within
/// the limits of parseYamlText() (kMaxYamlBytes, kMaxYamlLineBytes, kMaxYamlNesting) that parses.
/// XML is held to the YAML rules: each key once per list, whole numbers in int's range.
Teuchos::RCP<Teuchos::ParameterList> readParameterFile(const std::string& path, const std::string& what,
                                                       bool xml = false);

}  // namespace gphr
