#!/usr/bin/env bash
# A user's cache settings win over the project's defaults: configure GPHR with its own
# CMAKE_CXX_FLAGS_RELEASE and check that the compile commands carry exactly those flags.
# usage: check_user_flags.sh SOURCE_DIR
set -euo pipefail
src=$1
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
flags="-O2 -DGPHR_USER_FLAG_CHECK"
cmake -S "$src" -B "$work/b" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGPHR_ENABLE_TESTS=OFF \
  -DCMAKE_CXX_FLAGS_RELEASE="$flags" > "$work/cfg.log" || { cat "$work/cfg.log"; exit 1; }
grep -q "^CMAKE_CXX_FLAGS_RELEASE:STRING=$flags\$" "$work/b/CMakeCache.txt" \
  || { echo "FAIL: the cache lost the user's CMAKE_CXX_FLAGS_RELEASE:"; grep CMAKE_CXX_FLAGS_RELEASE "$work/b/CMakeCache.txt"; exit 1; }
grep -q -- "-DGPHR_USER_FLAG_CHECK" "$work/b/compile_commands.json" \
  || { echo "FAIL: the compile commands do not carry the user's flags"; exit 1; }
if grep -q -- "-O3" "$work/b/compile_commands.json"; then
  echo "FAIL: -O3 still in the compile commands although the user asked for -O2"; exit 1
fi
echo "user flags kept: $flags"
