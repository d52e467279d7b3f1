#!/usr/bin/env python3
"""shellfrac's Exodus tools against SEACAS's (the threads path, whose Trilinos has SEACAS; ctest label `threads`).

A 2-rank run of the beam blast at 225 m/s (30 us, shear-off: 400 elements, 16 outputs) is joined twice, by
SEACAS `epu -auto` and by `shellfrac_exojoin`. References: shellfrac_exocompare (exact) and exodiff (its default
tolerances) both find the two joins equal; a copy with one nodal value changed by 1e-3 relative is found different
by both (exit 1 and non-zero); a change of 1e-12 relative is found by shellfrac_exocompare (exact by default) but
not by exodiff, whose default relative tolerance is 1e-6 (docs/output.md).

usage: test_seacas.py PROJECT_DIR SHELLFRAC EXOCOMPARE EXOJOIN SEACAS_BIN MPIEXEC [MPIEXEC_PREFLAGS...]
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

from shellfrac_tools.launch import ENV

PROJECT, SHELLFRAC, EXOCOMPARE, EXOJOIN, SEACAS_BIN, MPIEXEC = sys.argv[1:7]
PREFLAGS = sys.argv[7:]
PYTHON = "/usr/bin/python3"  # has netCDF4


def run(args, cwd, check_rc=None):
    r = subprocess.run(args, cwd=cwd, env=dict(ENV, OMP_NUM_THREADS="1"), capture_output=True, text=True, timeout=600)
    if check_rc is not None:
        assert r.returncode == check_rc, "%s: exit %d\n%s%s" % (args, r.returncode, r.stdout, r.stderr)
    return r


def perturbed_copy(src, dst, factor):
    """dst = src with the largest nodal value of the first nodal variable at the last step times factor."""
    script = ("import netCDF4, shutil, sys\nshutil.copy(sys.argv[1], sys.argv[2])\n"
              "d = netCDF4.Dataset(sys.argv[2], 'r+')\n"
              "v = d.variables['vals_nod_var1']; x = v[-1, :]; i = int(abs(x).argmax()); x[i] *= float(sys.argv[3])\n"
              "v[-1, :] = x\nd.close()\n")
    subprocess.run([PYTHON, "-c", script, src, dst, repr(factor)], check=True)


class SeacasCrossCheck(unittest.TestCase):
    def test_joins_and_comparisons_agree(self):
        with tempfile.TemporaryDirectory() as tmp:
            shutil.copytree(os.path.join(PROJECT, "xml", "meshes"), os.path.join(tmp, "meshes"))
            text = open(os.path.join(PROJECT, "xml", "beam_blast_225.xml")).read()
            text, n = re.subn(r'(<Parameter name="End Time" type="double" value=")[^"]*"', r'\g<1>3e-5"', text)
            self.assertEqual(n, 1)
            with open(os.path.join(tmp, "beam_blast_225.xml"), "w") as f:
                f.write(text)
            run([MPIEXEC, "-np", "2"] + PREFLAGS + [SHELLFRAC, "--quiet", "beam_blast_225.xml"], tmp, 0)
            run([os.path.join(SEACAS_BIN, "epu"), "-auto", "beam_blast_225.exo.2.0"], tmp, 0)  # -> beam_blast_225.exo
            run([EXOJOIN, "beam_blast_225.exo", "joined.exo"], tmp, 0)
            exodiff = os.path.join(SEACAS_BIN, "exodiff")
            run([EXOCOMPARE, "beam_blast_225.exo", "joined.exo"], tmp, 0)
            self.assertEqual(run([exodiff, "-quiet", "beam_blast_225.exo", "joined.exo"], tmp).returncode, 0)
            perturbed_copy(os.path.join(tmp, "joined.exo"), os.path.join(tmp, "big.exo"), 1.001)
            run([EXOCOMPARE, "joined.exo", "big.exo"], tmp, 1)
            self.assertNotEqual(run([exodiff, "-quiet", "joined.exo", "big.exo"], tmp).returncode, 0)
            perturbed_copy(os.path.join(tmp, "joined.exo"), os.path.join(tmp, "tiny.exo"), 1 + 1e-12)
            run([EXOCOMPARE, "joined.exo", "tiny.exo"], tmp, 1)
            self.assertEqual(run([exodiff, "-quiet", "joined.exo", "tiny.exo"], tmp).returncode, 0)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
