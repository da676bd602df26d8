#include "gphr/driver/InputFile.hpp"

#include <Teuchos_StringInputSource.hpp>
#include <Teuchos_XMLParameterListCoreHelpers.hpp>
#include <Teuchos_YamlParameterListCoreHelpers.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "gphr/core/Error.hpp"

namespace gphr {

namespace {

// The line of Teuchos' message that names the problem ("Parser failure at line L column C").
std::string firstLineOf(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  const auto pos = s.find("Parser failure");
  if (pos != std::string::npos) line = s.substr(pos, s.find('\n', pos) - pos);
  return line;
}

// The single key a file of this kind has at its top level.
std::string rootKey(const std::string& what) { return what == "config" ? "gphr" : what; }

// The file's bytes, after the checks that need no parsing.
std::string readText(const std::string& path, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto st = fs::status(path, ec);
  GPHR_REQUIRE(st.type() != fs::file_type::not_found, InputError, "cannot read ", what, " file '", path,
               "': no such file");
  GPHR_REQUIRE(st.type() != fs::file_type::directory, InputError, what, " file '", path,
               "' is a directory; allowed: a YAML file");
  GPHR_REQUIRE(st.type() == fs::file_type::regular, InputError, what, " file '", path,
               "' is not a regular file; allowed: a YAML file");
  const auto size = fs::file_size(path, ec);
  GPHR_REQUIRE(!ec && size <= kMaxParameterFileBytes, InputError, what, " file '", path, "' has ", size,
               " bytes; allowed: at most ", kMaxParameterFileBytes);
  std::ifstream in(path, std::ios::binary);
  GPHR_REQUIRE(in.good(), InputError, "cannot read ", what, " file '", path, "'");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  GPHR_REQUIRE(text.find_first_not_of(" \t\r\n") != std::string::npos, InputError, what, " file '", path,
               "' is empty; allowed: a YAML mapping under the key '", rootKey(what), "'");
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    GPHR_REQUIRE(c >= 0x20 || c == '\t' || c == '\n' || c == '\r', InputError, what, " file '", path,
                 "' is not a text file (byte ", static_cast<int>(c), " at offset ", i, "); allowed: a YAML file");
  }
  return text;
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

// A YAML file's top level must be the one mapping key of its kind: Teuchos' reader silently drops
// a second key whose value is a scalar or a list (a mis-indented "pipeline: [rom]" at column 0),
// and fails on a second flow mapping with a message about flow mappings. Lines at column 0 that
// are comments, directives, document markers or list items are not keys.
void requireSingleTopLevelKey(const std::string& text, const std::string& path, const std::string& what) {
  std::istringstream in(text);
  int lineNo = 0, keys = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNo;
    if (line.empty() || std::string(" \t\r#-%.").find(line[0]) != std::string::npos) continue;
    ++keys;
    const std::string key = line.substr(0, line.find(':'));
    const std::string name = key.size() >= 2 && (key[0] == '"' || key[0] == '\'') ? key.substr(1, key.size() - 2) : key;
    GPHR_REQUIRE(name == rootKey(what), InputError, what, " file '", path, "' has the top-level key '", name,
                 "' at line ", lineNo, "; allowed: the single key '", rootKey(what), "' (other keys are indented under it)");
  }
  GPHR_REQUIRE(keys > 0, InputError, what, " file '", path, "' has no top-level key; allowed: a YAML mapping under the key '",
               rootKey(what), "'");
}

// Teuchos' XML reader returns the root list's entries in a list named ANONYMOUS: name it after the
// root element's name attribute, as the YAML reader names it after the top-level key.
void nameAfterXmlRoot(const std::string& text, Teuchos::ParameterList& pl) {
  Teuchos::StringInputSource source(text);
  const Teuchos::XMLObject root = source.getObject();
  if (root.hasAttribute("name")) pl.setName(root.getAttribute("name"));
}

// A key given twice in one of the line's flow mappings {a: 1, b: {c: 2}} (each at its own depth;
// Teuchos takes them on one line only), as "key 'a' in the flow mapping at line N"; "" if none.
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
        const size_t first = item.find_first_not_of(' '), last = colon == std::string::npos ? 0 : item.find_last_not_of(' ', colon - 1);
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

// The flow collections { [ of a line outside quotes and comments: the deepest nesting on it, and
// how many it leaves open at its end.
std::pair<long, long> flowDepth(const std::string& line) {
  long depth = 0, most = 0;
  char quote = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote || c == '"' || c == '\'') quote = quote == c ? 0 : (quote ? quote : c);
    else if (c == '#' && (i == 0 || line[i - 1] == ' ')) break;
    else if (c == '{' || c == '[') most = std::max(most, ++depth);
    else if (c == '}' || c == ']') --depth;
  }
  return {most, depth};
}

