#pragma once
// The queries file of `gphr query` (doc/model-file.md): YAML with one top-level key `queries`,
// sections `defaults` (keys every query inherits), `points` (named queries, each a mapping of
// parameters and keys) and `grid` (per parameter [from, to, count]: the tensor grid of those values,
// named grid-0000, ...). Every key, type and value is checked against the model file before any
// query runs (so no rank fails alone later).
#include <string>
#include <vector>

#include "gphr/driver/ReducedModel.hpp"

namespace gphr {

struct Query {
  std::string name;
  std::vector<double> mu;
  std::string method = "gp-deim";
  int k = 0, m = 0;
  double T = 0.0, dt = 0.0;
  long saveEvery = 10;
  bool probes = true;
  SetupRoute setup = SetupRoute::Interpolated;
  bool extrapolate = false;
  bool states = false;  // also the lifted states y0 + A z at the saved steps (needs the basis in the file)
  // Everything that determines the result, as text (a finished query is reused only if it matches).
  std::string key() const;
};

// Queries (top-level key `queries`) or the test points of `gphr validate` (top-level key
// `validate`: the same sections; each point runs every model of the file, so method, k, m and
// probes are not keys there, and points outside the box are allowed and marked).
enum class QueryFileKind { Queries, Validation };
std::vector<Query> readQueries(const std::string& path, const ReducedModel& model,
                               QueryFileKind kind = QueryFileKind::Queries);

}  // namespace gphr
