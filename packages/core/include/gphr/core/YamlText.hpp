#pragma once
/// @file
/// Bounded YAML: every YAML text GPHR parses -- a user's config, queries or validation file, and
/// the sections a reduced-model file stores (scene, integrator, adeim) -- goes through
/// parseYamlText(), which checks limits that need no parsing before Teuchos' reader sees a byte.
/// Teuchos' reader is quadratic in the length of one scalar or flow collection and copies a
/// nested list at every level above it (a 2 MB quoted value took over 120 s, 3,000 levels 28 s),
/// so the limits below are what keeps any accepted text parsing in well under a second (the
/// figures: doc/design.md, "Bounded input"). Every failure is one InputError line that starts
/// with the caller's name of the text and gives the line and what is allowed.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>

#include <cstddef>
#include <string>

namespace gphr {

/// Limits of a YAML text, checked before it is parsed.
/// @{
/// A whole text: Teuchos' reader takes ~1.2 s a MB even where it is linear (a queries file of named
/// points: 0.96 MB in 1.1 s, 2.4 MB in 3.2 s on a 2-core VM), so 256 KiB (~0.35 s; ~10,000 named
/// points, more as a queries grid) keeps any accepted file well under a second.
constexpr std::size_t kMaxYamlBytes = std::size_t(256) << 10;
/// One line, so one scalar or one-line flow collection, on which the reader is quadratic (a 100 KB
/// value: 0.85 s; 16 KiB: ~0.02 s).
constexpr std::size_t kMaxYamlLineBytes = 16384;
constexpr long kMaxYamlNesting = 32;  ///< block and flow levels (GPHR's deepest config nests 4)
/// @}

/// The parsed text, its top-level key the list's name. `source` names the text in messages
/// ("config file 'c.yaml'", "reduced-model file 'm.h5': its integrator section"); `rootKey`, when
/// not empty, is the single key the text may have at its top level. Non-ASCII bytes are allowed in
/// comments only (they are blanked there: Teuchos' reader refuses them anywhere). InputError on a
/// text over a limit, a control byte, a block scalar (| or >) or a quoted scalar over several lines
/// (no GPHR key takes one), a duplicate key, or malformed YAML with its line.
Teuchos::RCP<Teuchos::ParameterList> parseYamlText(const std::string& text, const std::string& source,
                                                   const std::string& rootKey = "");

/// Teuchos' exception text as one line for a message: without its source positions and throw
/// counters ("file.cpp:N:", "Throw number = ..."), at most a few hundred characters.
std::string teuchosMessage(const std::string& what);

/// The first duplicate key of a block-style YAML mapping or of a one-line flow mapping in `text`, as
/// "key 'K' at line L (first at line F)"; empty if there is none.
std::string duplicateYamlKey(const std::string& text);

}  // namespace gphr
