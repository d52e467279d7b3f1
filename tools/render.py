#!/usr/bin/python3
"""Renders a shellfrac Exodus result (one file or a per-rank set) with ParaView, without a display.

The deformed mid-surface (the reader adds `displ` to the coordinates) is coloured by an element field:
`damage` (default), `eq_plastic_strain`, any other element or nodal scalar, or the categorical fields
`fragment_id` (the largest piece grey, every other piece its own colour) and `rank` (the partition map).
Pictures are written for the chosen times and views; `--animate` writes an animated GIF over the frames.

usage (Debian 12: tools/install-deps.sh --render installs paraview, python3-paraview, xvfb and python3-pil):
  tools/render.py RESULTS [--field damage] [--time T ...] [--view iso ...]
        [--focus X Y Z --direction DX DY DZ --distance D] [--zoom Z] [--range LO HI] [--size 1280 720]
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

# Runs inside ParaView's Programmable Filter on the merged mesh: a colour index per cell (fragment_id: 0 for the
# piece with the most elements, 1 + a hash of the id for the others; rank: 1 + the rank modulo the palette).
# The filter runs its script in this script's namespace and imports numpy's sum, min, max and abs there: hence
# the function around it and builtins.* below.
COLOUR_INDEX = """
def _shellfrac_colour_index():
    import numpy as np
    from vtk.numpy_interface import dataset_adapter as dsa
    ids = np.asarray(inputs[0].CellData['%(field)s']).astype(np.int64)
    out = np.zeros(len(ids), dtype=np.int32)
    if len(ids):
        if '%(field)s' == 'fragment_id':
            values, counts = np.unique(ids, return_counts=True)
            main_piece = values[np.argmax(counts)]
            out = (1 + (ids * 2654435761) %% %(n)d).astype(np.int32)
            out[ids == main_piece] = 0
        else:
            out = (1 + ids %% %(n)d).astype(np.int32)
    output.CellData.append(dsa.VTKArray(out), 'colour_index')
_shellfrac_colour_index()
"""


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
    p.add_argument("--title", default="", help="text in the upper left corner; the time is appended")
    p.add_argument("--time-unit", default="ms", choices=("s", "ms", "us"), help="unit of the time label")
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


def frame_time_label(t, unit):
    scale = {"s": 1.0, "ms": 1e3, "us": 1e6}[unit]
    return "t = %.4g %s" % (t * scale, unit)


class Scene:
    def __init__(self, args):
        self.args = args
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
            self.source.Script = COLOUR_INDEX % {"field": field, "n": len(PALETTE)}
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
            colours = [GREY] + PALETTE
            lut.InterpretValuesAsCategories = 1
            lut.Annotations = [text for i in range(len(colours)) for text in (str(i), "")]
            lut.IndexedColors = [c for rgb in colours for c in rgb]
            self.display.SetScalarBarVisibility(self.view, False)
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

    def go_to(self, t):
        self.view.ViewTime = t
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
        self.label.Text = (self.args.title + "  " if self.args.title else "") + \
            frame_time_label(t, self.args.time_unit)

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
            position = camera.GetPosition()
            fit = math.sqrt(builtins.sum((p - f) ** 2 for p, f in zip(position, camera.GetFocalPoint())))
            camera.SetPosition([f + fit * d for f, d in zip(focus, direction)])
        if a.zoom != 1.0:
            camera.Dolly(a.zoom)
        self.view.CameraParallelProjection = 0

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
            print("render.py: wrote %s (%s, %s view, %s)" % (name, args.field, v, frame_time_label(t, args.time_unit)))
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
