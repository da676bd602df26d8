#!/usr/bin/env python3
"""The package layout holds (doc/design.md, "Packages"): every #include "gphr/<pkg>/..." of a
package's sources, headers and tests names the package itself or one it may use; no two files
include each other, directly or around a ring (a file's .hpp and .cpp count as one module: a
header that declares what a .cpp defines, and that .cpp including a header that includes it back,
is a cycle); and every package directory is in the table.

usage: check_layout.py SOURCE_DIR
"""
import os
import re
import sys

# What each package may use, directly or through the ones it uses (the arrows point one way).
ALLOWED = {
    "core": set(),
    "models": {"core"},
    "timeint": {"core"},
    "reduction": {"core"},
    "io": {"core"},
    "hyper": {"core", "timeint", "reduction", "io"},
    "online": {"core", "models", "timeint", "reduction", "hyper", "io"},
    "offline": {"core", "models", "timeint", "reduction", "hyper", "io", "online"},
    "evaluation": {"core", "models", "timeint", "reduction", "hyper", "io", "online", "offline"},
    "driver": {"core", "models", "timeint", "reduction", "hyper", "io", "online", "offline", "evaluation"},
}
# Tests of a package may also use the packages that build their fixtures (never the application).
TEST_EXTRA = {"reduction": {"timeint", "models"}, "hyper": {"models"}, "online": {"models"},
              "timeint": {"models"}, "io": {"models", "timeint", "reduction", "hyper"}}

INCLUDE = re.compile(r'^\s*#\s*include\s+"gphr/([a-z]+)/([^"]+)"', re.M)


def main(src):
    pkgs = os.path.join(src, "packages")
    errors = []
    present = sorted(d for d in os.listdir(pkgs) if os.path.isdir(os.path.join(pkgs, d)))
    for p in present:
        if p not in ALLOWED:
            errors.append(f"packages/{p}: not in the layout table of test/layout/check_layout.py")
    graph = {}  # module (package/stem of a library .hpp/.cpp) -> modules it includes
    for p in present:
        for root, _, files in os.walk(os.path.join(pkgs, p)):
            for f in files:
                if not f.endswith((".hpp", ".cpp")):
                    continue
                path = os.path.join(root, f)
                rel = os.path.relpath(path, src)
                is_test = os.sep + "test" + os.sep in rel
                may = ALLOWED.get(p, set()) | {p} | (TEST_EXTRA.get(p, set()) if is_test else set())
                text = open(path, encoding="utf-8").read()
                for used, name in INCLUDE.findall(text):
                    if used not in may:
                        errors.append(f"{rel}: includes gphr/{used}/{name}; package '{p}' may use "
                                      f"{', '.join(sorted(may - {p})) or 'nothing of GPHR'}")
                if not is_test:
                    key = f"{p}/{os.path.splitext(f)[0]}"
                    deps = {f"{u}/{os.path.splitext(n)[0]}" for u, n in INCLUDE.findall(text)} - {key}
                    graph.setdefault(key, set()).update(deps)
    # a cycle through the headers (two headers that include each other, or a longer ring)
    state = {}

    def visit(node, stack):
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, [])):
            if state.get(nxt) == 1:
                ring = stack[stack.index(nxt):] + [nxt]
                errors.append("include cycle: " + " -> ".join(ring))
            elif nxt in graph and not state.get(nxt):
                visit(nxt, stack)
        stack.pop()
        state[node] = 2

    for node in sorted(graph):
        if not state.get(node):
            visit(node, [])
    for e in errors:
        print("FAIL:", e)
    print(f"{len(graph)} modules in {len(present)} packages; {len(errors)} layout error(s)")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
