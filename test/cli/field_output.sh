#!/usr/bin/env bash
# The fields of `gphr run` beside its numbers: fields.png (swe2d) and spacetime.png (nls1d) with
# one panel row per model, and with output.xdmf a fields.xdmf that check_xdmf.py opens as a
# reader would (every dataset it names exists with the stated shape; the difference fields are
# the differences; the grid puts the initial state at its coordinates). With MPIEXEC, the swe2d
# run again on 2 ranks: the same XDMF text, and the same states to 1e-9 of the field's size
# (runs on 1 and 2 ranks agree to round-off, rom_ranks.sh; a wrong rank's block is off by O(1)).
# usage: field_output.sh GPHR [MPIEXEC]
set -eu
gphr=$1; mpiexec=${2:-}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
py=/usr/bin/python3  # Debian's, with h5py (setup.sh)
cat > "$work/swe.yaml" <<'YAML'
gphr:
  scene: {name: swe2d, nx: 12}
  parameters: {beta: 1.6435, gamma: 0.7762}
  time: {T: 0.4, dt: 0.01}
  integrator: {newtonTolerance: 1.0e-12}
  training: {points: [2, 2], snapshotEvery: 2}
  reduction: {k: 6}
  pipeline: {rom: true, methods: [rom, gp-deim], m: [6, 24]}
  hyper: {snapshotEvery: 2}
  output: {saveEvery: 10, xdmf: true}
YAML
run() {  # run CONFIG DIR [mpirun args]
  local cfg=$1 dir=$2; shift 2
  "$@" "$gphr" run "$cfg" --output "$dir" > /dev/null 2> "$dir.err" || { cat "$dir.err"; exit 1; }
}
png_size() { $py -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); assert d[:8]==b'\x89PNG\r\n\x1a\n'; print(*struct.unpack('>II', d[16:24]))" "$1"; }
run "$work/swe.yaml" "$work/swe"
# The ROM and the most accurate GP-DEIM run (m = 24; m = 6 is ~30 times worse), nothing else.
fields=chi_fom,Phi_fom,chi_rom_k6,Phi_rom_k6,chi_rom_k6_minus_fom,chi_gp-deim_k6_m24,Phi_gp-deim_k6_m24_minus_fom
$py "$here/check_xdmf.py" "$work/swe/fields.xdmf" /fom/times --fields "$fields" --initial swe2d:1.6435
grep -q "gp-deim_k6_m6" "$work/swe/fields.xdmf" && { echo "FAIL: the less accurate gp-deim run is shown"; exit 1; }
# fields.png: 3 times (start, middle, end) by 5 rows (fom, then each model and its difference).
if command -v gnuplot > /dev/null; then
  [ "$(png_size "$work/swe/fields.png")" = "990 1500" ] || { echo "FAIL: fields.png is $(png_size "$work/swe/fields.png")"; exit 1; }
fi
if [ -n "$mpiexec" ]; then
  run "$work/swe.yaml" "$work/swe2" "$mpiexec" --allow-run-as-root --oversubscribe -np 2
  cmp "$work/swe/fields.xdmf" "$work/swe2/fields.xdmf" || { echo "FAIL: fields.xdmf differs on 2 ranks"; exit 1; }
  $py "$here/check_xdmf.py" "$work/swe2/fields.xdmf" /fom/times --fields "$fields"
  $py - "$work/swe/artifacts.h5" "$work/swe2/artifacts.h5" <<'PY'
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r") for p in sys.argv[1:])
scale = np.max(np.abs(a["/fom/trajectory"][...]))
for name in ["/fom/trajectory"] + [f"/runs/{g}/{d}" for g in a["/runs"] if "states" in a[f"/runs/{g}"] for d in ("states", "difference")]:
    err = np.max(np.abs(a[name][...] - b[name][...]))
    assert err <= 1e-9 * scale, f"{name}: 1 and 2 ranks differ by {err}"
print("1 and 2 ranks agree")
PY
fi
# nls1d: spacetime.png (x by t: the full model and 2 models above, their differences below).
cat > "$work/nls.yaml" <<'YAML'
gphr:
  scene: {name: nls1d, n: 64}
  time: {T: 1.0, dt: 0.01}
  training: {points: [3]}
  reduction: {k: 6}
  pipeline: {rom: true, methods: [rom, gp-deim], m: [12]}
  hyper: {snapshotEvery: 5}
  output: {saveEvery: 5, xdmf: true}
YAML
run "$work/nls.yaml" "$work/nls"
$py "$here/check_xdmf.py" "$work/nls/fields.xdmf" /fom/times --fields re_u_fom,im_u_gp-deim_k6_m12_minus_fom --initial nls1d
if command -v gnuplot > /dev/null; then
  [ "$(png_size "$work/nls/spacetime.png")" = "1260 720" ] || { echo "FAIL: spacetime.png is $(png_size "$work/nls/spacetime.png")"; exit 1; }
fi
# Without output.xdmf: no fields.xdmf, and artifacts.h5 holds no lifted states.
sed -i 's/xdmf: true/xdmf: false/' "$work/nls.yaml"
run "$work/nls.yaml" "$work/nls"
[ ! -e "$work/nls/fields.xdmf" ] || { echo "FAIL: fields.xdmf without output.xdmf"; exit 1; }
h5dump -H "$work/nls/artifacts.h5" | grep -q '"states"' && { echo "FAIL: states stored without output.xdmf"; exit 1; }
echo ok
