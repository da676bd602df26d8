#include "gphr/core/ParameterValidation.hpp"

#include <limits>
#include <sstream>

#include "gphr/core/Error.hpp"

namespace gphr {

using Teuchos::ParameterList;
using IntValidator = Teuchos::EnhancedNumberValidator<int>;
using DoubleValidator = Teuchos::EnhancedNumberValidator<double>;
using ChoiceValidator = Teuchos::StringValidator;

namespace {

// Marks a section of a valid list as passed through (see setPassThroughSection).
class PassThroughValidator : public Teuchos::ParameterEntryValidator {
 public:
  const std::string getXMLTypeName() const override { return "gphrPassThroughSection"; }
  void printDoc(const std::string& doc, std::ostream& os) const override { os << "# " << doc << "\n"; }
  ValidStringsList validStringValues() const override { return Teuchos::null; }
  void validate(const Teuchos::ParameterEntry&, const std::string&, const std::string&) const override {}
};

bool isPassThrough(const Teuchos::ParameterEntry& e) {
  return !Teuchos::rcp_dynamic_cast<const PassThroughValidator>(e.validator()).is_null();
}

std::string keyList(const ParameterList& valid) {
  std::string s;
  for (auto it = valid.begin(); it != valid.end(); ++it) s += (s.empty() ? "" : ", ") + valid.name(it);
  return s;
}

std::string allowedText(const Teuchos::ParameterEntry& e) {
  auto v = e.validator();
  std::ostringstream os;
  os.precision(12);
  if (auto iv = Teuchos::rcp_dynamic_cast<const IntValidator>(v); !iv.is_null()) {
    os << "an integer in [" << iv->getMin() << ", " << iv->getMax() << "]";
  } else if (auto dv = Teuchos::rcp_dynamic_cast<const DoubleValidator>(v); !dv.is_null()) {
    os << "a number in [" << dv->getMin() << ", " << dv->getMax() << "]";
  } else if (auto cv = Teuchos::rcp_dynamic_cast<const ChoiceValidator>(v); !cv.is_null()) {
    os << "one of";
    for (const auto& c : *cv->validStringValues()) os << " '" << c << "'";
  } else if (e.isType<bool>()) {
    os << "true or false";
  } else if (e.isType<std::string>()) {
    os << "a string";
  } else if (e.isType<Teuchos::Array<double>>()) {
    os << "a list of numbers";
  } else {
    os << "a value of type " << e.getAny(false).typeName();
  }
  return os.str();
}

// YAML gives 3 for a double key: accept an int where a double is expected.
void coerceNumber(ParameterList& user, const std::string& key, const Teuchos::ParameterEntry& ve) {
  Teuchos::ParameterEntry& ue = user.getEntry(key);
  if (ve.isType<double>() && ue.isType<int>()) user.set(key, static_cast<double>(Teuchos::getValue<int>(ue)));
  if (ve.isType<Teuchos::Array<double>>() && ue.isType<Teuchos::Array<int>>()) {
    const auto& a = Teuchos::getValue<Teuchos::Array<int>>(ue);
    user.set(key, Teuchos::Array<double>(a.begin(), a.end()));
  }
}

std::string valueText(const Teuchos::ParameterEntry& e) {
  if (e.isType<double>()) return detail::concat(e.getValue<double>(nullptr));  // as read (Error.hpp's Shortest)
  std::ostringstream os;
  os.precision(12);
  os << std::boolalpha;
  e.getAny(false).print(os);
  return os.str();
}

// What kind of value the YAML reader made of an entry: 64.0 and 1e2 are real numbers and "64" a
// string, though each prints as a number, so a type mismatch says which it got.
std::string kindText(const Teuchos::ParameterEntry& e) {
  if (e.isType<int>()) return "an integer";
  if (e.isType<double>()) return "a real number (written with a point or an exponent)";
  if (e.isType<std::string>()) return "a string (quoted, or not a number)";
  if (e.isType<bool>()) return "true or false";
  if (e.isType<Teuchos::Array<int>>() || e.isType<Teuchos::Array<double>>() ||
      e.isType<Teuchos::Array<std::string>>())
    return "a list";
  return "a value of type " + e.getAny(false).typeName();
}

}  // namespace

void validateParameters(ParameterList& user, const ParameterList& valid, const std::string& path) {
  const std::string where = path.empty() ? "" : path + ".";
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string key = user.name(it);
    GPHR_REQUIRE(valid.isParameter(key), InputError, "unknown key '", where, key, "'; valid keys",
                 path.empty() ? "" : " in '" + path + "'", ": ", keyList(valid));
    const Teuchos::ParameterEntry& ve = valid.getEntry(key);
    if (ve.isList()) {
      GPHR_REQUIRE(user.isSublist(key), InputError, "key '", where, key,
                   "' must be a section (a map of keys), not a value; valid keys in it: ",
                   keyList(valid.sublist(key)));
      if (!isPassThrough(ve)) validateParameters(user.sublist(key), valid.sublist(key), where + key);
      continue;
    }
    GPHR_REQUIRE(!user.isSublist(key), InputError, "key '", where, key,
                 "' must be a value, not a section; allowed: ", allowedText(ve));
    coerceNumber(user, key, ve);
    const Teuchos::ParameterEntry& ue = user.getEntry(key);
    GPHR_REQUIRE(ue.getAny(false).type() == ve.getAny(false).type(), InputError, "key '", where, key,
                 "' has value ", valueText(ue), ", ", kindText(ue), "; allowed: ", allowedText(ve));
    if (!ve.validator().is_null()) {
      try {
        ve.validator()->validate(ue, key, path);
      } catch (const std::exception&) {
        throw InputError(detail::concat("key '", where, key, "' has value ", valueText(ue),
                                        "; allowed: ", allowedText(ve)));
      }
    }
  }
  // Defaults for what the user left out (recursively for sections).
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string key = valid.name(it);
    if (valid.isSublist(key)) {
      if (!user.isSublist(key)) user.sublist(key);
      if (!isPassThrough(valid.getEntry(key))) validateParameters(user.sublist(key), valid.sublist(key), where + key);
    } else if (!user.isParameter(key)) {
      user.setEntry(key, valid.getEntry(key));
    }
  }
}

