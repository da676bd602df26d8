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
  # 1 ulp below the box: the message shows the value as read (it printed 0.9, the bound itself)
  outside_ulp)     printf '%s\n  parameters:\n    eps: 0.89999999999999991\n' "$base" > "$cfg"
                   expect="parameters.eps' has value 0.8999999999999999; allowed: a number in [0.9, 1.1]" ;;
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
  m_per_k_k)       printf '%s\n  pipeline: {methods: [gp-deim], k: [4, 8], m: [8], mPerK: {k6: [4]}}\n' "$base" > "$cfg"
                   expect="key 'pipeline.mPerK.k6' names k = 6, which is not evaluated; allowed: a k of pipeline.k (4, 8)" ;;
  m_per_k_name)    printf '%s\n  pipeline: {methods: [gp-deim], k: [4], m: [8], mPerK: {four: [4]}}\n' "$base" > "$cfg"
                   expect="key 'pipeline.mPerK.four' is not a reduced size; allowed: k<K> for a K of pipeline.k (4), e.g. k4" ;;
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
  # Bounded parsing (YamlText.hpp): Teuchos' reader is quadratic in one value or flow list (2 MB: > 120 s)
  huge_value)      python3 -c "print('gphr:\n  scene:\n    name: \'' + 'x' * (2 << 20) + '\'')" > "$cfg"
                   expect="config file '$cfg' has 2097180 bytes; allowed: at most 262144" ;;
  huge_list)       python3 -c "print('gphr:\n  scene: {name: nls1d, n: 64}\n  training:\n    values: [' + ', '.join(['1.0'] * 400000) + ']')" > "$cfg"
                   expect="has 2000061 bytes; allowed: at most 262144" ;;
  long_line)       python3 -c "print('gphr:\n  scene:\n    name: \'' + 'x' * 100000 + '\'')" > "$cfg"
                   expect="config file '$cfg': line 3 has 100012 bytes; allowed: at most 16384 (a long list in block style" ;;
  huge_file)       { printf '%s\n' "$base"; python3 -c "print(('# ' + 'c' * 98 + '\n') * 50000, end='')"; } > "$cfg"
                   expect="config file '$cfg' has 5050073 bytes; allowed: at most 262144" ;;
  multiline_quote) printf 'gphr:\n  scene:\n    name: "nls1d\n      and more"\n' > "$cfg"
                   expect="line 3 opens a quoted value it does not close; allowed: a quoted value on one line" ;;
  block_scalar)    printf 'gphr:\n  scene:\n    name: |\n      nls1d\n' > "$cfg"; expect="line 3 starts a block scalar (| or >)" ;;
  utf8_value)      printf '%s\n' "$base" | sed 's/name: nls1d/name: nls1d\xc3\xa9/' > "$cfg"
                   expect="line 3 column 16 holds a non-ASCII character outside a comment; allowed: ASCII" ;;
  # XML held to the YAML rules: Teuchos wraps 4294967360 to 64 and keeps the last of two n's silently
  xml_wrapped_int) cfg=$work/config.xml
                   printf '<ParameterList name="gphr"><ParameterList name="scene"><Parameter name="name" type="string" value="nls1d"/><Parameter name="n" type="int" value="4294967360"/></ParameterList></ParameterList>\n' > "$cfg"
                   expect="key 'scene.n' has value '4294967360'; allowed: a whole number from -2147483648 to 2147483647" ;;
  xml_duplicate)   cfg=$work/config.xml
                   printf '<ParameterList name="gphr"><ParameterList name="scene"><Parameter name="n" type="int" value="64"/><Parameter name="n" type="int" value="32"/></ParameterList></ParameterList>\n' > "$cfg"
                   expect="config.xml': key 'scene.n' is given twice; allowed: each key once per list" ;;
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
