#!/usr/bin/python3
"""Render a radwalk .vtp solution to PNG with VTK (no ParaView needed).

Colours are the radiance B/pi of each patch (the cell field B_rgb, the radiosity's RGB triple, or the
area-weighted point field with --smooth), times --exposure, sRGB-encoded and clamped: the same mapping as
`radwalk pathtrace --image`, so a radiosity solution and a path-traced image of the same scene can be compared
side by side.

With --field NAME of a one-component field (the thermal fields of `radwalk exchange`: q, Q, J, G, T and their _se;
or any scalar) the field is colour-mapped instead, with a colour bar titled with the field and its unit: a
diverging blue-white-red map symmetric about 0 for signed fields (q, Q: heat gained blue, heat lost red), a
sequential one otherwise (T, J, G, errors). --range LO HI fixes the map's range.

Usage (Debian's VTK is an X build: run it under scripts/with_xvfb.sh when there is no display; it ends its X
server whatever happens to the render):
    scripts/with_xvfb.sh /usr/bin/python3 scripts/render_vtp.py cb.vtp cb.png [--smooth]
        [--field B_rgb] [--size 512] [--camera px py pz tx ty tz ux uy uz fov_deg] [--exposure 1]
    scripts/with_xvfb.sh /usr/bin/python3 scripts/render_vtp.py heat.vtp q.png --field q [--range -50 50]
Without --camera the camera is the one camera rule (scripts/camera_rule.py: `radwalk pathtrace`'s fit,
apps/scene_camera.h, the same as the ParaView state's and scripts/paraview_render.py's): the Cornell box's own
camera for its files; inside a closed scene, looking at the objects in it from where it sees most of them (or at
the most lit region of an empty room); otherwise from outside, framing the bounding box from the side that shows
the most fronts. The camera used is printed.
"""
import argparse
import math
import os
import sys

import vtk

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from camera_rule import camera_rule  # noqa: E402  (the one camera rule, shared with paraview_render.py)


def srgb(c):
    c = max(0.0, min(1.0, c))
    return 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055


def colours(array, exposure):
    n = array.GetNumberOfTuples()
    out = vtk.vtkUnsignedCharArray()
    out.SetNumberOfComponents(3)
    out.SetNumberOfTuples(n)
    out.SetName("colour")
    for i in range(n):
        b = array.GetTuple3(i)
        out.SetTuple3(i, *(round(255 * srgb(exposure * v / math.pi)) for v in b))
    return out


# Units of the fields `radwalk exchange` writes (docs/heat-exchange.md, "Outputs").
UNITS = {"q": "W/m^2", "q_se": "W/m^2", "Q": "W", "Q_se": "W", "J": "W/m^2", "J_se": "W/m^2", "G": "W/m^2",
         "T": "K", "T_se": "K", "B": "W/m^2", "emissivity": "1", "sky": "1", "back": "1"}
SIGNED = {"q", "Q"}


def scalar_lookup(name, values, value_range=None):
    """A lookup table for a one-component field: diverging (blue, white, red) and symmetric about 0 for the signed
    heat fields, sequential (dark blue to yellow) otherwise; range from the data unless given."""
    lo, hi = value_range if value_range else values.GetRange()
    diverging = name in SIGNED or (value_range is None and lo < 0 < hi)
    if diverging and not value_range:
        m = max(abs(lo), abs(hi)) or 1.0
        lo, hi = -m, m
    if not hi > lo:
        lo, hi = lo - 0.5, hi + 0.5
    ctf = vtk.vtkColorTransferFunction()
    if diverging:
        ctf.SetColorSpaceToDiverging()
        ctf.AddRGBPoint(lo, 0.230, 0.299, 0.754)
        ctf.AddRGBPoint(0.5 * (lo + hi), 0.865, 0.865, 0.865)
        ctf.AddRGBPoint(hi, 0.706, 0.016, 0.150)
    else:
        ctf.AddRGBPoint(lo, 0.050, 0.030, 0.330)
        ctf.AddRGBPoint(lo + 0.5 * (hi - lo), 0.800, 0.280, 0.400)
        ctf.AddRGBPoint(hi, 0.990, 0.910, 0.150)
    table = vtk.vtkLookupTable()
    table.SetNumberOfTableValues(256)
    table.SetRange(lo, hi)
    for k in range(256):
        r, g, b = ctf.GetColor(lo + (hi - lo) * k / 255.0)
        table.SetTableValue(k, r, g, b, 1.0)
    table.Build()
    return table, diverging


