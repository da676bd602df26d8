#!/usr/bin/env bash
# summary.json says what produced it: the Newton driver (a NOX run says nox, a default run gphr),
# the linear solver, the gphr version, build type and flags, and the whole validated config with
# its defaults; DIR/config.yaml is the config as run and, run again, gives the same config.
# The version names the commit the binary was built from: in a git checkout, git describe of
# SOURCE_DIR now (a binary built before the last commit, with the version fixed at configure time,
# named the older commit).
# usage: provenance.sh GPHR SOURCE_DIR
set -eu
gphr=$1
described=$(git -C "$2" describe --always --tags 2>/dev/null || true)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
for solver in nox gphr; do
  printf 'gphr:\n  scene: {name: nls1d, n: 64}\n  time: {T: 0.05, dt: 0.01}\n  integrator: {newtonSolver: %s}\n' $solver > $solver.yaml
  "$gphr" run $solver.yaml --output $solver > /dev/null 2> $solver.err || { cat $solver.err; exit 1; }
  "$gphr" run $solver/config.yaml --output $solver-again > /dev/null 2> again.err || { cat again.err; exit 1; }
  python3 - $solver "$described" <<'PY'
import json, sys
solver, described = sys.argv[1], sys.argv[2]
s = json.load(open(solver + "/summary.json"))
p = s["provenance"]
assert p["solvers"]["newton"] == solver, p["solvers"]
assert p["config"]["integrator"]["newtonSolver"] == solver
assert p["solvers"]["linear"] == "GMRES + RILUK", p["solvers"]
assert p["config"]["integrator"]["newtonTolerance"] > 0  # defaults are filled in
assert s["gphr_version"].startswith("0.") and p["build"]["build_type"] and p["build"]["cxx_flags"], p["build"]
again = json.load(open(solver + "-again/summary.json"))["provenance"]["config"]
version = s["gphr_version"]
if described:  # VERSION-DESCRIBE[-dirty]
    assert version.split("-", 1)[1] in (described, described + "-dirty"), (version, described)
assert p["build"]["gphr_version"] == version
assert again == p["config"], "config.yaml did not reproduce the config"
print(solver, "ok:", p["solvers"], p["build"]["gphr_version"])
PY
done
