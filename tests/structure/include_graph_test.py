#!/usr/bin/python3
"""The include graph keeps the house's rules: the three modules (dem_module, fluid_module, coupler)
never include one another, only the shared layer (scene/, wire/ and the rockcut/*.pb.h generated from
proto/); inside the fluid module the SP operators (sp/) include nothing of the models
(models/), which build on them; and the coupler's floors include only their own and those below:
bottom run/ and process/, middle schemes/, observers/, cutting_models/ and output/, top
checkpoint/, session/ and cli/.

Every quoted #include of a module's sources is resolved as its compiler does: against the module's
own folder, then the shared layer. One that resolves only in another module, or not at all, fails.

  tests/structure/include_graph_test.py SOURCE_DIR
"""
import os
import re
import sys
import unittest

MODULES = ("dem_module", "fluid_module", "coupler")
SHARED = ("scene", "wire")
SCHEMAS = "proto"
# Folders whose files may not include the named folders of the same module: the fluid's operators
# nothing of its models; the coupler's floors nothing of a floor above (coupler/CMakeLists.txt).
COUPLER_MIDDLE = ("schemes", "observers", "cutting_models", "output")
COUPLER_TOP = ("checkpoint", "session", "cli")
LAYERS = {("fluid_module", "sp"): ("models",)}
for bottom in ("run", "process"):
    LAYERS[("coupler", bottom)] = COUPLER_MIDDLE + COUPLER_TOP
for middle in COUPLER_MIDDLE:
    LAYERS[("coupler", middle)] = COUPLER_TOP
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
ROOT = None


def sources(folder):
    for directory, _, files in os.walk(folder):
        for name in files:
            if name.endswith((".cpp", ".hpp", ".h")):
                yield os.path.join(directory, name)


def includes(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return INCLUDE.findall(f.read())


def where(include, module, root):
    """'own', 'shared', 'generated', another module's name, or None."""
    if os.path.isfile(os.path.join(root, module, include)):
        return "own"
    if include.split("/")[0] in SHARED and os.path.isfile(os.path.join(root, include)):
        return "shared"
    if include.startswith("rockcut/") and include.endswith(".pb.h"):
        proto = os.path.join(root, SCHEMAS, include[:-len(".pb.h")] + ".proto")
        if os.path.isfile(proto):
            return "generated"
    for other in MODULES:
        if other != module and os.path.isfile(os.path.join(root, other, include)):
            return other
    return None


def violations(root):
    found = []
    # The shared layer is held to the same rule: it includes itself and the generated headers only.
    for module in MODULES + SHARED:
        for path in sources(os.path.join(root, module)):
            rel = os.path.relpath(path, os.path.join(root, module))
            folder = rel.split(os.sep)[0]
            for include in includes(path):
                # A file's own folder first, as the compiler does for quoted includes.
                if os.path.isfile(os.path.join(os.path.dirname(path), include)):
                    continue
                place = where(include, module, root)
                if place not in ("own", "shared", "generated"):
                    found.append(f"{module}/{rel}: #include \"{include}\" "
                                 + (f"is {place}'s" if place else "resolves nowhere"))
                elif place == "own" and include.split("/")[0] in LAYERS.get((module, folder), ()):
                    found.append(f"{module}/{rel}: #include \"{include}\": {folder}/ may not "
                                 f"include {include.split('/')[0]}/")
    return found


class IncludeGraph(unittest.TestCase):
    def test_the_tree_keeps_the_rules(self):
        self.assertEqual(violations(ROOT), [])

    def test_a_module_including_another_is_caught(self):
        # The check itself, on a small tree: it must not pass everything.
        import tempfile
        with tempfile.TemporaryDirectory() as tree:
            def write(rel, text=""):
                os.makedirs(os.path.dirname(os.path.join(tree, rel)), exist_ok=True)
                with open(os.path.join(tree, rel), "w") as f:
                    f.write(text)
            write("wire/message.hpp")
            write("dem_module/core/bonds.hpp", '#include "wire/message.hpp"\n')
            write("fluid_module/sp/kernel.hpp")
            write("fluid_module/models/model.hpp", '#include "sp/kernel.hpp"\n')
            write("coupler/run/clock.hpp")
            write("coupler/session/loop.hpp", '#include "run/clock.hpp"\n')
            self.assertEqual(violations(tree), [])
            write("coupler/run/bad.cpp", '#include "core/bonds.hpp"\n')
            write("fluid_module/sp/bad.cpp", '#include "models/model.hpp"\n')
            write("dem_module/core/gone.cpp", '#include "nowhere/x.hpp"\n')
            write("coupler/run/up.cpp", '#include "session/loop.hpp"\n')
            write("wire/down.cpp", '#include "models/model.hpp"\n')
            found = violations(tree)
            self.assertEqual(len(found), 5, found)
            self.assertTrue(any("wire/down.cpp" in v and "is fluid_module's" in v for v in found),
                            found)
            self.assertTrue(any("run/ may not include session/" in v for v in found), found)
            self.assertTrue(any("is dem_module's" in v for v in found), found)
            self.assertTrue(any("sp/ may not include models/" in v for v in found), found)
            self.assertTrue(any("resolves nowhere" in v for v in found), found)


if __name__ == "__main__":
    ROOT = os.path.abspath(sys.argv[1])
    unittest.main(argv=[sys.argv[0]] + sys.argv[2:], verbosity=2)
