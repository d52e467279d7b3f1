#!/usr/bin/python3
"""Renders a shellfrac Exodus result (one file or a per-rank set) with ParaView, without a display.

The deformed mid-surface (the reader adds `displ` to the coordinates) is coloured by an element field:
`damage` (default), `eq_plastic_strain`, any other element or nodal scalar, or the categorical fields
`fragment_id` (the largest piece grey, the next twelve by size each its own colour, listed in a legend with
their elements, mass and speed from `<base>_fragments.csv`; the rest summed up under the title) and `rank` (the
partition map, a legend of the ranks). The title names the run, the field and the time. The camera frames the
model's box as seen from the view (80 % of the frame), not ParaView's bounding sphere. Pictures are written for
the chosen times and views; `--animate` writes an animated GIF over the frames.

usage (Debian 12: tools/install-deps.sh --render installs paraview, python3-paraview, xvfb and python3-pil):
  tools/render.py RESULTS [--field damage] [--time T ...] [--view iso ...]
        [--focus X Y Z --direction DX DY DZ --distance D] [--zoom Z] [--range LO HI] [--size 1280 720]
        [--title TEXT] [--units auto|SI|mm-t-s|mm-kg-ms|mm-g-ms|in-lbf-s|none]
        [--animate OUT.gif --fps 8 --every 1] [-o OUT.png]

RESULTS is `run.exo`, one file of a per-rank set (`run.exo.2.0`) or the set's base name (`run.exo`). Times are
in the file's units; each picks the nearest frame; the default is the last frame. Views: iso (default), top,
bottom, front (from -x), back, left (from +y), right (from -y), or a camera given by --focus, --direction (from
the focus towards the camera) and --distance. With several times or views the output name gets
`_<view>_t<time>` before its extension. The rendering runs in a child pvpython, under `xvfb-run` when there is no
DISPLAY, and is retried when ParaView fails to connect to the X server.
"""
import argparse
import builtins
import math
import os
import shutil
import sys


def run_as_child():
    """Runs this script again in a child pvpython (under xvfb-run when there is no DISPLAY) and retries when
    ParaView's X connection check aborts it: measured with Debian 12's ParaView 5.11 on a loaded machine, about one
    start in three aborts with "bad X server connection" in vtkPVRenderingCapabilitiesInformation, with a
    persistent Xvfb as well as with xvfb-run. Returns the child's exit code."""
    import subprocess
    pvpython = shutil.which("pvpython")
    if not pvpython:
        sys.stderr.write("render.py: no pvpython (Debian: apt-get install paraview python3-paraview)\n")
        return 1
    env = dict(os.environ, SHELLFRAC_RENDER_CHILD="1")
    for attempt in range(6):
        cmd = [pvpython, os.path.abspath(__file__)] + sys.argv[1:]
        if not os.environ.get("DISPLAY"):
            xvfb = shutil.which("xvfb-run")
            if not xvfb:
                sys.stderr.write("render.py: no DISPLAY and no xvfb-run to make one (Debian: apt-get install xvfb)\n")
                return 1
            # a 24-bit screen (ParaView's X rendering fails on xvfb-run's default 8-bit one), a display number
            # of its own
            cmd = [xvfb, "-a", "-n", str(100 + (os.getpid() * 7 + attempt * 131) % 30000), "-s",
                   "-screen 0 1920x1080x24"] + cmd
        r = subprocess.run(cmd, env=env, stderr=subprocess.PIPE, text=True)
        if r.returncode == 0 or "bad X server connection" not in r.stderr:
            sys.stderr.write(r.stderr)
            return r.returncode
    sys.stderr.write(r.stderr)
    sys.stderr.write("render.py: ParaView could not connect to the X server in %d attempts\n" % (attempt + 1))
    return 1


if not os.environ.get("SHELLFRAC_RENDER_CHILD"):
    sys.exit(run_as_child())

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, GetScalarBar,
                             IOSSReader, MergeBlocks, ProgrammableFilter, Render, SaveScreenshot, Show, Text)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # pvpython may not add the script's directory
from shellfrac_tools.cli import fail  # noqa: E402
from shellfrac_tools.results_files import ResultsError, rank_files  # noqa: E402
from shellfrac_tools.tables import TableError, pieces_at  # noqa: E402
from shellfrac_tools.units import SYSTEMS, chosen_units  # noqa: E402