void describeParameters(const ParameterList& valid, std::ostream& os, int indent) {
  const std::string pad(indent, ' ');
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string key = valid.name(it);
    const Teuchos::ParameterEntry& e = valid.getEntry(key);
    if (e.isList()) {
      os << pad << key << ":" << (isPassThrough(e) ? " (section passed through)" : "") << "\n";
      if (isPassThrough(e)) os << pad << "    " << e.docString() << "\n";
      describeParameters(valid.sublist(key), os, indent + 2);
      continue;
    }
    os << pad << key << " (default " << valueText(e) << "; " << allowedText(e) << ")\n";
    if (!e.docString().empty()) os << pad << "    " << e.docString() << "\n";
  }
}

void setIntParameter(ParameterList& pl, const std::string& name, int def, int lo, int hi,
                     const std::string& doc) {
  pl.set(name, def, doc, Teuchos::rcp(new IntValidator(lo, hi)));
}

void setDoubleParameter(ParameterList& pl, const std::string& name, double def, double lo, double hi,
                        const std::string& doc) {
  pl.set(name, def, doc, Teuchos::rcp(new DoubleValidator(lo, hi)));
}

void setChoiceParameter(ParameterList& pl, const std::string& name, const std::string& def,
                        const Teuchos::Array<std::string>& choices, const std::string& doc) {
  pl.set(name, def, doc, Teuchos::rcp(new ChoiceValidator(choices)));
}

void setPassThroughSection(ParameterList& pl, const std::string& name, const std::string& doc) {
  pl.set(name, ParameterList(name), doc, Teuchos::rcp(new PassThroughValidator));
}

}  // namespace gphr
