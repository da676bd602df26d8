#include "gphr/models/Scene.hpp"

#include "gphr/core/Error.hpp"

namespace gphr {

void ParameterBox::check(const std::vector<double>& mu) const {
  GPHR_REQUIRE(mu.size() == names.size(), InputError, "expected ", names.size(),
               " parameter value(s) but got ", mu.size());
  for (size_t i = 0; i < mu.size(); ++i)
    GPHR_REQUIRE(mu[i] >= bounds[i].first && mu[i] <= bounds[i].second, InputError, "parameter ",
                 names[i], " = ", mu[i], " lies outside the scene's box [", bounds[i].first, ", ",
                 bounds[i].second, "]");
}

GO SceneGrid::numPoints() const {
  GO count = 1;
  for (GO p : points) count *= p;
  return count;
}

void SceneGrid::check(GO fullDim, const std::string& scene) const {
  GPHR_REQUIRE(!points.empty() && points.size() <= 3 && origin.size() == points.size() &&
                   spacing.size() == points.size(),
               InputError, "scene '", scene, "' declares a grid of ", points.size(), " directions with ", origin.size(),
               " origin and ", spacing.size(), " spacing values; allowed: 1 to 3 directions, one of each per direction");
  for (size_t d = 0; d < points.size(); ++d)
    GPHR_REQUIRE(points[d] >= 1 && spacing[d] > 0.0, InputError, "scene '", scene, "' declares direction ", d,
                 " with ", points[d], " points and spacing ", spacing[d], "; allowed: >= 1 point, spacing > 0");
  GPHR_REQUIRE(!components.empty() && numPoints() * static_cast<GO>(components.size()) == fullDim, InputError,
               "scene '", scene, "' declares a grid of ", numPoints(), " points and ", components.size(),
               " components for a state of size ", fullDim, "; allowed: points x components = the state's size");
}

std::pair<RCP<HamiltonianSystem>, RCP<Vector>> Scene::rebuild(const HamiltonianSystem& like,
                                                              const std::vector<double>& mu) const {
  return build(like.space().comm(), mu);
}

namespace {
SceneInstance shiftedIfAsked(std::pair<RCP<HamiltonianSystem>, RCP<Vector>> built, bool shift) {
  auto [system, y0] = std::move(built);
  SceneInstance s;
  s.physicalInitialState = y0;
  if (!shift) {
    s.system = system;
    s.y0 = rcp(new Vector(*y0, Teuchos::Copy));
  } else {
    s.system = system->shifted(*y0);
    s.y0 = rcp(new Vector(y0->getMap()));  // y_s(0) = 0
  }
  return s;
}
}  // namespace

SceneInstance Scene::instantiate(const RCP<const Comm>& comm, const std::vector<double>& mu, bool shift) const {
  return shiftedIfAsked(build(comm, mu), shift);
}

SceneInstance Scene::instantiate(const HamiltonianSystem& like, const std::vector<double>& mu, bool shift) const {
  return shiftedIfAsked(rebuild(like, mu), shift);
}

double nlsMass(const Vector& y) {
  const double nrm = y.norm2();
  return nrm * nrm;
}

}  // namespace gphr
