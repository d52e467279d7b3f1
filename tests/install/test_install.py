#!/usr/bin/python3
"""shellfrac installs, and another project builds against the install with find_package(shellfrac).

* `cmake --install BUILD --prefix P` into a fresh prefix: the programs, the headers (with the generated
  core/version.hpp), the libraries and lib/cmake/shellfrac/shellfrac-config.cmake + version file.
* The install does not point back into the source or build tree (a user may delete both).
* tests/install/consumer, a project of its own, configures with only shellfrac_DIR set, builds, and reads an
  example deck through the installed library; its version is project(VERSION) of the top CMakeLists.txt, and
  it reports what xml/cantilever_plate_oscillation.xml holds: 1 block, 1 material, End Time 0.3.
* The installed `shellfrac --version` prints the same version.

usage: test_install.py PROJECT_DIR BUILD_DIR MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

PROJECT = pathlib.Path(sys.argv[1]).resolve()
BUILD = pathlib.Path(sys.argv[2]).resolve()
MPIEXEC = sys.argv[3:]
del sys.argv[1:]

VERSION = re.search(r"project\(shellfrac VERSION ([0-9.]+)", (PROJECT / "CMakeLists.txt").read_text()).group(1)
DECK = PROJECT / "xml" / "cantilever_plate_oscillation.xml"


def run(cmd, **kw):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    if r.returncode != 0:
        raise AssertionError(f"{' '.join(map(str, cmd))} exited {r.returncode}:\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
    return r


class Install(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = pathlib.Path(tempfile.mkdtemp(prefix="shellfrac_install_"))
        cls.prefix = cls.tmp / "prefix"
        run(["cmake", "--install", BUILD, "--prefix", cls.prefix])

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_files_installed(self):
        p = self.prefix
        for rel in ["bin/shellfrac", "bin/shellfrac_meshtool", "bin/shellfrac_exocompare", "bin/shellfrac_exojoin",
                    "include/shellfrac/core/version.hpp", "include/shellfrac/solver/simulation.hpp",
                    "include/shellfrac/solver/input/deck.hpp", "include/shellfrac/disc/dg_element.hpp",
                    "lib/libshellfrac_solver.a", "lib/cmake/shellfrac/shellfrac-config.cmake",
                    "lib/cmake/shellfrac/shellfrac-config-version.cmake", "lib/cmake/shellfrac/shellfracTargets.cmake"]:
            self.assertTrue((p / rel).is_file(), rel)
        self.assertIn(f'version = "{VERSION}"', (p / "include/shellfrac/core/version.hpp").read_text())

    def test_install_does_not_point_into_source_or_build(self):
        for f in (self.prefix / "lib" / "cmake" / "shellfrac").iterdir():
            text = f.read_text()
            for tree in (PROJECT, BUILD):
                self.assertNotIn(str(tree) + "/", text, f"{f.name} names {tree}")

    def test_consumer_project_builds_and_runs(self):
        src = self.tmp / "consumer"
        shutil.copytree(PROJECT / "tests" / "install" / "consumer", src)
        build = self.tmp / "consumer-build"
        env = dict(os.environ)
        env.pop("CMAKE_PREFIX_PATH", None)
        run(["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
             f"-Dshellfrac_DIR={self.prefix / 'lib' / 'cmake' / 'shellfrac'}"], env=env)
        run(["cmake", "--build", build, "-j2"], env=env)
        r = run(MPIEXEC + ["-n", "1", build / "consumer", DECK])
        self.assertIn(f"shellfrac {VERSION}: 1 block(s), 1 material(s), end time 0.3", r.stdout)

    def test_installed_program_reports_the_version(self):
        r = run(MPIEXEC + ["-n", "1", self.prefix / "bin" / "shellfrac", "--version"])
        self.assertIn(f"shellfrac {VERSION}", r.stdout)


if __name__ == "__main__":
    unittest.main(verbosity=2)