VIEWS = {  # direction from the focal point towards the camera, view-up
    "iso": ((-1.0, -1.0, 0.8), (0.0, 0.0, 1.0)),
    "top": ((0.0, 0.0, 1.0), (1.0, 0.0, 0.0)),
    "bottom": ((0.0, 0.0, -1.0), (1.0, 0.0, 0.0)),
    "front": ((-1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
    "back": ((1.0, 0.0, 0.0), (0.0, 0.0, 1.0)),
    "left": ((0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
    "right": ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
}
CATEGORICAL = ("fragment_id", "rank")
# 12 distinguishable colours (RGB 0..1) for the pieces and the ranks
PALETTE = [(0.12, 0.47, 0.71), (1.00, 0.50, 0.05), (0.17, 0.63, 0.17), (0.84, 0.15, 0.16), (0.58, 0.40, 0.74),
           (0.55, 0.34, 0.29), (0.89, 0.47, 0.76), (0.74, 0.74, 0.13), (0.09, 0.75, 0.81), (0.68, 0.78, 0.91),
           (1.00, 0.73, 0.47), (0.60, 0.87, 0.54)]
GREY = (0.78, 0.78, 0.78)
FILL = 0.8  # the share of the frame the model fills (room for the title and the legend)

# Runs inside ParaView's Programmable Filter on the merged mesh: a colour index per cell. fragment_id: the index
# the legend gives the piece (%(indices)s: 0 for the largest, 1, 2, ... for the next ones by size), and for a piece
# beyond the legend 1 + a hash of its id; without a fragment table, 0 for the piece with the most elements. rank:
# 1 + the rank modulo the palette. The filter runs its script in this script's namespace and imports numpy's sum,
# min, max and abs there: hence the function around it and builtins.* below.
COLOUR_INDEX = """
def _shellfrac_colour_index():
    import numpy as np
    from vtk.numpy_interface import dataset_adapter as dsa
    ids = np.asarray(inputs[0].CellData['%(field)s']).astype(np.int64)
    out = np.zeros(len(ids), dtype=np.int32)
    if len(ids):
        if '%(field)s' == 'fragment_id':
            indices = %(indices)s
            out = (1 + (ids * 2654435761) %% %(n)d).astype(np.int32)
            if not indices:
                values, counts = np.unique(ids, return_counts=True)
                indices = {int(values[np.argmax(counts)]): 0}
            for piece, index in indices.items():
                out[ids == piece] = index
        else:
            out = (1 + ids %% %(n)d).astype(np.int32)
    output.CellData.append(dsa.VTKArray(out), 'colour_index')
_shellfrac_colour_index()
"""


def piece_legend(pieces, n_colours, units):
    """({fragment id: colour index}, [(colour index, legend text)]) for the pieces of a frame, largest first: the
    largest grey (index 0), the next n_colours - 1 each its own colour, the rest summed up in one line (their colours
    repeat: 1 + a hash of the id)."""
    indices, legend = {}, []
    for k, (piece, elements, mass, speed) in enumerate(pieces[:n_colours]):
        indices[piece] = k
        motion = ", %.3g%s at %.3g%s" % (mass, " " + units.mass if units else "", speed,
                                         " " + units.speed if units else "")
        legend.append((k, "piece %d: %d elements%s%s" % (piece, elements, motion, " (largest)" if k == 0 else "")))
    rest = pieces[n_colours:]
    if rest:
        legend.append((-1, "... %d more pieces, %d elements (colours repeat)" % (len(rest), builtins.sum(p[1] for p in rest))))
    return indices, legend


def run_name(results):
    name = os.path.basename(results)
    return name[:name.index(".exo")] if ".exo" in name else name


def result_files(path):
    """The absolute path the reader is given (it finds the other files of a per-rank set itself)."""
    try:
        return os.path.abspath(rank_files(path)[0])  # a complete set: every rank file present
    except ResultsError as e:
        fail(str(e))


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("results")
    p.add_argument("--field", default="damage")
    p.add_argument("--time", type=float, nargs="+", help="output times (nearest frame); default: the last")
    p.add_argument("--view", nargs="+", default=["iso"], choices=sorted(VIEWS) + ["custom"])
    p.add_argument("--focus", type=float, nargs=3, help="focal point (default: the centre of the model)")
    p.add_argument("--direction", type=float, nargs=3, help="from the focus towards the camera (view 'custom')")
    p.add_argument("--up", type=float, nargs=3, default=(0.0, 0.0, 1.0))
    p.add_argument("--distance", type=float, help="camera distance from the focus (default: fit the model)")
    p.add_argument("--zoom", type=float, default=1.0, help="move the camera towards the focus by this factor")
    p.add_argument("--range", type=float, nargs=2, help="colour range (default: damage and plastic strain 0..max)")
    p.add_argument("--size", type=int, nargs=2, default=(1280, 720))
    p.add_argument("--title", help="title in the upper left corner (default: the run's name); the field and the time"
                   " are appended")
    p.add_argument("--units", choices=("auto",) + tuple(SYSTEMS), default="auto",
                   help="units of the labels (default: those the run declared, 'Units' of its deck)")
    p.add_argument("--time-unit", default="ms", choices=("s", "ms", "us"), help="unit of the time label (SI runs)")
    p.add_argument("--animate", help="write an animated GIF over the frames to this file")
    p.add_argument("--fps", type=float, default=8.0)
    p.add_argument("--every", type=int, default=1, help="animate every k-th frame")
    p.add_argument("-o", "--output", default="render.png")
    a = p.parse_args()
    if a.direction and "custom" not in a.view:
        a.view = ["custom"]
    if "custom" in a.view and not a.direction:
        fail("--view custom needs --direction DX DY DZ")
    if a.every < 1 or a.fps <= 0 or a.zoom <= 0:
        fail("--every must be >= 1, --fps and --zoom > 0")
    return a


def frame_time_label(t, unit, units):
    """The time of a frame: in `unit` (s, ms or us) for an SI run, else in the run's own time unit (bare without)."""
    if units.name != "SI":
        return "t = %.4g%s" % (t, " " + units.time if units else "")
    scale = {"s": 1.0, "ms": 1e3, "us": 1e6}[unit]
    return "t = %.4g %s" % (t * scale, unit)


class Scene:
    def __init__(self, args):
        self.args = args
        try:
            self.units = chosen_units(args.units, args.results)
        except ResultsError as e:
            fail(str(e))
        self.view = GetActiveViewOrCreate("RenderView")  # first: the render window before any filter
        self.view.ViewSize = list(args.size)
        self.reader = IOSSReader(FileName=[result_files(args.results)])
        self.reader.UpdatePipelineInformation()
        self.times = list(self.reader.TimestepValues) or [0.0]
        cell_fields = [f.split("/")[-1] for f in self.reader.GetProperty("ElementBlockFieldInfo")[::2]]
        self.merged = MergeBlocks(Input=self.reader)
        field = args.field
        self.categorical = field in CATEGORICAL
        if self.categorical:
            if field not in cell_fields:
                fail("%s has no element field '%s' (fields: %s); add it to Output->Fields"
                     % (args.results, field, ", ".join(cell_fields) or "none"))
            self.source = ProgrammableFilter(Input=self.merged)
            self.source.Script = COLOUR_INDEX % {"field": field, "n": len(PALETTE), "indices": "{}"}
            self.colour_array = ("CELLS", "colour_index")
        else:
            self.source = self.merged
            self.colour_array = ("CELLS" if field in cell_fields else "POINTS", field)
        self.view.Background = [1.0, 1.0, 1.0]
        self.view.OrientationAxesVisibility = 1
        try:
            self.view.UseColorPaletteForBackground = 0
        except AttributeError:
            pass
        self.display = Show(self.source, self.view)
        self.label = Text(Text="")
        label_display = Show(self.label, self.view)
        label_display.Color = [0.0, 0.0, 0.0]
        label_display.FontSize = 14
        label_display.WindowLocation = "Upper Left Corner"
        self.colour()
        Render(self.view)  # paraview.simple resets the camera at a view's first render: have it before aiming

    def colour(self):
        ColorBy(self.display, self.colour_array)
        lut = GetColorTransferFunction(self.colour_array[1])
        if self.categorical:
            lut.InterpretValuesAsCategories = 1
            self.legend([(i, "") for i in range(len(PALETTE) + 1)])
            bar = GetScalarBar(lut, self.view)
            bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
            bar.Title = "pieces" if self.args.field == "fragment_id" else "ranks"
            bar.ComponentTitle = ""
            bar.WindowLocation = "Upper Right Corner"
            bar.ScalarBarLength = 0.3
            bar.LabelFontSize = 13
        else:
            if self.args.field in ("damage", "eq_plastic_strain"):  # intact skin light grey, then yellow to dark red
                lut.RGBPoints = [0.0, 0.86, 0.86, 0.86, 0.02, 1.0, 0.87, 0.35, 0.5, 0.93, 0.42, 0.1, 1.0, 0.55, 0.0,
                                 0.05]
                lut.ColorSpace = "RGB"
            else:
                lut.ApplyPreset("Cool to Warm", True)
            self.display.SetScalarBarVisibility(self.view, True)
            bar = GetScalarBar(lut, self.view)
            bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
            bar.Title = self.args.field
            bar.ComponentTitle = ""
        self.lut = lut

    def legend(self, entries):
        """The categorical colours with their legend: [(colour index, text)], index 0 grey, then the palette; an
        index below 0 a line of text with no colour. Shown when some entry has a text."""
        colours = [GREY] + PALETTE
        shown = [(i, text) for i, text in entries if i >= 0]
        lut = GetColorTransferFunction(self.colour_array[1])
        lut.Annotations = [x for i, text in shown for x in (str(i), text)]
        lut.IndexedColors = [c for i, _ in shown for c in colours[i]]
        self.display.SetScalarBarVisibility(self.view, any(text for _, text in shown))
        self.legend_note = "".join("\n" + text for i, text in entries if i < 0)

    def categories_at(self, t):
        """Colours and legend of the categorical field at frame t: pieces by size from the fragment table, or the
        ranks of the set."""
        if self.args.field == "rank":
            ranks = len(rank_files(self.args.results))
            self.legend([(1 + r % len(PALETTE), "rank %d" % r if ranks <= len(PALETTE) else "ranks = %d mod %d"
                          % (r, len(PALETTE))) for r in range(builtins.min(ranks, len(PALETTE)))])
            return
        try:
            pieces = pieces_at(self.args.results, t)
        except TableError as e:
            fail(str(e))
        indices, entries = piece_legend(pieces, len(PALETTE) + 1, self.units)
        self.source.Script = COLOUR_INDEX % {"field": "fragment_id", "n": len(PALETTE), "indices": repr(indices)}
        self.legend(entries or [(0, "")])

    def go_to(self, t):
        self.view.ViewTime = t
        if self.categorical:
            self.categories_at(t)
        self.source.UpdatePipeline(t)
        if not self.categorical:
            if self.args.range:
                lo, hi = self.args.range
            else:
                info = self.source.GetDataInformation()
                arrays = info.GetCellDataInformation() if self.colour_array[0] == "CELLS" \
                    else info.GetPointDataInformation()
                array = arrays.GetArrayInformation(self.colour_array[1])
                if array is None:
                    fail("%s has no field '%s' at t = %g" % (self.args.results, self.args.field, t))
                lo, hi = array.GetComponentRange(-1 if array.GetNumberOfComponents() > 1 else 0)
                if self.args.field in ("damage", "eq_plastic_strain"):
                    lo, hi = 0.0, builtins.max(hi, 1e-12 if self.args.field == "eq_plastic_strain" else 1.0)
            self.lut.RescaleTransferFunction(lo, builtins.max(hi, lo + 1e-30))
        title = self.args.title if self.args.title is not None else run_name(self.args.results)
        time = frame_time_label(t, self.args.time_unit, self.units)
        self.label.Text = "%s: %s at %s%s" % (title, self.args.field, time,
                                              getattr(self, "legend_note", ""))

    def aim(self, view_name):
        a = self.args
        if view_name == "custom":
            direction, up = a.direction, a.up
        else:
            direction, up = VIEWS[view_name]
        norm = math.sqrt(builtins.sum(c * c for c in direction))
        direction = [c / norm for c in direction]
        camera = self.view.GetActiveCamera()
        self.view.ResetCamera(False)
        focus = list(a.focus) if a.focus else list(camera.GetFocalPoint())
        camera.SetFocalPoint(focus)
        camera.SetPosition([f + d for f, d in zip(focus, direction)])
        camera.SetViewUp(list(up))
        self.view.ResetCamera(False)  # fit the model along the new direction
        camera.SetFocalPoint(focus)
        if a.distance:
            camera.SetPosition([f + a.distance * d for f, d in zip(focus, direction)])
        else:
            fit = self.fitting_distance(focus, direction, up, camera.GetViewAngle())
            camera.SetPosition([f + fit * d for f, d in zip(focus, direction)])
        if a.zoom != 1.0:
            camera.Dolly(a.zoom)
        self.view.CameraParallelProjection = 0

    def fitting_distance(self, focus, direction, up, view_angle):
        """The camera distance at which the model's box, seen from `direction`, fills FILL of the frame's width or
        height (whichever binds): the box corners projected on the view plane, plus their depth towards the camera.
        ParaView's own fit takes the bounding sphere, which leaves an elongated model in half the frame."""
        b = self.source.GetDataInformation().GetBounds()
        corners = [(x, y, z) for x in b[0:2] for y in b[2:4] for z in b[4:6]]
        dot = lambda a, c: builtins.sum(p * q for p, q in zip(a, c))  # noqa: E731
        along = dot(up, direction)
        up = [u - along * d for u, d in zip(up, direction)]
        norm = math.sqrt(dot(up, up)) or 1.0
        up = [u / norm for u in up]
        right = [up[1] * direction[2] - up[2] * direction[1], up[2] * direction[0] - up[0] * direction[2],
                 up[0] * direction[1] - up[1] * direction[0]]
        rel = [[c - f for c, f in zip(corner, focus)] for corner in corners]
        half_width = builtins.max(builtins.abs(dot(r, right)) for r in rel)
        half_height = builtins.max(builtins.abs(dot(r, up)) for r in rel)
        depth = builtins.max(dot(r, direction) for r in rel)
        aspect = self.args.size[0] / float(self.args.size[1])
        tangent = math.tan(math.radians(view_angle) / 2)
        return builtins.max(half_height, half_width / aspect, 1e-30) / (FILL * tangent) + builtins.max(depth, 0.0)

    def save(self, path):
        Render(self.view)
        if not SaveScreenshot(path, self.view, ImageResolution=list(self.args.size)):
            fail("could not write %s" % path)


def nearest(times, t):
    return builtins.min(times, key=lambda s: builtins.abs(s - t))


def output_name(base, view, t, several):
    if not several:
        return base
    stem, ext = os.path.splitext(base)
    return "%s_%s_t%.6g%s" % (stem, view, t, ext or ".png")


def write_gif(frames, path, fps):
    try:
        from PIL import Image
    except ImportError:
        fail("--animate needs Python Imaging (Debian: python3-pil)")
    images = [Image.open(f).convert("P", palette=Image.ADAPTIVE, colors=255) for f in frames]
    tmp = path + ".part"
    images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:], duration=int(1000 / fps), loop=0)
    os.replace(tmp, path)


def main():
    args = parse()
    for path in [args.output] + ([args.animate] if args.animate else []):
        if not os.path.isdir(os.path.dirname(os.path.abspath(path))):
            fail("output folder of %s does not exist" % path)
    scene = Scene(args)
    times = [nearest(scene.times, t) for t in args.time] if args.time else [scene.times[-1]]
    several = len(times) * len(args.view) > 1
    for t in times:
        scene.go_to(t)
        for v in args.view:
            scene.aim(v)
            name = output_name(args.output, v, t, several)
            scene.save(name)
            print("render.py: wrote %s (%s, %s view, %s)"
                  % (name, args.field, v, frame_time_label(t, args.time_unit, scene.units)))
    if args.animate:
        import tempfile
        frames = []
        with tempfile.TemporaryDirectory(dir=os.path.dirname(os.path.abspath(args.animate))) as tmp:
            scene.aim(args.view[0])
            for k, t in enumerate(scene.times[::args.every]):
                scene.go_to(t)
                frame = os.path.join(tmp, "frame%05d.png" % k)
                scene.save(frame)
                frames.append(frame)
            write_gif(frames, args.animate, args.fps)
        print("render.py: wrote %s (%d frames, %g per second)" % (args.animate, len(frames), args.fps))


if __name__ == "__main__":
    main()
