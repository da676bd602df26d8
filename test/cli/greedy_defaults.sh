#!/usr/bin/env bash
# A file built with --target-error carries, per method, the model a query takes when it leaves k
# or m open: the cheapest that met the target over the candidates (NLS n = 32, k = 3, m = 4 and 6,
# target 0.5: both meet it, m = 4 is cheaper), confirmed by full solves at fresh points. The build
# names it, the file holds it (attribute query_defaults, its errors), a query naming no m runs it;
# the same query on a file built without a target is refused, saying where defaults come from.
# usage: greedy_defaults.sh GPHR
set -u
gphr=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; for f in *.err; do echo "--- $f"; tail -5 "$f"; done; exit 1; }
printf 'gphr:\n  scene: {name: nls1d, n: 32}\n  time: {T: 0.2, dt: 0.01}\n  training: {points: [3]}\n  reduction: {k: 3}\n  pipeline: {methods: [gp-deim], m: [4, 6]}\n  build: {candidates: 6, confirmPoints: 2}\n  output: {progressSeconds: 0.0}\n' > c.yaml
printf 'queries:\n  defaults: {T: 0.2, dt: 0.01}\n  points:\n    a: {eps: 1.0}\n' > q.yaml
"$gphr" build c.yaml --model g.h5 --target-error 0.5 --output art > build.out 2> build.err || fail "greedy build"
grep -q "greedy: query default gp-deim k=3 m=4: estimated max [0-9.e+-]* over the candidates, E_L2 max [0-9.e+-]* at 2 fresh points" build.err \
  || fail "the build does not name its query default"
/usr/bin/python3 - g.h5 <<'PY' || fail "the file's query defaults"
import h5py, math, sys
f = h5py.File(sys.argv[1], "r")
names = f.attrs["query_defaults"]
names = names.decode() if isinstance(names, bytes) else str(names)
est, verified, met = f.attrs["query_default_errors"]
assert names == "gp-deim k=3 m=4", names
assert 0 < est <= 0.5 and met == 1.0 and 0 < verified < 1 and math.isfinite(verified), (est, verified, met)
print("query default", names, "estimated max %.3g, E_L2 max at fresh points %.3g" % (est, verified))
PY
"$gphr" query g.h5 q.yaml --output out > query.out 2> query.err || fail "a query without m on the greedy file"
grep -q "^a,1,gp-deim,3,4," out/queries.csv || fail "the query did not run the default gp-deim k=3 m=4: $(cat out/queries.csv)"
"$gphr" build c.yaml --model plain.h5 --output art > /dev/null 2> plain.err || fail "plain build"
"$gphr" query plain.h5 q.yaml --output out2 > /dev/null 2> plain_query.err && fail "a query without m accepted on a file with no defaults"
grep -q "k and m must be given (the file holds gp-deim k=3 m=4, gp-deim k=3 m=6; a file built with --target-error gives defaults per method)" plain_query.err \
  || fail "the refusal does not say where defaults come from: $(cat plain_query.err)"
echo "ok: the greedy file's query default gp-deim k=3 m=4 ran a query that named no m; the plain file refused it"
