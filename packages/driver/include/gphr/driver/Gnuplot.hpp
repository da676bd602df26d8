#pragma once
/// @file
/// The one way the reports run gnuplot: no shell between gphr and gnuplot (a path with a quote or
/// a `;` in it, from --output, cannot run commands), every path and label inside a script quoted
/// for gnuplot, and a picture counted as drawn only when gnuplot exited 0 and the PNG is whole.
#include <string>
#include <vector>

namespace gphr {

/// Whether a `gnuplot` executable is on the PATH (searched directly, not by a shell).
bool haveGnuplot();

/// `text` as a gnuplot single-quoted string: inside one, gnuplot reads '' as a quote and nothing
/// else specially, so a path or label cannot end the string and continue as gnuplot commands. A
/// line break (which no gnuplot string can hold) is an InputError naming the text.
std::string gnuplotQuoted(const std::string& text);

/// Runs `gnuplot SCRIPT` (posix_spawnp, its output discarded) and removes the script; true when it
/// exited 0 and each of `pngs` is a whole PNG file (it ends with the IEND chunk: a full disk leaves
/// a short one while gnuplot still exits 0). A PNG of `pngs` that is not whole is removed.
bool runGnuplot(const std::string& script, const std::vector<std::string>& pngs);

}  // namespace gphr
