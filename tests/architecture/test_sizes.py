#!/usr/bin/python3
"""The sizes of docs/architecture.md hold in packages/ (a file at most 600 lines, a function at most 80, or a
one-line `// size:` reason), and the check can fail.

* The tree: tools/check_sizes.py finds no file or function over its limit without a reason.
* The check itself, on a small tree made here: a long file, a long free function, a long member function with a
  constructor initialiser list and a long lambda-holding function are reported with exit 1; the same with a
  `// size:` reason, a long class body, a long brace initialiser and a long comment are not.

usage: test_sizes.py PROJECT_DIR
"""
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest

PROJECT = pathlib.Path(sys.argv.pop(1) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
CHECK = PROJECT / "tools" / "check_sizes.py"


def check(root):
    return subprocess.run([sys.executable, str(CHECK), str(root)], capture_output=True, text=True)


def body(lines):
    return "".join(f"  x += {i};\n" for i in range(lines))


class TheTree(unittest.TestCase):
    def test_no_file_or_function_over_its_limit(self):
        r = check(PROJECT)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)


class TheCheck(unittest.TestCase):
    def setUp(self):
        self.root = pathlib.Path(tempfile.mkdtemp(prefix="shellfrac_sizes_"))
        self.write("core/short.cpp", "namespace a {\nint f(int x) {\n" + body(10) + "  return x;\n}\n}  // namespace a\n")

    def tearDown(self):
        shutil.rmtree(self.root, ignore_errors=True)

    def write(self, rel, text):
        path = self.root / "packages" / rel.split("/")[0] / "src" / "shellfrac" / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)

    def test_short_tree_passes(self):
        r = check(self.root)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)

    def test_long_free_function_fails(self):
        # 3 signature lines (the template's included) + 79 body lines + the closing brace: 83 lines.
        self.write("core/long.cpp", "namespace a {\ntemplate <class T>\nint g(int x,\n      int y) {\n" + body(78) +
                   "  return x;\n}\n}  // namespace a\n")
        r = check(self.root)
        self.assertEqual(r.returncode, 1)
        self.assertIn("packages/core/src/shellfrac/core/long.cpp:2: function g is 83 lines (limit 80)", r.stdout)

    def test_function_of_80_lines_passes(self):
        self.write("core/edge.cpp", "int g(int x) {\n" + body(77) + "  return x;\n}\n")
        r = check(self.root)
        self.assertEqual(r.returncode, 0, r.stdout)

    def test_long_constructor_and_lambda_fail(self):
        self.write("core/ctor.cpp", "struct S { S(int); int a_, b_; };\nS::S(int x)\n    : a_(x), b_{x} {\n"
                   "  auto f = [&](int y) {\n" + body(80) + "  };\n  f(1);\n}\n")
        r = check(self.root)
        self.assertEqual(r.returncode, 1)
        self.assertIn("ctor.cpp:2: function S::S is 86 lines", r.stdout)

    def test_long_file_fails(self):
        self.write("core/file.cpp", "".join(f"int v{i} = {i};\n" for i in range(601)))
        r = check(self.root)
        self.assertEqual(r.returncode, 1)
        self.assertIn("file.cpp: 601 lines (limit 600)", r.stdout)

    def test_reasons_classes_initialisers_and_comments_pass(self):
        self.write("core/reason.cpp", "// size: the parser's states read best in one switch\n" +
                   "".join(f"int v{i} = {i};\n" for i in range(601)) +
                   "// size: one table of cases, each a line\nint h(int x) {\n" + body(90) + "  return x;\n}\n")
        self.write("core/shapes.hpp", "struct Big {\n" + "".join(f"  int m{i} = {i};\n" for i in range(90)) +
                   "  int get() const { return m0; }\n};\nconst int table[] = {\n" +
                   "".join(f"  {i},\n" for i in range(90)) + "};\n/* a comment { with braces\n" +
                   "".join("  {\n" for _ in range(90)) + "*/\n")
        r = check(self.root)
        self.assertEqual(r.returncode, 0, r.stdout)


if __name__ == "__main__":
    unittest.main(verbosity=2)
