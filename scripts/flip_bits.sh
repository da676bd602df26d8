#!/usr/bin/env bash
# Bit-flip sweep of a reduced-model file: copies FILE, flips one bit in it, runs
# `gphr query COPY QUERIES`, and counts the exit codes. A run passes when it exits 0 with finite
# results, or exits 2 with one error line; anything else (a crash, a hang past 30 s, another exit
# code, a NaN or "diverged" result written with exit 0, an error of several lines) is printed with
# the byte and bit that caused it, and makes the sweep exit 1. What the suite's
# cli_model_file_fuzz checks on 76 chosen damages, this checks on as many random ones as asked.
#
# usage: scripts/flip_bits.sh GPHR FILE QUERIES.yaml [COUNT [SEED [FROM [TO [STEP]]]]]
#   COUNT random flips (default 200) anywhere in FILE, or, with FROM and TO, one random bit in each
#   byte FROM, FROM + STEP, ... < TO (STEP default 1; e.g. an object header's range, from h5dump
#   or h5py's h5o.get_info(...).addr). SEED (default 1) makes a sweep repeatable.
# e.g. build/packages/driver/gphr build test/support/small_nls_model.yaml --model m.h5 --output art &&
#      printf 'queries:\n  defaults: {T: 0.2}\n  points:\n    a: {eps: 1.0}\n' > q.yaml &&
#      bash scripts/flip_bits.sh build/packages/driver/gphr m.h5 q.yaml 600
# A flip in a byte the query never reads (unused space, the provenance attributes, the basis of a
# model it does not lift) passes with exit 0: the report counts those apart only by their exit code.
set -u
[ $# -ge 3 ] || { sed -n 2,17p "$0"; exit 2; }
gphr=$1 good=$2 queries=$3 count=${4:-200} seed=${5:-1} from=${6:-} to=${7:-} step=${8:-1}
[ -x "$gphr" ] || { echo "flip_bits: '$gphr' is not an executable" >&2; exit 2; }
[ -f "$good" ] || { echo "flip_bits: no file '$good'" >&2; exit 2; }
[ -f "$queries" ] || { echo "flip_bits: no queries file '$queries'" >&2; exit 2; }
[[ "$count" =~ ^[0-9]+$ && "$count" -ge 1 && "$seed" =~ ^[0-9]+$ && "$step" =~ ^[0-9]+$ ]] ||
  { echo "flip_bits: COUNT $count, SEED $seed, STEP $step; allowed: COUNT >= 1, SEED >= 0, STEP >= 1, integers" >&2; exit 2; }
[[ -z "$from" || ( "$from" =~ ^[0-9]+$ && "$to" =~ ^[0-9]+$ ) ]] ||
  { echo "flip_bits: FROM '$from', TO '$to'; allowed: byte offsets (integers >= 0), both given" >&2; exit 2; }
size=$(stat -c %s "$good")
if [ -n "$from" ]; then
  [ -n "$to" ] && [ "$from" -ge 0 ] && [ "$to" -le "$size" ] && [ "$from" -lt "$to" ] && [ "$step" -ge 1 ] ||
    { echo "flip_bits: FROM $from, TO $to, STEP $step; allowed: 0 <= FROM < TO <= $size (the file's bytes), STEP >= 1" >&2; exit 2; }
fi
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
RANDOM=$seed
# the bytes to flip and a bit in each, drawn here in order (a subshell would draw its own numbers)
if [ -n "$from" ]; then
  for ((off = from; off < to; off += step)); do echo "$off $((RANDOM % 8))"; done
else
  for ((i = 0; i < count; i++)); do echo "$(((RANDOM * 32768 + RANDOM) % size)) $((RANDOM % 8))"; done
fi > "$work/flips"
declare -A codes
bad=0 done=0 total=$(wc -l < "$work/flips")
while read -r off bit; do
  cp "$good" "$work/t.h5"
  byte=$(od -An -tu1 -j"$off" -N1 "$work/t.h5" | tr -d ' ')
  printf "$(printf '\\x%02x' $((byte ^ (1 << bit))))" | dd of="$work/t.h5" bs=1 seek="$off" conv=notrunc status=none
  rm -rf "$work/out"
  timeout -k 2 30 "$gphr" query "$work/t.h5" "$queries" --output "$work/out" --threads 1 < /dev/null > /dev/null \
    2> "$work/err"
  rc=$?
  codes[$rc]=$((${codes[$rc]:-0} + 1))
  what=""
  case $rc in
    0) grep -qi 'nan\|diverged' "$work/out/queries.csv" 2> /dev/null && what="exit 0 with a NaN or diverged result" ;;
    2) [ "$(grep -c '^gphr' "$work/err")" -eq 1 ] || what="exit 2 with $(grep -c . "$work/err") lines" ;;
    124 | 137) what="hung (killed after 30 s)" ;;
    *) what="exit code $rc" ;;
  esac
  if [ -n "$what" ]; then
    bad=$((bad + 1))
    echo "byte $off bit $bit: $what: $(head -c 300 "$work/err" | tr '\n' ' ')"
  fi
  done=$((done + 1))
  [ $((done % 50)) -eq 0 ] && echo "[flip_bits] $done of $total flips, $bad failed" >&2
done < "$work/flips"
printf 'flips: %d of %s (%d bytes)\n' "$done" "$good" "$size"
for rc in $(printf '%s\n' "${!codes[@]}" | sort -n); do
  case $rc in 0) label="ran (exit 0)" ;; 2) label="refused (exit 2, one error line)" ;; *) label="exit $rc" ;; esac
  printf '  %-34s %d\n' "$label" "${codes[$rc]}"
done
echo "failed: $bad"
[ "$bad" -eq 0 ]
