#!/usr/bin/env pvpython
"""Render a radwalk result (.vtp, cell field B as RGB) to PNG with ParaView, from a fixed viewpoint.

How to run it (NOT in the radwalk build environment): Debian 12's ParaView Python (python3-paraview) conflicts
with VTK's Python (python3-vtk9, which radwalk's scripts/render_vtp.py uses): the two packages cannot be
installed together. Use a separate machine or container with ParaView, e.g.

    docker run --rm -it -v "$PWD":/w -w /w debian:12 bash
    apt-get update && apt-get install -y paraview xvfb
    xvfb-run -a pvpython scripts/paraview_render.py results/cornell_box.vtp cornell_paraview.png

(or any ParaView 5.x binary release: `pvpython --force-offscreen-rendering scripts/paraview_render.py ...`).
This script has not been run in radwalk's CI or build environment (no ParaView there);
scripts/render_vtp.py (VTK only) is the tested alternative and renders the same view.

What it shows: the cell field B (radiosity, W/m^2) mapped to display colours like render_vtp.py: radiance B/pi,
scaled by --exposure, clamped to [0, 1] and gamma-encoded (1/2.2, ParaView's Calculator has no sRGB curve; within
1 % of sRGB above 0.01), shown directly as RGB (no colour map, no lighting). With
--smooth the point field B (area-weighted averages at the corners) is used instead.

Viewpoint: the Cornell box's camera (position (278, 273, -800), looking at (278, 273, 0), up +y, 39.3 degree
field of view) for scenes in millimetres near that box; otherwise looking along +z at the bounding box from the
front (-z), fitted to the data. --camera px py pz tx ty tz ux uy uz fov overrides it.
"""
import argparse
import math
import sys

from paraview import simple as pv  # noqa: E402  (pvpython only)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("vtp")
    p.add_argument("png")
    p.add_argument("--width", type=int, default=800)
    p.add_argument("--height", type=int, default=800)
    p.add_argument("--exposure", type=float, default=1.0, help="multiplies the radiance B/pi before sRGB")
    p.add_argument("--smooth", action="store_true", help="use the point field B (smooth shading)")
    p.add_argument("--camera", type=float, nargs=10, metavar="V",
                   help="px py pz tx ty tz ux uy uz fov_deg")
    a = p.parse_args()

    reader = pv.XMLPolyDataReader(FileName=[a.vtp])
    reader.UpdatePipeline()
    association = "POINTS" if a.smooth else "CELLS"
    data = reader.PointData if a.smooth else reader.CellData
    if "B" not in data.keys():
        sys.exit(f"{a.vtp}: no {'point' if a.smooth else 'cell'} field B (write it with 'radwalk solve -o')")

    # Display colour per cell (or point): sRGB(exposure * B / pi), as a 3-component array shown without a map.
    calc = pv.Calculator(Input=reader)
    calc.AttributeType = "Point Data" if a.smooth else "Cell Data"
    calc.ResultArrayName = "display_rgb"
    k = a.exposure / math.pi
    # Calculator has no sRGB; a gamma 1/2.2 curve is within 1 % of it above 0.01 and is applied per component.
    calc.Function = (f"iHat*(min(max({k}*B_X,0),1)^(1/2.2)) + jHat*(min(max({k}*B_Y,0),1)^(1/2.2)) + "
                     f"kHat*(min(max({k}*B_Z,0),1)^(1/2.2))")

    view = pv.CreateView("RenderView")
    view.ViewSize = [a.width, a.height]
    view.Background = [0, 0, 0]
    view.OrientationAxesVisibility = 0
    display = pv.Show(calc, view)
    pv.ColorBy(display, (association, "display_rgb"))
    display.MapScalars = 0  # the array is the colour itself
    display.Ambient = 1.0
    display.Diffuse = 0.0

    bounds = reader.GetDataInformation().GetBounds()
    camera = view.GetActiveCamera()
    if a.camera:
        c = a.camera
    elif bounds[1] - bounds[0] > 400 and bounds[1] < 700:  # the Cornell box (mm)
        c = [278, 273, -800, 278, 273, 0, 0, 1, 0, 39.3]
    else:
        cx, cy, cz = ((bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2)
        size = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4])
        c = [cx, cy, bounds[4] - 2.0 * size, cx, cy, cz, 0, 1, 0, 40]
    camera.SetPosition(c[0], c[1], c[2])
    camera.SetFocalPoint(c[3], c[4], c[5])
    camera.SetViewUp(c[6], c[7], c[8])
    camera.SetViewAngle(c[9])
    view.CameraParallelProjection = 0

    pv.Render(view)
    pv.SaveScreenshot(a.png, view, ImageResolution=[a.width, a.height])
    print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
