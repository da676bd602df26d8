#!/usr/bin/env bash
# What the README shows exists and runs: every file it names (examples, docs, bench scripts) is in
# the tree; every `gphr run CONFIG` of its code blocks names a config that cli_examples runs and
# checks; every `gphr build / query / validate` command names the example files cli_model_workflow
# runs; the two set-up commands are .ci/run's and the main job's. A renamed or deleted file, or a
# README command that no test runs, fails here.
# usage: readme_configs.sh GPHR README
set -eu
gphr=$1; readme=$2
root=$(cd "$(dirname "$readme")" && pwd)
fail() { echo "FAIL: $*"; exit 1; }
[ -x "$gphr" ] || fail "no gphr binary at $gphr"
# 1. Every path the README names exists.
paths=$(grep -oE '(^|[ `(\[])(examples|doc|bench|scripts|packages)/[A-Za-z0-9_./{},*-]+' "$readme" |
        sed -E 's/^[ `(\[]//; s/[.,)]*$//' | sort -u)
[ -n "$paths" ] || fail "the README names no file"
for p in $paths; do
  case "$p" in *'{'*|*'*'*) continue ;; esac  # brace or glob patterns: checked below as a layout line
  [ -e "$root/$p" ] || fail "the README names $p, which does not exist"
done
for pkg in core models timeint reduction hyper io driver; do [ -d "$root/packages/$pkg" ] || fail "no packages/$pkg"; done
# 2. gphr run CONFIG: a config that cli_examples runs (examples/*.yaml, each with expectations).
for cfg in $(grep -oE 'gphr run [^ ]+\.yaml' "$readme" | awk '{print $3}' | sort -u); do
  case "$(dirname "$cfg")" in
    examples) grep -q "^    $(basename "$cfg" .yaml))" "$root/test/cli/examples.sh" || fail "cli_examples does not check $cfg" ;;
    examples/paper) grep -q "^    $(basename "$cfg")) sed" "$root/test/cli/paper_examples.sh" \
                      || fail "cli_paper_examples does not run $cfg" ;;
    *) fail "README runs $cfg, which is not in examples/ or examples/paper/" ;;
  esac
done
# 3. The build / query / validate example files are the ones cli_model_workflow runs.
for f in nls_build.yaml nls_queries.yaml nls_validate.yaml; do
  grep -q "examples/model/$f" "$readme" || fail "the README does not show examples/model/$f"
  grep -q "$f" "$root/test/cli/model_workflow.sh" || fail "cli_model_workflow does not run $f"
done
# 4. The two set-up commands.
ci=$(grep -E '^bash scripts/setup.sh' "$root/.ci/run")
grep -qxF "$ci" "$readme" || fail "the README's test command is not .ci/run's ($ci)"
grep -qx 'bash scripts/setup.sh && build/packages/driver/gphr --output gphr-output' "$readme" || fail "main-job command missing"
# 5. Every bench script the README runs exists and says how to use it.
for s in $(grep -oE 'bash bench/[a-z_]+\.sh' "$readme" | awk '{print $2}' | sort -u); do
  grep -q "^# usage:" "$root/$s" || fail "$s has no usage line"
done
echo "ok: $(echo "$paths" | wc -w) paths, the README's commands are run by cli_examples, cli_model_workflow and .ci/run"
