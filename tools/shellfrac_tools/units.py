"""The system of units a run declared (`Units`, docs/input_reference.xml): read from the results' Exodus information
record `units: NAME (...)` and turned into the unit names of the tools' labels. The names are solver/input/units.cpp's."""
from .results_files import ResultsError, rank_files


class Units:
    """Unit names for labels ("" for `none`). SI times scale to ms and us on short runs (`time_scales`)."""

    def __init__(self, name, length="", mass="", time="", energy=""):
        self.name, self.length, self.mass, self.time, self.energy = name, length, mass, time, energy
        self.speed = "%s/%s" % (length, time) if length else ""

    def __bool__(self):
        return self.name != "none"

    def time_scales(self):
        """(factor, name) pairs from the largest: a time t reads t / factor in that unit."""
        if self.name == "SI":
            return ((1.0, "s"), (1e-3, "ms"), (1e-6, "us"))
        if self.name == "mm-kg-ms" or self.name == "mm-g-ms":
            return ((1.0, "ms"), (1e-3, "us"))
        return ((1.0, self.time),)


SYSTEMS = {u.name: u for u in (
    Units("SI", "m", "kg", "s", "J"),
    Units("mm-t-s", "mm", "t", "s", "mJ"),
    Units("mm-kg-ms", "mm", "kg", "ms", "J"),
    Units("mm-g-ms", "mm", "g", "ms", "mJ"),
    Units("in-lbf-s", "in", "lbf s^2/in", "s", "in lbf"),
    Units("none"),
)}


def declared_units(results):
    """The Units of the run that wrote `results` (a file or a per-rank set), SI if its file names none (results of
    a version before the declaration). Raises ResultsError if the results cannot be read."""
    import netCDF4  # here: the tools that only name a system need no netCDF
    path = rank_files(results)[0]
    try:
        with netCDF4.Dataset(path) as ds:
            if "info_records" not in ds.variables:
                return SYSTEMS["SI"]
            for row in ds.variables["info_records"][:].data:
                line = b"".join(c for c in row if c).decode("utf-8", "replace").strip()
                if line.startswith("units: "):
                    name = line[len("units: "):].split(" ")[0]
                    return SYSTEMS.get(name, SYSTEMS["none"])
    except OSError as e:
        raise ResultsError("%s: %s" % (path, e))
    return SYSTEMS["SI"]


def chosen_units(option, results):
    """The units of --units OPTION: 'auto' reads the declaration of the results, else the named system."""
    return declared_units(results) if option == "auto" else SYSTEMS[option]
