#include "gphr/core/YamlText.hpp"

#include <Teuchos_YamlParameterListCoreHelpers.hpp>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {

// A message quotes at most this much of Teuchos' text (which can repeat a whole value).
constexpr std::size_t kMaxReasonChars = 240;

std::string shortened(const std::string& s) {
  return s.size() <= kMaxReasonChars ? s : s.substr(0, kMaxReasonChars) + "...";
}

// The line of Teuchos' message that names the problem ("Parser failure at line L column C").
std::string firstLineOf(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  const auto pos = s.find("Parser failure");
  if (pos != std::string::npos) line = s.substr(pos, s.find('\n', pos) - pos);
  return line;
}

// Teuchos' message without its source positions and throw counters ("file.cpp:N:", "Throw ...").
std::string teuchosReason(const std::string& s) {
  std::istringstream in(s);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || (line.find(".cpp:") != std::string::npos && line.back() == ':') ||
        line.rfind("Throw ", 0) == 0)
      continue;
    out += (out.empty() ? "" : " ") + line;
  }
  return out.empty() ? firstLineOf(s) : out;
}

// Calls use(line, lineNo, indent) for each line that is not blank or a comment.
template <class Use>
void forEachContentLine(const std::string& text, Use&& use) {
  std::istringstream in(text);
  int lineNo = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNo;
    const size_t indent = line.find_first_not_of(' ');
    if (indent != std::string::npos && line[indent] != '#') use(line, lineNo, indent);
  }
}

// Whether a quote at position i opens a quoted scalar: only where a scalar starts (after the
// indent, a key's colon, a list dash or a flow bracket or comma); elsewhere (don't) it is text.
bool opensQuote(const std::string& line, size_t i) {
  size_t j = i;
  while (j > 0 && line[j - 1] == ' ') --j;
  return j == 0 || std::string(":-[{,").find(line[j - 1]) != std::string::npos;
}

// One line's structure, outside quotes: where its comment starts (npos: none), its deepest flow
// nesting { [ and how many it leaves open; `unclosedQuote` where a quoted scalar runs past the line.
struct LineShape {
  size_t comment = std::string::npos;
  long deepest = 0, open = 0;
  bool unclosedQuote = false;
};
LineShape shapeOf(const std::string& line) {
  LineShape s;
  char quote = 0;
  long depth = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote) {
      if (c == quote && quote == '\'' && i + 1 < line.size() && line[i + 1] == '\'') ++i;  // '' inside '...'
      else if (c == '\\' && quote == '"') ++i;
      else if (c == quote) quote = 0;
    } else if ((c == '"' || c == '\'') && opensQuote(line, i)) {
      quote = c;
    } else if (c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
      s.comment = i;
      break;
    } else if (c == '{' || c == '[') {
      s.deepest = std::max(s.deepest, ++depth);
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  s.open = depth;
  s.unclosedQuote = quote != 0;
  return s;
}

// A block scalar indicator (| or >, with its modifiers) as a key's or a list item's value.
bool blockScalar(const std::string& line, const LineShape& s) {
  std::string code = line.substr(0, std::min(line.size(), s.comment));
  while (!code.empty() && (code.back() == ' ' || code.back() == '\t' || code.back() == '\r')) code.pop_back();
  const size_t space = code.find_last_of(' ');
  if (space == std::string::npos) return false;
  const std::string token = code.substr(space + 1);
  if (token.empty() || (token[0] != '|' && token[0] != '>') ||
      token.find_first_not_of("+-0123456789", 1) != std::string::npos)
    return false;
  size_t j = space;
  while (j > 0 && code[j - 1] == ' ') --j;
  return j > 0 && (code[j - 1] == ':' || code[j - 1] == '-');
}

