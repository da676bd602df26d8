#pragma once
/// @file
/// What a greedy build (gphr build --target-error) leaves beside its stage tables: greedy.csv (a
/// row per round: training points, the best model, its largest estimate over the candidates, the
/// point added) and greedy.png (that estimate against the full solves, the target, and the query
/// defaults' E_L2 at the fresh confirmation points). Not report.md: the build's directory is also
/// `gphr run`'s, whose report it would replace.
#include <string>

#include "gphr/offline/GreedyTraining.hpp"

namespace gphr {

/// Rank 0: DIR/greedy.csv, and DIR/greedy.png where gnuplot is found (a failure to draw is said on
/// stderr, the CSV stays). Returns the files written, for the console.
std::string writeGreedyReport(const std::string& dir, const GreedyResult& greedy, const std::vector<std::string>& names,
                              double target);

}  // namespace gphr
