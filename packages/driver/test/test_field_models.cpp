// Which runs the field outputs show, and what a scene without a grid gets: a message naming it,
// not a file.
#include <gtest/gtest.h>

#include "gphr/core/Error.hpp"
#include "gphr/driver/FieldModels.hpp"
#include "gphr/driver/FieldPictures.hpp"
#include "gphr/driver/XdmfWriter.hpp"
#include "gphr/models/Scene.hpp"

using namespace gphr;

namespace {

// A finished run with `states` lifted states (null vectors: FieldStates only counts and keeps them).
ModelRun run(const std::string& method, int m, double eL2, size_t states, bool ok = true) {
  ModelRun r;
  r.method = method, r.k = 4, r.m = m, r.eL2 = eL2, r.ok = ok;
  r.states.assign(states, Teuchos::null);
  return r;
}

// Runs offered in the order the pipeline evaluates them: each name keeps its most accurate
// complete run so far, and a superseded run's states are released (their use count drops to 0).
TEST(FieldModels, EachNameKeepsItsMostAccurateCompleteRun) {
  FieldStates fields({"rom", "best", "gp-adeim"}, 5);
  EXPECT_TRUE(fields.wants("rom") && fields.wants("sdeim") && fields.wants("gp-deim"));
  EXPECT_FALSE(FieldStates({"gp-deim"}, 5).wants("rom"));
  ModelRun rom = run("rom", 0, 1e-3, 5), coarse = run("gp-deim", 8, 1e-2, 5), fine = run("gp-deim", 16, 2e-3, 5),
           cut = run("gp-eqp", 16, 1e-4, 4), diverged = run("deim", 16, 1e-5, 5, false), sdeim = run("sdeim", 8, 5e-3, 5);
  fields.offer(rom);
  fields.offer(coarse);
  const std::weak_ptr<const FieldStates::Kept> first = fields.picked().back();
  ASSERT_EQ(first.lock()->label, "gp-deim k=4 m=8");
  for (ModelRun* r : {&fine, &cut, &diverged, &sdeim}) fields.offer(*r);
  EXPECT_TRUE(first.expired());  // gp-deim m=8's states went when m=16 beat it
  const auto picked = fields.picked();
  ASSERT_EQ(picked.size(), 2u);
  EXPECT_EQ(picked[0]->label, "rom k=4");
  EXPECT_EQ(picked[1]->label, "gp-deim k=4 m=16");  // gp-eqp kept too few states, deim diverged
  EXPECT_EQ(picked[1]->states.size(), 5u);
  EXPECT_TRUE(fine.states.empty() && sdeim.states.empty());  // taken or dropped, never left with the run
  ASSERT_EQ(fields.notes().size(), 1u);
  EXPECT_NE(fields.notes()[0].find("'gp-adeim'"), std::string::npos) << fields.notes()[0];
  FieldStates same({"gp-deim", "best"}, 5);
  ModelRun again = run("gp-deim", 16, 2e-3, 5);
  same.offer(again);
  EXPECT_EQ(same.picked().size(), 1u);  // one run picked by two names is shown once
}

TEST(FieldModels, NearestSavedTime) {
  const std::vector<size_t> got = nearestSaved({0.0, 0.1, 0.2, 0.25}, {0.0, 0.14, 0.16, 1.0});
  EXPECT_EQ(got, (std::vector<size_t>{0, 1, 2, 3}));
}

// A user's scene that declares no grid (Scene::grid's default).
class NoGrid final : public Scene {
 public:
  std::string name() const override { return "my-scene"; }
  const ParameterBox& parameterBox() const override { return box_; }
  std::pair<RCP<HamiltonianSystem>, RCP<Vector>> build(const RCP<const Comm>&, const std::vector<double>&) const override {
    return {};
  }
  RCP<const RowEvaluator> rowKernel(const std::vector<double>&) const override { return Teuchos::null; }

 private:
  ParameterBox box_;
};

TEST(FieldModels, ASceneWithoutAGridIsToldSo) {
  try {
    fieldGrid(NoGrid(), 8);
    FAIL() << "no InputError for a scene without a grid";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("scene 'my-scene' declares no grid"), std::string::npos) << msg;
  }
  EXPECT_THROW(fieldGrid(Swe2d(6), 2 * 36 + 1), InputError);  // a grid that does not fit the states
  EXPECT_EQ(fieldGrid(Swe2d(6), 2 * 36).numPoints(), 36);
  EXPECT_EQ(fieldName("gp-deim k=10 m=20"), "gp-deim_k10_m20");
}

// Rank 0 gathers what fields.png draws: a grid over 512^2 points is not drawn, nor a 3-D one, and
// each gets a line saying why (before any state is touched: the full model here has none).
TEST(FieldPictures, LargeAndThreeDimensionalGridsAreNotDrawn) {
  FieldOutput out;
  out.grid = SceneGrid{{513, 512}, {0.0, 0.0}, {1.0, 1.0}, {"h", "p"}, false};
  const FieldPicture big = fieldPicture({}, FomResult(), out);
  EXPECT_TRUE(big.file.empty());
  EXPECT_NE(big.note.find("a grid of 262656 points is more than the 262144 drawn"), std::string::npos) << big.note;
  out.grid = SceneGrid{{4, 4, 4}, {0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {"h", "p"}, false};
  const FieldPicture cube = fieldPicture({}, FomResult(), out);
  EXPECT_TRUE(cube.file.empty());
  EXPECT_NE(cube.note.find("1-D and 2-D grids"), std::string::npos) << cube.note;
}

}  // namespace
