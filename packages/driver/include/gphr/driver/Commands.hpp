#pragma once
/// @file
/// The `gphr` commands besides `run`: build (offline stages -> a reduced-model file), query (the
/// file's models at many parameters, spread over the ranks) and validate (the models against the
/// full model over a set of test parameters), one header each, and the output directory they
/// share. Each returns the process exit code; bad input is an InputError (exit 2), thrown on every
/// rank.
#include "gphr/core/Provenance.hpp"
#include "gphr/driver/BuildCommand.hpp"
#include "gphr/driver/OutputDirectory.hpp"
#include "gphr/driver/QueryCommand.hpp"
#include "gphr/driver/ValidateCommand.hpp"
