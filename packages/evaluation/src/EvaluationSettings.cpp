#include "gphr/evaluation/EvaluationSettings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>


namespace gphr {

double maxDeviation(const std::vector<double>& H, double H0) {
  double d = 0.0;
  for (double h : H) d = std::max(d, std::abs(h - H0));
  return d;
}

double driftBound(const SimulationSettings& time, int degree, const RunStats& stats) {
  const Teuchos::ParameterList integrator = validatedIntegrator(time.integrator);  // its defaults, as the integrators read them
  return quadratureIsExact(integrator.get<std::string>("scheme"), integrator.get<int>("quadraturePoints"), degree)
             ? stats.driftBound
             : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace gphr
