// The method registry: names unique and refused by name when unknown, and each entry's traits
// consistent with one another, since builders, model files and reports select by traits alone.
#include <gtest/gtest.h>

#include <string>

#include "gphr/core/Error.hpp"
#include "gphr/core/Method.hpp"

namespace gphr {
namespace {

TEST(MethodRegistry, NamesAreUniqueAndUnknownOnesAreRefusedByName) {
  const auto& all = methodRegistry();
  for (size_t i = 0; i < all.size(); ++i)
    for (size_t j = i + 1; j < all.size(); ++j) {
      EXPECT_NE(std::string(all[i].name), all[j].name);
      EXPECT_NE(all[i].id, all[j].id) << all[i].name << " and " << all[j].name;
    }
  EXPECT_EQ(methodNames(), "fom, rom, gp-deim, gp-adeim, deim, sdeim, gp-eqp, gp-eqp-refit");
  EXPECT_TRUE(isMethod("gp-deim"));
  EXPECT_FALSE(isMethod("gp_deim"));
  for (const auto& m : all) {
    EXPECT_EQ(&methodInfo(m.id), &m) << m.name;
    EXPECT_EQ(&methodInfo(std::string(m.name)), &m) << m.name;
  }
  try {
    methodInfo("gp_deim");
    ADD_FAILURE() << "an unknown method was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'gp_deim'; allowed: fom, rom, gp-deim"), std::string::npos) << e.what();
  }
}

TEST(MethodRegistry, TraitsAgreeWithOneAnother) {
  for (const auto& m : methodRegistry()) {
    // a weight fit exactly for the term-weighted methods, a gradient basis exactly for the baselines
    EXPECT_EQ(m.fit != TermWeightFit::None, m.reduction == Reduction::TermWeights) << m.name;
    EXPECT_EQ(m.gradientBasis != GradientBasis::None, m.reduction == Reduction::GradientDeim) << m.name;
    // only the adaptive method samples the full residual online (its queries build the full system)
    EXPECT_EQ(m.needsFullResidual, m.adaptive()) << m.name;
    // a model file holds the hyper-reduced Hamiltonian models: a sample mesh with weights, or GP-ADEIM
    EXPECT_EQ(m.storable, m.reduction == Reduction::TermWeights || m.adaptive()) << m.name;
    EXPECT_EQ(m.storable, std::string(m.fromFile) != "") << m.name;
    // m is a size of the hyper-reduction: never of the full model or the ROM; the sdeim's is 2k
    if (!m.hyperReduced()) {
      EXPECT_FALSE(m.takesM) << m.name;
    }
    EXPECT_EQ(m.takesM, m.hyperReduced() && m.gradientBasis != GradientBasis::ReducedBasis) << m.name;
  }
  EXPECT_EQ(methodNames([](const MethodInfo& m) { return m.storable; }), "gp-deim, gp-adeim, gp-eqp, gp-eqp-refit");
  EXPECT_EQ(methodNames([](const MethodInfo& m) { return m.quadratureFit(); }), "gp-eqp, gp-eqp-refit");
  EXPECT_EQ(methodNames([](const MethodInfo& m) { return !m.reduced(); }), "fom");
  EXPECT_EQ(methodNames([](const MethodInfo& m) { return m.reduced() && !m.hyperReduced(); }), "rom");
}

}  // namespace
}  // namespace gphr