// The text as the parser may see it, after the checks that need no parsing: its size, each line's
// length and bytes, quoted scalars on one line, no block scalars; non-ASCII bytes of comments blanked.
std::string checkedText(const std::string& text, const std::string& source) {
  GPHR_REQUIRE(text.size() <= kMaxYamlBytes, InputError, source, " has ", text.size(), " bytes; allowed: at most ",
               kMaxYamlBytes);
  GPHR_REQUIRE(text.find_first_not_of(" \t\r\n") != std::string::npos, InputError, source,
               " is empty; allowed: a YAML mapping");
  std::string out;
  out.reserve(text.size());
  int lineNo = 0;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find('\n', start), text.size());
    std::string line = text.substr(start, end - start);
    ++lineNo;
    GPHR_REQUIRE(line.size() <= kMaxYamlLineBytes, InputError, source, ": line ", lineNo, " has ", line.size(),
                 " bytes; allowed: at most ", kMaxYamlLineBytes, " (a long list in block style, one item per line)");
    for (size_t i = 0; i < line.size(); ++i) {
      const unsigned char c = static_cast<unsigned char>(line[i]);
      GPHR_REQUIRE(c >= 0x20 || c == '\t' || c == '\r', InputError, source, " is not a text file (byte ",
                   static_cast<int>(c), " at line ", lineNo, " column ", i + 1, "); allowed: a YAML file");
    }
    const LineShape shape = shapeOf(line);
    for (size_t i = 0; i < line.size(); ++i) {
      if (static_cast<unsigned char>(line[i]) < 0x80) continue;
      GPHR_REQUIRE(i > shape.comment && shape.comment != std::string::npos, InputError, source, ": line ", lineNo,
                   " column ", i + 1, " holds a non-ASCII character outside a comment; allowed: ASCII (other "
                   "characters in comments only)");
      line[i] = ' ';
    }
    GPHR_REQUIRE(!shape.unclosedQuote, InputError, source, ": line ", lineNo,
                 " opens a quoted value it does not close; allowed: a quoted value on one line");
    GPHR_REQUIRE(!blockScalar(line, shape), InputError, source, ": line ", lineNo,
                 " starts a block scalar (| or >); allowed: a value on the key's line");
    out += line;
    if (end < text.size()) out += '\n';
    start = end + 1;
  }
  return out;
}

// The deepest nesting of the text (block mappings by indent, plus flow { [ on a line) and its line.
std::pair<long, int> nestingOf(const std::string& text) {
  std::vector<size_t> indents;  // the block mappings open at this line
  std::pair<long, int> deepest{0, 0};
  forEachContentLine(text, [&](const std::string& line, int lineNo, size_t indent) {
    while (!indents.empty() && indents.back() > indent) indents.pop_back();
    if (indents.empty() || indents.back() < indent) indents.push_back(indent);
    const long depth = static_cast<long>(indents.size()) + shapeOf(line).deepest;
    if (depth > deepest.first) deepest = {depth, lineNo};
  });
  return deepest;
}

// Teuchos' reader silently drops a second top-level key whose value is a scalar or a list (a
// mis-indented "pipeline: [rom]" at column 0): the text's top level must be the one key of its
// kind. Lines at column 0 that are comments, directives, document markers or list items are not keys.
void requireSingleTopLevelKey(const std::string& text, const std::string& source, const std::string& root) {
  std::istringstream in(text);
  int lineNo = 0, keys = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNo;
    if (line.empty() || std::string(" \t\r#-%.").find(line[0]) != std::string::npos) continue;
    ++keys;
    const std::string key = line.substr(0, line.find(':'));
    const std::string name = key.size() >= 2 && (key[0] == '"' || key[0] == '\'') ? key.substr(1, key.size() - 2) : key;
    GPHR_REQUIRE(name == root, InputError, source, " has the top-level key '", shortened(name), "' at line ", lineNo,
                 "; allowed: the single key '", root, "' (other keys are indented under it)");
  }
  GPHR_REQUIRE(keys > 0, InputError, source, " has no top-level key; allowed: a YAML mapping under the key '", root,
               "'");
}