def fit_camera(poly, field=None):
    """The camera for the data: the one camera rule (scripts/camera_rule.py; `field` is not used)."""
    return camera_rule(poly)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("vtp")
    p.add_argument("png")
    p.add_argument("--field", default="B_rgb",
                   help="3-component field shown as colour (default B_rgb, the radiosity's RGB triple), or a "
                        "1-component field colour-mapped with a colour bar (q, Q, J, G, T, ...)")
    p.add_argument("--range", type=float, nargs=2, default=None, help="LO HI of a 1-component field's colour map")
    p.add_argument("--smooth", action="store_true", help="use the point field (Gouraud shading)")
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--exposure", type=float, default=1.0)
    p.add_argument("--camera", type=float, nargs=10, default=None,
                   help="px py pz tx ty tz ux uy uz fov_deg (default: fitted to the data)")
    a = p.parse_args()

    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(a.vtp)
    reader.Update()
    poly = reader.GetOutput()
    data = poly.GetPointData() if a.smooth else poly.GetCellData()
    field = data.GetArray(a.field)
    if field is None and a.field == "B_rgb":  # a file from before B became one component
        field = data.GetArray("B")
    kind = 'point' if a.smooth else 'cell'
    if field is None or field.GetNumberOfComponents() not in (1, 3):
        sys.exit(f"{a.vtp}: no 1- or 3-component {kind} field '{a.field}'")
    if a.range and field.GetNumberOfComponents() != 1:
        sys.exit(f"--range is for a 1-component field; '{a.field}' has 3 components (use --exposure)")
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(poly)
    bar = None
    if field.GetNumberOfComponents() == 3:
        data.SetScalars(colours(field, a.exposure))
        mapper.SetColorModeToDirectScalars()
    else:
        table, diverging = scalar_lookup(a.field, field, a.range)
        data.SetActiveScalars(a.field)
        mapper.SetLookupTable(table)
        mapper.SetUseLookupTableScalarRange(True)
        mapper.SetColorModeToMapScalars()
        bar = vtk.vtkScalarBarActor()
        bar.SetLookupTable(table)
        unit = UNITS.get(a.field, "")
        bar.SetTitle(a.field + (" (" + unit + ")" if unit else ""))
        bar.SetNumberOfLabels(5)
        bar.SetLabelFormat("%.4g")
        bar.SetPosition(0.86, 0.08)
        bar.SetWidth(0.12)
        bar.SetHeight(0.84)
        bar.SetBarRatio(0.35)
        for text in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
            text.SetColor(1, 1, 1)
            text.SetShadow(0)
            text.SetItalic(0)
        print("field %s: %s map over [%g, %g] %s" % (a.field, "diverging" if diverging else "sequential",
                                                    table.GetRange()[0], table.GetRange()[1], unit))
    mapper.SetScalarModeToUsePointData() if a.smooth else mapper.SetScalarModeToUseCellData()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetLighting(False)  # show the radiosity itself, not a shaded surface
    if a.smooth:
        prop.SetInterpolationToGouraud()

    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    if bar is not None:
        renderer.AddActor2D(bar)
    renderer.SetBackground(0, 0, 0)
    cam = renderer.GetActiveCamera()
    c = a.camera if a.camera else camera_rule(poly)
    print("camera: position %g %g %g, look at %g %g %g, up %g %g %g, fov %g degrees" % tuple(c))
    cam.SetPosition(c[0], c[1], c[2])
    cam.SetFocalPoint(c[3], c[4], c[5])
    cam.SetViewUp(c[6], c[7], c[8])
    cam.SetViewAngle(c[9])
    renderer.ResetCameraClippingRange()

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(a.size, a.size)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(a.png)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
