#pragma once
/// @file
/// Validation of user ParameterLists against a documented list of valid parameters (Teuchos
/// validators carry the ranges and choices). Unlike Teuchos' own multi-line messages, every
/// failure here is one line naming the key path, the value and what is allowed.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <ostream>
#include <string>

namespace gphr {

/// Check `user` against `valid` recursively, then fill in defaults. Throws InputError for an
/// unknown key (listing the valid keys), a wrong type, or a value outside its validator.
void validateParameters(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                        const std::string& path = "");

/// Reference documentation of a valid list: key, type, default, allowed values, description.
void describeParameters(const Teuchos::ParameterList& valid, std::ostream& os, int indent = 0);

/// Helpers to declare documented parameters with validators.
void setIntParameter(Teuchos::ParameterList& pl, const std::string& name, int def, int lo, int hi,
                     const std::string& doc);
/// Declares a double parameter `name` with default `def` in [lo, hi] and description `doc`.
void setDoubleParameter(Teuchos::ParameterList& pl, const std::string& name, double def, double lo,
                        double hi, const std::string& doc);
/// Declares a string parameter `name` with default `def`, one of `choices`, and description `doc`.
void setChoiceParameter(Teuchos::ParameterList& pl, const std::string& name, const std::string& def,
                        const Teuchos::Array<std::string>& choices, const std::string& doc);
/// A section whose contents are not checked here but passed through to a library that reads them
/// itself (e.g.\ NOX's "Line Search"): the user must give a section (or nothing) under that key.
void setPassThroughSection(Teuchos::ParameterList& pl, const std::string& name, const std::string& doc);

}  // namespace gphr