// GPHR's deepest config nests 4 levels (gphr: section: key: {flow}); Teuchos copies a nested
// list again at every level above it, so a file nesting thousands deep (25 KB) parses for minutes.
constexpr long kMaxNesting = 32;

// The deepest nesting of the YAML text (block mappings by indent, plus flow { [ on a line) and the
// line where it is reached.
std::pair<long, int> yamlNesting(const std::string& text) {
  std::vector<size_t> indents;  // the block mappings open at this line
  std::pair<long, int> deepest{0, 0};
  forEachContentLine(text, [&](const std::string& line, int lineNo, size_t indent) {
    while (!indents.empty() && indents.back() > indent) indents.pop_back();
    if (indents.empty() || indents.back() < indent) indents.push_back(indent);
    const long depth = static_cast<long>(indents.size()) + flowDepth(line).first;
    if (depth > deepest.first) deepest = {depth, lineNo};
  });
  return deepest;
}

// Whether a line opens a flow collection { [ that it does not close.
bool unclosedFlow(const std::string& text) {
  bool open = false;
  forEachContentLine(text, [&](const std::string& line, int, size_t) { open = open || flowDepth(line).second > 0; });
  return open;
}

}  // namespace

std::string duplicateYamlKey(const std::string& text) {
  // Block mappings: a key is a line "  name:" (no flow braces before the colon); a mapping's keys
  // share its indent, and a deeper line opens a child mapping of the key above it. Flow mappings
  // on a line: duplicateFlowKey.
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

Teuchos::RCP<Teuchos::ParameterList> readParameterFile(const std::string& path, const std::string& what, bool xml) {
  const std::string text = readText(path, what);
  if (!xml) {
    requireSingleTopLevelKey(text, path, what);
    const auto [depth, line] = yamlNesting(text);
    GPHR_REQUIRE(depth <= kMaxNesting, InputError, what, " file '", path, "' nests ", depth, " levels deep at line ",
                 line, "; allowed: at most ", kMaxNesting);
  }
  try {
    if (!xml) return Teuchos::getParametersFromYamlString(text);
    auto pl = Teuchos::getParametersFromXmlString(text);
    nameAfterXmlRoot(text, *pl);
    return pl;
  } catch (const std::exception& e) {
    const std::string dup = xml ? "" : duplicateYamlKey(text);
    GPHR_REQUIRE(dup.empty(), InputError, what, " file '", path, "' has a duplicate ", dup,
                 "; allowed: each key once per mapping");
    // Teuchos' YAML reader takes a flow mapping {a: 1, b: 2} on one line only: say so, since its
    // own message gives just a position.
    throw InputError(detail::concat(what, " file '", path, "' is malformed ", xml ? "XML" : "YAML", ": ",
                                    xml || std::string(e.what()).find("Parser failure") == std::string::npos
                                        ? teuchosReason(e.what())
                                        : firstLineOf(e.what()),
                                    xml || !unclosedFlow(text)
                                        ? ""
                                        : " (a {key: value, ...} mapping must fit on one line; "
                                          "write longer sections in block style, one key per line)"));
  }
}

}  // namespace gphr
