#!/usr/bin/env pvpython
"""Render a radwalk result (.vtp, or one step of a .pvd series) to PNG with ParaView, in true colours.

Run it with ParaView's pvpython under an X server; scripts/pvpython.sh fetches Debian 12's ParaView beside the
system VTK (it never installs it) and runs the unpacked pvpython:

    scripts/with_xvfb.sh scripts/pvpython.sh scripts/paraview_render.py cb.vtp cb.png
    scripts/with_xvfb.sh scripts/pvpython.sh scripts/paraview_render.py series/solve.pvd s.png --step 3

(scripts/with_xvfb.sh gives it an X server of its own and ends that server whatever happens: crash, signal,
timeout; any other pvpython works too). tests/paraview/ runs it in CTest and compares the image with the path tracer's.

Colours: the display array B_srgb that radwalk writes (sRGB of the radiance B/pi, clamped, exposure 1: the
mapping of `radwalk pathtrace --image x.png`) shown with Map Scalars off, no lighting. With --exposure other than
1, or for a file without B_srgb, the same mapping is computed from the RGB triple B_rgb by ParaView's Calculator
(exact sRGB: 12.92 c below 0.0031308, 1.055 c^(1/2.4) - 0.055 above). --smooth uses the point fields (per
smoothing group, see docs/paraview.md) instead of the cell fields. A file without the radiosity (B_rgb) is refused with a
message.

Camera: --camera px py pz tx ty tz ux uy uz fov_deg; by default the one camera rule (scripts/camera_rule.py:
`radwalk pathtrace`'s fit, apps/scene_camera.h; the ParaView state's and render_vtp.py's too): the Cornell box's own
camera when the file's field data name a scene cornell_box*; inside a closed scene, 60 degrees, looking at the
objects in it from where it sees most of them (or at the most lit region of an empty room); otherwise from
outside, 40 degrees, framing the bounding box from the side that shows the most fronts. ParaView resets the camera on the first
render, so the camera is set after it. Background: --background (default black), applied
with UseColorPaletteForBackground = 0 (ParaView ignores Background otherwise).
"""
import argparse
import math
import os
import sys

from paraview import simple as pv  # noqa: E402  (pvpython only)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_rule import camera_rule  # noqa: E402  (the one camera rule, shared with render_vtp.py)


def srgb_expression(array, component, k):
    """Calculator expression: exact sRGB of clamp(k * array_component, 0, 1)."""
    c = f"min(max({k!r}*{array}_{component},0),1)"
    return f"if({c}<=0.0031308,12.92*{c},1.055*{c}^(1/2.4)-0.055)"


def open_data(path, step=None):
    """(reader, time or None) for a .vtp, or for step `step` (index; default the last) of a .pvd."""
    if path.endswith(".pvd"):
        reader = pv.PVDReader(FileName=path)
        times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
        if isinstance(reader.TimestepValues, float):
            times = [reader.TimestepValues]
        index = len(times) - 1 if step is None else step
        if not -len(times) <= index < len(times):
            sys.exit(f"{path}: has {len(times)} steps; --step {step} is out of range")
        t = times[index]
        reader.UpdatePipeline(t)
        return reader, t
    reader = pv.XMLPolyDataReader(FileName=[path])
    reader.UpdatePipeline()
    return reader, None


def default_camera(reader):
    """The one camera rule (scripts/camera_rule.py) for the data the reader gives."""
    from paraview import servermanager
    data = servermanager.Fetch(reader)
    if data.IsA("vtkMultiBlockDataSet"):
        data = data.GetBlock(0)
    return camera_rule(data)


def render(path, png, width=512, height=512, exposure=1.0, smooth=False, camera=None, background=(0, 0, 0),
           step=None):
    """Renders `path` to `png`; returns the camera used (10 numbers)."""
    reader, t = open_data(path, step)
    association = "POINTS" if smooth else "CELLS"
    data = reader.PointData if smooth else reader.CellData
    rgb = "B_rgb" if "B_rgb" in data.keys() else "B"  # B was the RGB triple before it became one component
    if rgb not in data.keys() or data[rgb].GetNumberOfComponents() != 3:
        sys.exit(f"{path}: no {'point' if smooth else 'cell'} field B to render (arrays: {', '.join(data.keys())}); "
                 "B is written by 'radwalk solve -o', 'radwalk pathtrace -o' and --progressive series")
    source, colour = reader, "B_srgb"
    if exposure != 1.0 or "B_srgb" not in data.keys():
        calc = pv.Calculator(Input=reader)
        calc.AttributeType = "Point Data" if smooth else "Cell Data"
        calc.ResultArrayName = "display_srgb"
        k = exposure / math.pi
        # Component variables follow the array's component names (R, G, B in radwalk's files; X, Y, Z in old ones).
        names = [data[rgb].GetComponentName(c) or "XYZ"[c] for c in range(3)]
        if any(n in ("", None) or not n.isidentifier() for n in names):
            names = ["X", "Y", "Z"]
        calc.Function = " + ".join(f"{v}*({srgb_expression(rgb, n, k)})"
                                   for v, n in zip(("iHat", "jHat", "kHat"), names))
        source, colour = calc, "display_srgb"

    view = pv.CreateView("RenderView")
    view.ViewSize = [width, height]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = list(background)
    if t is not None:
        view.ViewTime = t
    display = pv.Show(source, view)
    pv.ColorBy(display, (association, colour))
    display.MapScalars = 0  # the array is the colour itself
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.Specular = 0.0
    display.SetScalarBarVisibility(view, False)
    if smooth:
        display.Interpolation = "Gouraud"

    c = list(camera) if camera else default_camera(reader)
    pv.Render(view)  # the first render resets the camera; set ours after it
    view.CameraPosition = c[0:3]
    view.CameraFocalPoint = c[3:6]
    view.CameraViewUp = c[6:9]
    view.CameraViewAngle = c[9]
    view.CameraParallelProjection = 0
    pv.Render(view)
    pv.SaveScreenshot(png, view, ImageResolution=[width, height], TransparentBackground=0)
    pv.Delete(view)
    return c


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("data", help=".vtp, or .pvd (a series)")
    p.add_argument("png")
    p.add_argument("--width", type=int, default=512)
    p.add_argument("--height", type=int, default=512)
    p.add_argument("--exposure", type=float, default=1.0, help="multiplies the radiance B/pi before sRGB")
    p.add_argument("--smooth", action="store_true", help="use the point fields (smooth shading)")
    p.add_argument("--step", type=int, help=".pvd: step index to render (default: the last; -1 is the last)")
    p.add_argument("--camera", type=float, nargs=10, metavar="V", help="px py pz tx ty tz ux uy uz fov_deg")
    p.add_argument("--background", type=float, nargs=3, default=[0, 0, 0], metavar="C", help="RGB in [0, 1]")
    a = p.parse_args()
    if not os.path.exists(a.data):
        sys.exit(f"{a.data}: no such file")
    render(a.data, a.png, a.width, a.height, a.exposure, a.smooth, a.camera, a.background, a.step)
    print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
