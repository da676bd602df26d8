#!/usr/bin/env bash
# Bad input to `gphr run`: non-zero exit, exactly one line on stderr that contains the expected
# words, and nothing left in the output directory.
# usage: bad_input.sh GPHR CASE
set -u
gphr=$1; case=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cfg=$work/config.yaml
base='gphr:
  scene:
    name: nls1d
    n: 64
  time:
    T: 0.1
    dt: 0.01'
case $case in
  negative_n)      printf '%s\n' "$base" | sed 's/n: 64/n: -8/' > "$cfg"; expect="scene.n' has value -8" ;;
  zero_dt)         printf '%s\n' "$base" | sed 's/dt: 0.01/dt: 0/' > "$cfg"; expect="time.dt' has value 0" ;;
  T_less_than_dt)  printf '%s\n' "$base" | sed 's/T: 0.1/T: 0.001/' > "$cfg"; expect="smaller than time.dt" ;;
  outside_box)     printf '%s\n  parameters:\n    eps: 1.5\n' "$base" > "$cfg"; expect="parameters.eps' has value 1.5; allowed: a number in [0.9, 1.1]" ;;
  unknown_key)     printf '%s\n    foo: 3\n' "$base" > "$cfg"; expect="unknown key 'time.foo'; valid keys in 'time': T, dt" ;;
  malformed_yaml)  printf 'gphr:\n  scene: [\n    name: : nls1d\n' > "$cfg"; expect="malformed YAML" ;;
  wrong_type)      printf '%s\n  integrator:\n    scheme: rk4\n' "$base" > "$cfg"; expect="integrator.scheme' has value rk4; allowed: one of 'imr' 'avf'" ;;
  missing_file)    cfg=$work/nope.yaml; expect="cannot read config file" ;;
  eqp_floor)       printf '%s\n  eqp:\n    columnFloor: 1.5\n' "$base" > "$cfg"; expect="eqp.columnFloor' has value 1.5" ;;
  field_models)    printf '%s\n  output:\n    fieldModels: [rom, gp-dim]\n' "$base" > "$cfg"; expect="output.fieldModels' has entry 'gp-dim'; allowed: best or one of" ;;
  field_times)     printf '%s\n  output:\n    fieldTimes: [0.05, 0.2]\n' "$base" > "$cfg"; expect="output.fieldTimes' has entry 0.2; allowed: times in [0, 0.1]" ;;
  too_many_steps)  printf '%s\n' "$base" | sed 's/dt: 0.01/dt: 1.0e-12/' > "$cfg"; expect="time.T / time.dt = 100000000000 steps (T = 0.1, dt = 1e-12); allowed: at most 10000000" ;;
  top_level_key)   printf '%s\npipeline: [rom]\n' "$base" > "$cfg"; expect="has the top-level key 'pipeline' at line 8; allowed: the single key 'gphr'" ;;
  no_key)          printf '# a comment only\n' > "$cfg"; expect="has no top-level key; allowed: a YAML mapping under the key 'gphr'" ;;
  # 40 nested flow mappings: refused before Teuchos' parser, which copies each level again (5000: minutes)
  deep_nesting)    python3 -c "d = 40; print('gphr:\n  scene: ' + '{a: ' * d + '1' + '}' * d)" > "$cfg"
                   expect="nests 42 levels deep at line 2; allowed: at most 32" ;;
  # a scalar where a mapping belongs: malformed, without the hint on one-line flow mappings
  scalar_root)     printf 'gphr: 7\n' > "$cfg"; expect="is malformed YAML" ; unexpected="must fit on one line" ;;
  real_n)          printf '%s\n' "$base" | sed 's/n: 64/n: 64.0/' > "$cfg"
                   expect="key 'scene.n' has value 64, a real number (written with a point or an exponent); allowed: an integer in" ;;
  duplicate_m)     printf '%s\n  pipeline:\n    methods: [gp-deim]\n    m: [8, 4, 8]\n' "$base" > "$cfg"
                   expect="key 'pipeline.m' has entry 8 twice; allowed: each size once" ;;
  # a k above what 2 x 11 training states give (two POD columns each: at most 44), refused before the training
  basis_k)         printf '%s\n  training: {points: [2]}\n  reduction: {k: 45}\n  pipeline: {methods: [rom]}\n' "$base" > "$cfg"
                   expect="k = 45 cannot come from the training: 2 parameter(s) x 11 states give a psd basis of at most k = 44"
                   want_rc=2; after_start=1 ;;
  malformed_xml)   cfg=$work/config.xml; printf '<ParameterList name="gphr"><ParameterList name="time">\n' > "$cfg"
                   expect="is malformed XML: XML parse error at line 2: file ended before closing element 'ParameterList'" ;;
  # the full model's Newton cannot meet 1e-15 in one iteration: a solver failure (exit 3), not a status
  fom_newton)      printf '%s\n  integrator:\n    newtonTolerance: 1.0e-15\n    maxNewtonIterations: 1\n' "$base" > "$cfg"
                   expect="solver failure: Newton did not converge at step 1"; want_rc=3; after_start=1 ;;
  *) echo "unknown case $case"; exit 1 ;;
esac
"$gphr" run "$cfg" --output "$work/out" > "$work/stdout" 2> "$work/stderr"
rc=$?
fail() { echo "FAIL ($case): $*"; echo "--- stderr:"; cat "$work/stderr"; exit 1; }
[ $rc -ne 0 ] || fail "exit code 0"
[ -z "${want_rc:-}" ] || [ $rc -eq "$want_rc" ] || fail "exit code $rc, expected $want_rc"
# a failure after the run started follows its one start line ([gphr] scene ..., output in ...)
[ "$(wc -l < "$work/stderr")" -eq $((1 + ${after_start:-0})) ] || fail "stderr has $(wc -l < "$work/stderr") lines, expected $((1 + ${after_start:-0}))"
grep -qF -- "$expect" "$work/stderr" || fail "stderr lacks: $expect"
[ -z "${unexpected:-}" ] || ! grep -qF -- "$unexpected" "$work/stderr" || fail "stderr says: $unexpected"
if [ -d "$work/out" ] && [ -n "$(ls -A "$work/out")" ]; then fail "output left behind: $(ls "$work/out")"; fi
echo "ok ($case): $(cat "$work/stderr")"
