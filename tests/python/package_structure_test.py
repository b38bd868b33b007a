#!/usr/bin/python3
"""The shape of the rockcut package (python/rockcut), read from its source with `ast`: no import
circle between its modules (also through imports inside functions, which only hide a circle until
the function runs), and no module over LIMIT lines unless LONG_MODULES names it with its reason.
Also checks the checks, on small packages written for the purpose. Under a second; runs nothing.

  tests/python/package_structure_test.py --coupler build/bin/coupler --tmp DIR
"""
import ast
import os
import shutil
import unittest

import harness  # tests/python/harness.py: the command line

ARGS = None
PACKAGE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python", "rockcut")
NAME = "rockcut"

LIMIT = 300  # lines of one module
# Modules allowed over LIMIT lines: module name -> the reason a reader sees. Empty: every module is
# within the limit. An entry for a module within the limit fails the test (remove it).
LONG_MODULES = {}


def modules(folder):
    """{module name: path} of the package's modules (__init__ included)."""
    return {f[:-3]: os.path.join(folder, f) for f in sorted(os.listdir(folder)) if f.endswith(".py")}


def imported(tree, names, package=NAME):
    """The package's own modules that a module's syntax tree imports, at module level or inside a
    function: `from . import a`, `from .a import x`, `from rockcut import a`,
    `from rockcut.a import x`, `import rockcut.a`."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level == 1 or (node.level == 0 and node.module == package):
                if node.level == 1 and node.module:
                    found.add(node.module.split(".")[0])
                else:
                    found.update(a.name for a in node.names if a.name in names)
            elif node.level == 0 and node.module and node.module.startswith(package + "."):
                found.add(node.module.split(".")[1])
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith(package + "."):
                    found.add(a.name.split(".")[1])
    return {m for m in found if m in names}


def import_graph(folder, package=NAME):
    """{module: set of the package's modules it imports}; the package itself (__init__), which
    every import of a submodule loads first, is not an edge."""
    found = modules(folder)
    graph = {}
    for name, path in found.items():
        with open(path) as f:
            tree = ast.parse(f.read(), path)
        graph[name] = imported(tree, found, package) - {"__init__"}
    return graph


def circles(graph):
    """The import circles: each strongly connected set of modules (Tarjan) with more than one
    module, or one that imports itself, as a sorted list."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1 or v in graph.get(v, ()):
                found.append(sorted(group))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(found)


def line_counts(folder):
    counts = {}
    for name, path in modules(folder).items():
        with open(path) as f:
            counts[name] = sum(1 for _ in f)
    return counts


def write_package(root, files):
    shutil.rmtree(root, ignore_errors=True)
    os.makedirs(root)
    for name, text in files.items():
        with open(os.path.join(root, name), "w") as f:
            f.write(text)
    return root


class ThePackage(unittest.TestCase):
    def test_no_import_circle(self):
        graph = import_graph(PACKAGE)
        self.assertGreater(len(graph), 10, "the package's modules were not found")
        self.assertTrue(graph["sweep"], "sweep's imports were not found")
        found = circles(graph)
        self.assertEqual(found, [], "import circles: " + "; ".join(" <-> ".join(c) for c in found))

    def test_no_long_module_without_a_reason(self):
        counts = line_counts(PACKAGE)
        long_ = {m: n for m, n in counts.items() if n > LIMIT and m not in LONG_MODULES}
        self.assertEqual(long_, {}, f"modules over {LIMIT} lines: split them by job, or name them "
                                    "in LONG_MODULES with the reason")
        for m, reason in LONG_MODULES.items():
            self.assertIn(m, counts, f"LONG_MODULES names {m}, which is not in the package")
            self.assertGreater(counts[m], LIMIT, f"{m} is within the limit: remove it from "
                                                 "LONG_MODULES")
            self.assertTrue(reason.strip(), f"LONG_MODULES: {m} without a reason")


class TheChecks(unittest.TestCase):
    """The checks on small packages: they find what they are for."""

    def test_circles_are_found_also_through_imports_inside_functions(self):
        root = write_package(os.path.join(ARGS.tmp, "structure", "circular"), {
            "__init__.py": "def __getattr__(name):\n    from . import a\n    return a\n",
            "a.py": "from . import b\n",
            "b.py": "def f():\n    from .c import g\n    return g\n",
            "c.py": "import os\nfrom rockcut import a\n",
            "d.py": "from .b import f\nimport rockcut.e\n",
            "e.py": "from rockcut.e import x\n",
            "f.py": "import json\n",
        })
        graph = import_graph(root)
        self.assertEqual(graph["a"], {"b"})
        self.assertEqual(graph["b"], {"c"})
        self.assertEqual(graph["c"], {"a"})
        self.assertEqual(graph["d"], {"b", "e"})
        self.assertEqual(graph["f"], set())
        self.assertEqual(graph["__init__"], {"a"})
        self.assertEqual(circles(graph), [["a", "b", "c"], ["e"]])

    def test_a_tree_has_no_circle(self):
        self.assertEqual(circles({"a": {"b", "c"}, "b": {"c"}, "c": set()}), [])

    def test_the_previous_circle_of_sweep_status_and_collect_is_found(self):
        # The package before the campaign model: collect imported status and sweep, status
        # imported sweep, and sweep imported collect and status inside functions.
        root = write_package(os.path.join(ARGS.tmp, "structure", "before"), {
            "__init__.py": "",
            "collect.py": "from . import status, sweep\n",
            "status.py": "from .sweep import read_plan\n",
            "sweep.py": "def main(argv):\n    from . import collect as collect_verb, "
                        "status as status_verb\n",
        })
        self.assertEqual(circles(import_graph(root)), [["collect", "status", "sweep"]])

    def test_long_modules_are_counted(self):
        root = write_package(os.path.join(ARGS.tmp, "structure", "long"), {
            "__init__.py": "", "short.py": "x = 1\n" * LIMIT, "long.py": "x = 1\n" * (LIMIT + 1)})
        counts = line_counts(root)
        self.assertEqual(counts["short"], LIMIT)
        self.assertEqual(counts["long"], LIMIT + 1)


if __name__ == "__main__":
    ARGS, rest = harness.arguments()
    harness.run(rest)
