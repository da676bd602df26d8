#include "gphr/driver/InputFile.hpp"

#include <Teuchos_StringInputSource.hpp>
#include <Teuchos_XMLParameterListReader.hpp>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "gphr/core/Error.hpp"
#include "gphr/core/YamlText.hpp"

namespace gphr {

namespace {

// The single key a file of this kind has at its top level.
std::string rootKey(const std::string& what) { return what == "config" ? "gphr" : what; }

// The file's bytes, after the checks that need no reading of its contents.
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
  GPHR_REQUIRE(!ec && size <= kMaxYamlBytes, InputError, what, " file '", path, "' has ", size,
               " bytes; allowed: at most ", kMaxYamlBytes);
  std::ifstream in(path, std::ios::binary);
  GPHR_REQUIRE(in.good(), InputError, "cannot read ", what, " file '", path, "'");
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Teuchos' XML reader returns the root list's entries in a list named ANONYMOUS: name it after the
// root element's name attribute, as the YAML reader names it after the top-level key.
void nameAfterXmlRoot(const Teuchos::XMLObject& root, Teuchos::ParameterList& pl) {
  if (root.hasAttribute("name")) pl.setName(root.getAttribute("name"));
}

// An int as written: a whole number in int's range (Teuchos' reader wraps 4294967360 to 64).
void requireXmlInt(const std::string& text, const std::string& where) {
  const auto first = text.find_first_not_of(" \t"), last = text.find_last_not_of(" \t");
  const std::string v = first == std::string::npos ? "" : text.substr(first, last + 1 - first);
  const size_t digits = v.find_first_not_of("0123456789", v.empty() || (v[0] != '-' && v[0] != '+') ? 0 : 1);
  errno = 0;
  const long long x = std::strtoll(v.c_str(), nullptr, 10);
  GPHR_REQUIRE(!v.empty() && digits == std::string::npos && v.find_first_of("0123456789") != std::string::npos &&
                   errno == 0 && x >= std::numeric_limits<int>::min() && x <= std::numeric_limits<int>::max(),
               InputError, where, " has value '", v.substr(0, 40), "'; allowed: a whole number from ",
               std::numeric_limits<int>::min(), " to ", std::numeric_limits<int>::max());
}

// The XML rules that Teuchos' reader does not keep and the YAML reader does: each name once among
// a list's entries (Teuchos keeps the last silently), ints in range (it wraps them), and the
// YAML depth limit.
void checkXmlList(const Teuchos::XMLObject& list, const std::string& path, int depth) {
  GPHR_REQUIRE(depth <= kMaxYamlNesting, InputError, "nests ", depth, " levels deep at '", path, "'; allowed: at most ",
               kMaxYamlNesting);
  std::set<std::string> names;
  for (int i = 0; i < list.numChildren(); ++i) {
    const Teuchos::XMLObject& c = list.getChild(i);
    if (c.getTag() != "Parameter" && c.getTag() != "ParameterList") continue;
    const std::string name = c.hasAttribute("name") ? c.getAttribute("name") : "";
    const std::string where = "key '" + (path.empty() ? name : path + "." + name) + "'";
    GPHR_REQUIRE(names.insert(name).second, InputError, where, " is given twice; allowed: each key once per list");
    if (c.getTag() == "ParameterList") {
      checkXmlList(c, path.empty() ? name : path + "." + name, depth + 1);
      continue;
    }
    const std::string type = c.hasAttribute("type") ? c.getAttribute("type") : "";
    const std::string value = c.hasAttribute("value") ? c.getAttribute("value") : "";
    if (type == "int") requireXmlInt(value, where);
    if (type == "Array(int)") {  // {1, 2, 3}
      std::string items = value;
      for (char& ch : items)
        if (ch == '{' || ch == '}' || ch == ',') ch = ' ';
      std::istringstream in(items);
      for (std::string item; in >> item;) requireXmlInt(item, where);
    }
  }
}

// An XML config: the byte and line limits of a YAML text, then Teuchos' reader, then the rules above.
Teuchos::RCP<Teuchos::ParameterList> parseXml(const std::string& text, const std::string& source) {
  size_t lineNo = 1, lineStart = 0;
  for (size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size() && text[i] != '\n') continue;
    GPHR_REQUIRE(i - lineStart <= kMaxYamlLineBytes, InputError, source, ": line ", lineNo, " has ", i - lineStart,
                 " bytes; allowed: at most ", kMaxYamlLineBytes);
    ++lineNo, lineStart = i + 1;
  }
  try {
    Teuchos::StringInputSource input(text);
    const Teuchos::XMLObject root = input.getObject();
    checkXmlList(root, "", 1);
    auto pl = Teuchos::XMLParameterListReader().toParameterList(root);
    auto out = Teuchos::rcp(new Teuchos::ParameterList(pl));
    nameAfterXmlRoot(root, *out);
    return out;
  } catch (const InputError& e) {
    throw InputError(detail::concat(source, ": ", e.what()));
  } catch (const std::exception& e) {
    throw InputError(detail::concat(source, " is malformed XML: ", teuchosMessage(e.what())));
  }
}

}  // namespace

Teuchos::RCP<Teuchos::ParameterList> readParameterFile(const std::string& path, const std::string& what, bool xml) {
  const std::string text = readText(path, what), source = what + " file '" + path + "'";
  return xml ? parseXml(text, source) : parseYamlText(text, source, rootKey(what));
}

}  // namespace gphr
