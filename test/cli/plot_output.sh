#!/usr/bin/env bash
# gphr's pictures: gnuplot runs without a shell, with every path quoted inside its script, so an
# --output directory named with a quote and a `;` neither runs a command nor loses its plots; and
# a picture counts only when it is a whole PNG: a gnuplot that exits 0 but leaves a short file (a
# full disk does) leaves no picture, no script or data file, and a note, while the run succeeds.
# usage: plot_output.sh GPHR SMALL_MODEL_CONFIG
set -u
gphr=$1; modelConfig=$2
export OPENBLAS_NUM_THREADS=1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
command -v gnuplot > /dev/null || { echo "gnuplot is not installed: the setup installs it"; exit 1; }
printf 'gphr:\n  scene: {name: nls1d, n: 64}\n  time: {T: 0.1, dt: 0.01}\n' > c.yaml
printf 'validate:\n  defaults: {T: 0.5, dt: 0.01}\n  grid:\n    eps: [0.9, 1.1, 3]\n' > v.yaml
"$gphr" build "$modelConfig" --model m.h5 --output art > /dev/null 2> build.err || fail "build: $(cat build.err)"
# whole FILE: FILE ends with the PNG IEND chunk
whole() { [ "$(tail -c 12 "$1" | od -An -tx1 | tr -d ' \n')" = 0000000049454e44ae426082 ]; }
# Hostile directory names: each command's pictures are whole PNGs and no command ran.
odd="o';touch PWNED;'"
"$gphr" run c.yaml --output "$odd" > /dev/null 2> run.err || fail "run into $odd: $(cat run.err)"
"$gphr" validate m.h5 v.yaml --output "v$odd" > /dev/null 2> validate.err || fail "validate: $(cat validate.err)"
[ ! -e PWNED ] || fail "a command in --output ran"
for png in "$odd/hamiltonian.png" "$odd/spacetime.png" "v$odd/validation_error.png"; do
  [ -f "$png" ] && whole "$png" || fail "'$png' is not a whole PNG"
done
echo "ok: --output \"$odd\" ran nothing and holds whole pictures"
# A gnuplot that exits 0 and leaves a short PNG: no picture, no leftovers, a note, exit 0.
mkdir fake
cat > fake/gnuplot <<'SH'
#!/bin/sh
out=$(sed -n "s/^set output '\(.*\)'$/\1/p" "$1" | head -1)
[ -n "$out" ] && printf '\211PNG\r\n\032\nshort' > "$out"
exit 0
SH
chmod +x fake/gnuplot
PATH=$PWD/fake:$PATH "$gphr" run c.yaml --output short > /dev/null 2> short.err || fail "run: $(cat short.err)"
PATH=$PWD/fake:$PATH "$gphr" validate m.h5 v.yaml --output vshort > /dev/null 2> vshort.err \
  || fail "validate: $(cat vshort.err)"
[ -f short/summary.json ] && [ -f vshort/validation_summary.json ] || fail "a run did not finish"
left=$(cd short && ls; cd ../vshort && ls) 
echo "$left" | grep -E '\.png|\.gp|\.dat|\.tmp|\.partial' && fail "short pictures or their files were left"
grep -q "no plots: gnuplot failed or the PNG could not be written whole" short.err || fail "run: no note: $(cat short.err)"
grep -q "validation_error.png' not drawn" vshort.err || fail "validate: no note: $(cat vshort.err)"
echo "ok: short PNGs were dropped with a note"
