#!/usr/bin/env bash
# Paths that would destroy or misplace files are refused before any work, with exit 2 and one line
# naming the path and what is allowed: --model at a device, FIFO, symbolic link or directory, at
# the config file or at the artifacts file (the model file is renamed over whatever is there);
# --output or --model given empty or without a value (query's "" would write into /); a
# --target-error that is not 0 < EPS < 1. A config in
# Teuchos XML with its root list named gphr runs like the YAML one.
# usage: bad_paths.sh GPHR
set -u
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
printf 'gphr:\n  scene: {name: nls1d, n: 64}\n  time: {T: 0.1, dt: 0.01}\n' > c.yaml
mknod dev c 1 3 2> /dev/null || mkfifo dev  # a device where the test may make one (root), else a FIFO
mkfifo fifo; ln -s target.h5 link; mkdir dir
# refused CMD...: exit 2, one stderr line containing $expect, and neither the target nor art/ touched.
refused() {
  "$gphr" "$@" > out.txt 2> err.txt
  local rc=$?
  [ $rc -eq 2 ] || fail "$*: exit code $rc, expected 2: $(cat err.txt)"
  [ "$(wc -l < err.txt)" -eq 1 ] || fail "$*: stderr is not one line: $(cat err.txt)"
  grep -qF -- "$expect" err.txt || fail "$*: stderr lacks '$expect': $(cat err.txt)"
  [ ! -e art ] || fail "$*: art/ was created"
  echo "ok: $(cat err.txt)"
}
expect="is not a regular file (a device, FIFO or socket); allowed: a new path or a regular file to replace"
refused build c.yaml --model dev --output art
refused build c.yaml --model fifo --output art
expect="--model 'link' is a symbolic link"; refused build c.yaml --model link --output art
expect="--model 'dir' is a directory"; refused build c.yaml --model dir --output art
# a target error that is not a relative error, or missing: refused before any work
expect="--target-error '2'; allowed: a number 0 < EPS < 1"; refused build c.yaml --model new.h5 --target-error 2 --output art
expect="--target-error '1e-3x'; allowed"; refused build c.yaml --model new.h5 --target-error 1e-3x --output art
expect="'--target-error' needs a number after it"; refused build c.yaml --model new.h5 --output art --target-error
expect="unknown argument '--target-error'"; refused run c.yaml --target-error 1e-3
expect="--model './c.yaml' is the config file"; refused build c.yaml --model ./c.yaml --output art
expect="is the artifacts file of --output"; refused build c.yaml --model art/../art/artifacts.h5 --output art
[ -p fifo ] && [ -L link ] && [ -d dir ] && [ -e dev ] && [ ! -f dev ] || fail "a refused --model target was replaced"
grep -q "^gphr:" c.yaml || fail "the config was overwritten"
expect="'--output' is given an empty path; allowed: a directory path"
refused query m.h5 q.yaml --output ""
refused validate m.h5 t.yaml --output ""
refused run c.yaml --output ""
expect="'--model' is given an empty path; allowed: a file path"; refused build c.yaml --model "" --output art
expect="'--output' needs a path after it"; refused query m.h5 q.yaml --output
# an option twice (the second replaced the first), an option where a path belongs, both verbosities
expect="'--output' is given twice; allowed: each option once"; refused run c.yaml --output a1 --output a2
expect="'--output' is followed by the option '--threads'; allowed: a path"; refused query m.h5 q.yaml --output --threads 2
expect="'--verbose' and '--quiet' are given together; allowed: one of them"; refused run c.yaml --verbose --quiet
[ ! -e a1 ] && [ ! -e a2 ] || fail "a refused run created its output directory"
# gp-adeim alone without the basis in the file: refused before the training, not after it
printf 'gphr:\n  scene: {name: nls1d, n: 64}\n  time: {T: 0.1, dt: 0.01}\n  training: {points: [2]}\n  pipeline: {methods: [gp-adeim], k: [4], m: [8]}\n  build: {withBasis: false}\n' > ad.yaml
expect="gp-adeim, the only method asked for, cannot be stored: its queries need the basis (build.withBasis: true)"
refused build ad.yaml --model ad.h5 --output art
sed 's/methods: \[gp-adeim\]/methods: [gp-deim]/; s/withBasis: false/probes: [128]/' ad.yaml > probe.yaml
expect="probe entry 128 is not a state entry; allowed: 0 to 127"; refused build probe.yaml --model ad.h5 --output art
# a k above what the training's states can give (2 x 11 states, two POD columns each: k <= 44)
sed 's/methods: \[gp-adeim\]/methods: [gp-deim]/; s/k: \[4\]/k: [45]/; /withBasis/d' ad.yaml > bigk.yaml
expect="k = 45 cannot come from the training: 2 parameter(s) x 11 states give a psd basis of at most k = 44 on n = 64 dofs"
refused build bigk.yaml --model ad.h5 --output art
# XML: <ParameterList name="gphr"> is the config's root, as the key gphr is YAML's.
cat > c.xml <<'XML'
<ParameterList name="gphr">
  <ParameterList name="scene"><Parameter name="name" type="string" value="nls1d"/><Parameter name="n" type="int" value="64"/></ParameterList>
  <ParameterList name="time"><Parameter name="T" type="double" value="0.1"/><Parameter name="dt" type="double" value="0.01"/></ParameterList>
