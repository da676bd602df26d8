#!/usr/bin/env bash
# doc/embedding.md compiles and runs as written: its ```cmake block becomes CMakeLists.txt and its
# ```cpp blocks, concatenated in order, query_embedding.cpp; the project is configured and built
# against the *installed* package (LANGUAGES CXX only, as the page shows), and runs on a model
# file written by the installed `gphr build` on 1 and 2 ranks, each with OPENBLAS_NUM_THREADS 1
# and 2. The four outputs must be identical bit for bit (the page's promise), every query ok, and
# the out-of-box query refused with the box named.
# usage: check_embedding_doc.sh BUILD_DIR SOURCE_DIR MPIEXEC
set -euo pipefail
build=$1; src=$2; mpiexec=$3
doc=$src/doc/embedding.md
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
mkdir -p "$work/project"
# The blocks of a kind, in order, without their fences.
awk -v kind=cmake '/^```/ { if (inside) { inside = 0; next } if ($0 == "```" kind) { inside = 1; next } } inside' \
  "$doc" > "$work/project/CMakeLists.txt"
awk '/^```/ { if (inside) { inside = 0; next } if ($0 == "```cpp") { inside = 1; next } } inside' "$doc" \
  > "$work/project/query_embedding.cpp"
[ "$(grep -c '^```cmake$' "$doc")" -eq 1 ] || fail "doc/embedding.md must hold exactly one cmake block"
[ "$(grep -c '^```cpp$' "$doc")" -ge 2 ] || fail "doc/embedding.md holds fewer than two cpp blocks"
grep -q "^project(query_embedding LANGUAGES CXX)$" "$work/project/CMakeLists.txt" \
  || fail "the page's CMake project must declare LANGUAGES CXX only"
cmake --install "$build" --prefix "$work/prefix" > /dev/null
cmake -S "$work/project" -B "$work/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/cfg.log" 2>&1 \
  || { cat "$work/cfg.log"; fail "the page's CMake project does not configure"; }
cmake --build "$work/build" > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "the page's program does not build"; }
cp "$src/test/support/small_nls_model.yaml" "$work/build.yaml"
(cd "$work" && OPENBLAS_NUM_THREADS=1 "$work/prefix/bin/gphr" build build.yaml --model model.h5 --output art > /dev/null)
for np in 1 2; do
  for threads in 1 2; do
    (cd "$work" && OPENBLAS_NUM_THREADS=$threads "$mpiexec" --allow-run-as-root --oversubscribe -np $np \
       "$work/build/query_embedding" model.h5 > "out_${np}_${threads}.txt" 2> "err_${np}_${threads}.txt") \
      || { cat "$work/err_${np}_${threads}.txt" "$work/out_${np}_${threads}.txt"; fail "the program failed on $np rank(s), $threads thread(s)"; }
  done
done
out=$work/out_1_1.txt
cat "$out"
[ "$(grep -c ', ok$' "$out")" -eq 5 ] || fail "the program did not report 5 queries ok"
grep -q "^eps = 0.90000000000000002: .*||y(T)|| = [0-9]" "$out" || fail "no lifted state's norm for the first query"
grep -q "^outside the box: .*allowExtrapolation" "$out" || fail "the out-of-box query was not refused with its remedy"
for f in out_1_2 out_2_1 out_2_2; do
  cmp -s "$out" "$work/$f.txt" || { diff "$out" "$work/$f.txt"; fail "$f differs from 1 rank, 1 thread"; }
done
echo "ok: doc/embedding.md builds against the installed package; 1 and 2 ranks, 1 and 2 OpenBLAS threads: identical"
