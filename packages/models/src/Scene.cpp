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

SceneInstance Scene::instantiate(const RCP<const Comm>& comm, const std::vector<double>& mu,
                                 bool shift) const {
  auto [system, y0] = build(comm, mu);
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

double nlsMass(const Vector& y) {
  const double nrm = y.norm2();
  return nrm * nrm;
}

}  // namespace gphr
