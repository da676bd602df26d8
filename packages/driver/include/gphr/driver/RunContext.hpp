#pragma once
#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>
#include <vector>

#include "gphr/models/Scene.hpp"

namespace gphr {

// What every stage of `gphr run` needs: the validated config, the scene, the test parameter.
struct RunContext {
  std::string outputDir;
  Teuchos::ParameterList config;  // validated
  std::shared_ptr<Scene> scene;
  std::vector<double> mu;  // test parameter
  RCP<const Comm> comm;
  std::string artifactsPath() const { return outputDir + "/artifacts.h5"; }
};

}  // namespace gphr
