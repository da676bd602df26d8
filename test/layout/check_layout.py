#!/usr/bin/env python3
"""The package layout holds (doc/design.md, "Packages"): every #include "gphr/<pkg>/..." of a
package's sources, headers and tests names the package itself or one it may use; no two files
include each other, directly or around a ring (a file's .hpp and .cpp count as one module: a
header that declares what a .cpp defines, and that .cpp including a header that includes it back,
is a cycle); every package directory is in the table; and no header declares what another module
defines (a function or class of module M is defined in M's .cpp files, so a reader finds it beside
its declaration).

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
# Tests of a package may also use the packages that build their fixtures (never the application):
# the online tests query model files the offline library writes.
TEST_EXTRA = {"reduction": {"timeint", "models"}, "hyper": {"models"}, "online": {"models", "offline"},
              "timeint": {"models"}, "io": {"models", "timeint", "reduction", "hyper"}}

INCLUDE = re.compile(r'^\s*#\s*include\s+"gphr/([a-z]+)/([^"]+)"', re.M)

KEYWORDS = {"return", "if", "for", "while", "switch", "using", "typedef", "class", "struct", "enum", "namespace",
            "template", "static_assert", "friend", "delete", "new", "sizeof", "decltype", "operator"}
# A namespace-scope line (column 0) that names a function: its name, or Class::name, before '('.
FUNCTION = re.compile(r"^(?!\s)(?:[\w:<>,\*& ]+?[\s\*&])?((?:\w+::)*~?\w+)\(")
CLASS = re.compile(r"^(?:class|struct)\s+(?:\w+\s+)?(\w+)\b[^;]*$")


def namespace_scope_lines(text):
    """Column-0 lines outside anonymous namespaces and comments, with whether each ends a declaration."""
    out, anonymous = [], 0
    for line in text.split("\n"):
        if re.match(r"^namespace\s*\{", line):
            anonymous += 1
            continue
        if anonymous and re.match(r"^\}\s*//\s*namespace\s*$", line):
            anonymous -= 1
            continue
        if anonymous or not line or line[0] in " \t#/}*" or line.startswith("//"):
            continue
        out.append(line)
    return out


def declared_and_defined(src, pkgs, present):
    """Errors for a function or class declared in one module's header and defined in another's .cpp."""
    declared, classes = {}, {}  # name -> modules whose header declares it
    defined = []  # (module, rel, name)
    for p in present:
        for root, _, files in os.walk(os.path.join(pkgs, p)):
            if os.sep + "test" in root:
                continue
            for f in files:
                if not f.endswith((".hpp", ".cpp")):
                    continue
                path = os.path.join(root, f)
                module = f"{p}/{os.path.splitext(f)[0]}"
                for line in namespace_scope_lines(open(path, encoding="utf-8").read()):
                    c = CLASS.match(line)
                    if c and f.endswith(".hpp"):
                        classes.setdefault(c.group(1), set()).add(module)
                        continue
                    m = FUNCTION.match(line)
                    if not m or m.group(1).split("::")[0] in KEYWORDS or line.split()[0] in KEYWORDS:
                        continue
                    if f.endswith(".hpp"):
                        if "::" not in m.group(1):
                            declared.setdefault(m.group(1), set()).add(module)
                    elif line.rstrip().endswith(("{", ",", "(")) or ")" in line:
                        defined.append((module, os.path.relpath(path, src), m.group(1)))
    errors = []
    for module, rel, name in defined:
        parts = name.split("::")
        owners = classes.get(parts[0], set()) if len(parts) > 1 else declared.get(name, set())
        if owners and module not in owners:
            errors.append(f"{rel}: defines {name}, which {', '.join(sorted(o + '.hpp' for o in owners))} declares; "
                          f"define it in that module's .cpp (or declare it in {module}.hpp)")
    return errors


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
    errors += declared_and_defined(src, pkgs, present)
    for e in errors:
        print("FAIL:", e)
    print(f"{len(graph)} modules in {len(present)} packages; {len(errors)} layout error(s)")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