// A key given twice in one of the line's flow mappings {a: 1, b: {c: 2}} (each at its own depth),
// as "key 'a' in the flow mapping at line N"; "" if none.
std::string duplicateFlowKey(const std::string& line, int lineNo) {
  for (size_t open = line.find('{'); open != std::string::npos; open = line.find('{', open + 1)) {
    std::set<std::string> keys;
    std::string item;
    int depth = 0;
    char quote = 0;
    for (size_t i = open + 1; i < line.size(); ++i) {
      const char c = line[i];
      if (quote || c == '"' || c == '\'') {
        quote = quote == c ? 0 : (quote ? quote : c);
      } else if (depth == 0 && (c == ',' || c == '}')) {
        const size_t colon = item.find(':');
        const size_t first = item.find_first_not_of(' '),
                     last = colon == std::string::npos ? 0 : item.find_last_not_of(' ', colon - 1);
        if (colon != std::string::npos && first < colon) {
          const std::string key = item.substr(first, last + 1 - first);
          if (!keys.insert(key).second) return detail::concat("key '", key, "' in the flow mapping at line ", lineNo);
        }
        item.clear();
        if (c == '}') break;
        continue;
      } else if (c == '{' || c == '[') {
        ++depth;
      } else if (c == '}' || c == ']') {
        --depth;
      }
      item += c;
    }
  }
  return "";
}

// Whether a line opens a flow collection { [ that it does not close.
bool unclosedFlow(const std::string& text) {
  bool open = false;
  forEachContentLine(text, [&](const std::string& line, int, size_t) { open = open || shapeOf(line).open > 0; });
  return open;
}

}  // namespace

std::string teuchosMessage(const std::string& what) { return shortened(teuchosReason(what)); }

std::string duplicateYamlKey(const std::string& text) {
  // Block mappings: a key is a line "  name:" (no flow braces before the colon); a mapping's keys
  // share its indent, and a deeper line opens a child mapping of the key above it.
  struct Level {
    size_t indent;
    std::map<std::string, int> keys;  // key -> line
  };
  std::vector<Level> stack;
  std::string found;
  forEachContentLine(text, [&](const std::string& line, int lineNo, size_t indent) {
    if (!found.empty()) return;
    found = duplicateFlowKey(line, lineNo);
    if (!found.empty() || line[indent] == '-') return;
    const size_t colon = line.find(':', indent);
    if (colon == std::string::npos || line.find_first_of("{[\"'", indent) < colon) return;
    const std::string key = line.substr(indent, colon - indent);
    while (!stack.empty() && stack.back().indent > indent) stack.pop_back();
    if (stack.empty() || stack.back().indent < indent) stack.push_back(Level{indent, {}});
    const auto [it, added] = stack.back().keys.emplace(key, lineNo);
    if (!added) found = detail::concat("key '", key, "' at line ", lineNo, " (first at line ", it->second, ")");
  });
  return found;
}

Teuchos::RCP<Teuchos::ParameterList> parseYamlText(const std::string& text, const std::string& source,
                                                   const std::string& rootKey) {
  const std::string clean = checkedText(text, source);
  if (!rootKey.empty()) requireSingleTopLevelKey(clean, source, rootKey);
  const auto [depth, line] = nestingOf(clean);
  GPHR_REQUIRE(depth <= kMaxYamlNesting, InputError, source, " nests ", depth, " levels deep at line ", line,
               "; allowed: at most ", kMaxYamlNesting);
  try {
    return Teuchos::getParametersFromYamlString(clean);
  } catch (const std::exception& e) {
    // Teuchos refuses a duplicate key with a message about something else: name it (scanned only
    // here: the scan does not know block lists of mappings, which GPHR's files do not use).
    const std::string dup = duplicateYamlKey(clean);
    GPHR_REQUIRE(dup.empty(), InputError, source, " has a duplicate ", shortened(dup),
                 "; allowed: each key once per mapping");
    const std::string what = e.what();
    // Teuchos' reader takes a flow mapping {a: 1, b: 2} on one line only: say so, since its own
    // message gives just a position.
    throw InputError(detail::concat(
        source, " is malformed YAML: ",
        shortened(what.find("Parser failure") == std::string::npos ? teuchosReason(what) : firstLineOf(what)),
        unclosedFlow(clean) ? " (a {key: value, ...} mapping must fit on one line; write longer sections in block "
                              "style, one key per line)"
                            : ""));
  }
}

}  // namespace gphr
