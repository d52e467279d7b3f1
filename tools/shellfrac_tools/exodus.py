"""One reader of shellfrac's Exodus II results files (docs/output.md), over netCDF4.

A file holds DG nodes (every element its own copies), element blocks `connect<b>` (b = 1, 2, ...), the element id
map (element global id + 1), nodal variables by scalar name (displ_x, ...), element variables per block, and
global variables (the history columns). A per-rank set is several such files (results_files.rank_files)."""
import numpy as np
from netCDF4 import Dataset


class ExodusFile:
    """One results file, open for reading (use as a context manager, or call close())."""

    def __init__(self, path):
        self.path = path
        self.ds = Dataset(path)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self):
        self.ds.close()

    def names(self, var):
        """The names stored in a netCDF character array (name_nod_var, name_elem_var, name_glo_var, eb_names)."""
        if var not in self.ds.variables:
            return []
        return ["".join(c.decode() for c in row if c).strip() for row in self.ds.variables[var][:].data]

    def times(self):
        """The output times (an empty array before the first step)."""
        return np.asarray(self.ds.variables["time_whole"][:]) if "time_whole" in self.ds.variables else np.zeros(0)

    def coordinates(self):
        """Reference coordinates of the file's nodes, (nodes, 3)."""
        return np.stack([np.asarray(self.ds.variables[c][:], dtype=float) for c in ("coordx", "coordy", "coordz")],
                        axis=1)

    def blocks(self):
        """[(b, connectivity)] of the file's non-empty blocks in file order: b is the 1-based block index,
        connectivity the (elements, nodes per element) array of 0-based node indices."""
        nblk = len(self.ds.dimensions["num_el_blk"]) if "num_el_blk" in self.ds.dimensions else 0
        out = []
        for b in range(1, nblk + 1):
            name = "connect%d" % b
            if name in self.ds.variables and self.ds.variables[name].shape[0] > 0:
                out.append((b, np.asarray(self.ds.variables[name][:]) - 1))
        return out

    def element_ids(self):
        """The 1-based global element ids in file order (blocks one after the other)."""
        if "elem_num_map" in self.ds.variables:
            return np.asarray(self.ds.variables["elem_num_map"][:])
        count = sum(len(c) for _, c in self.blocks())
        return np.arange(1, count + 1)

    def nodal(self, name, step):
        """Nodal scalar `name` (e.g. displ_x) at output `step` (Python index), or None if the file has none."""
        names = self.names("name_nod_var")
        if name not in names or len(self.times()) == 0:
            return None
        return np.asarray(self.ds.variables["vals_nod_var%d" % (names.index(name) + 1)][step, :], dtype=float)

    def displacement(self, step):
        """The displacement (nodes, 3) at output `step`, or None if the file has none."""
        parts = [self.nodal("displ_" + c, step) for c in "xyz"]
        return None if any(p is None for p in parts) else np.stack(parts, axis=1)

    def element(self, name, block, step=None):
        """Element variable `name` on block index `block`: at output `step`, or every output (outputs, elements)
        when step is None; None if the file has no such variable there."""
        names = self.names("name_elem_var")
        var = "vals_elem_var%deb%d" % (names.index(name) + 1, block) if name in names else None
        if var is None or var not in self.ds.variables:
            return None
        values = self.ds.variables[var]
        return np.asarray(values[:] if step is None else values[step, :], dtype=float)

    def global_variable(self, name):
        """Global variable `name` at every output, or None."""
        names = self.names("name_glo_var")
        if name not in names or "vals_glo_var" not in self.ds.variables:
            return None
        return np.asarray(self.ds.variables["vals_glo_var"][:, names.index(name)], dtype=float)