</ParameterList>
XML
"$gphr" run c.xml --output xml > /dev/null 2> xml.err || fail "the XML config did not run: $(cat xml.err)"
"$gphr" run c.yaml --output yaml > /dev/null 2> yaml.err || fail "the YAML config did not run: $(cat yaml.err)"
python3 - <<'PY' || fail "the XML and YAML configs ran differently"
import json
a, b = (json.load(open(d + "/summary.json")) for d in ("xml", "yaml"))
assert a["provenance"]["config"] == b["provenance"]["config"], "configs differ"
assert a["runs"][0]["H0"] == b["runs"][0]["H0"] and a["runs"][0]["H_err_max"] == b["runs"][0]["H_err_max"]
print("ok: the XML config runs as the YAML one")
PY
# Outputs never overlap inputs (resolved: '..', links): a query or validate whose --output holds its
# model file or its YAML file, a build or run whose --output holds its config. Before: the input
# was overwritten (results.h5 over the model file), exit 0.
printf 'gphr:\n  scene: {name: nls1d, n: 64}\n  time: {T: 0.1, dt: 0.01}\n  training: {points: [2]}\n  pipeline: {methods: [gp-deim], k: [4], m: [8]}\n  build: {withBasis: true}\n' > m.yaml
"$gphr" build m.yaml --model m.h5 --output mart > /dev/null 2> mbuild.err || fail "model build: $(cat mbuild.err)"
printf 'queries:\n  points:\n    a: {eps: 1.0}\n' > q.yaml
printf 'validate:\n  points:\n    a: {eps: 1.0}\n' > v.yaml
mkdir -p d; cp m.h5 d/results.h5; cp q.yaml d/queries.csv; cp m.h5 d/validation.csv; cp m.yaml d/c.yaml
ln -s d dl
keep=$(cat d/results.h5 d/queries.csv d/validation.csv d/c.yaml | md5sum)
expect="--output 'd' contains the model file 'd/results.h5', which the command reads; allowed: an output apart from its inputs"
refused query d/results.h5 q.yaml --output d
expect="--output 'd' contains the queries file 'd/queries.csv'"; refused query m.h5 d/queries.csv --output d
expect="--output 'd/' contains the model file 'dl/results.h5'"; refused query dl/results.h5 q.yaml --output d/
expect="--output 'd' contains the model file 'd/validation.csv'"; refused validate d/validation.csv v.yaml --output d
expect="--output 'dl/../d' contains the config file 'd/c.yaml'"; refused build d/c.yaml --model m2.h5 --output dl/../d
expect="--output 'd/..' contains the config file 'd/c.yaml'"; refused run d/c.yaml --output d/..
expect="--model 'dl/c.yaml' is the config file 'd/c.yaml'"; refused build d/c.yaml --model dl/c.yaml --output art
[ "$(cat d/results.h5 d/queries.csv d/validation.csv d/c.yaml | md5sum)" = "$keep" ] || fail "an input was changed"
[ ! -e d/queries ] && [ ! -e d/fom ] && [ ! -e m2.h5 ] || fail "a refused command began its output"
# --model where nothing can be written: refused before the training (it failed after the whole offline run)
expect="cannot write --model '/proc/gphr-model.h5'"; refused build m.yaml --model /proc/gphr-model.h5 --output art
# arguments are read before Kokkos starts: its own options are refused, not acted on (help printed, a library loaded)
expect="unknown argument '--kokkos-help'"; refused run c.yaml --kokkos-help
[ ! -s out.txt ] || fail "--kokkos-help printed: $(head -3 out.txt)"
expect="unknown argument '--kokkos-tools-library=/nonexistent/libgphr-tool.so'"
refused run c.yaml --kokkos-tools-library=/nonexistent/libgphr-tool.so
# the YAML file missing before an option: named as such (it said "unknown argument 'D'")
expect="'gphr query' needs MODEL.h5 and a YAML file before its options; found the option '--output' where the YAML file belongs"
refused query m.h5 --output D
# UTF-8 in comments is allowed (it was refused: "Unexpected character code -30"); outside them it is
# refused by name (bad_input utf8_value)
printf 'gphr:  # caf\xc3\xa9\n  scene: {name: nls1d, n: 64}  # \xce\xbb = 1\n  time: {T: 0.1, dt: 0.01}\n' > utf8.yaml
"$gphr" run utf8.yaml --output utf8 > /dev/null 2> utf8.err || fail "a config with UTF-8 in its comments: $(cat utf8.err)"
echo "ok: UTF-8 in comments"
echo "PASS"
