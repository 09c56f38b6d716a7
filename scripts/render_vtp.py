#!/usr/bin/python3
"""Render a radwalk .vtp solution to PNG with VTK (no ParaView needed).

Colours are the radiance B/pi of each patch (cell field B, or the area-weighted point field with --smooth),
times --exposure, sRGB-encoded and clamped: the same mapping as `radwalk pathtrace --image`, so a radiosity
solution and a path-traced image of the same scene can be compared side by side.

Usage (Debian's VTK is an X build: run it under xvfb-run when there is no display):
    xvfb-run -a -s "-screen 0 1024x1024x24" /usr/bin/python3 scripts/render_vtp.py cb.vtp cb.png [--smooth]
        [--field B] [--size 512] [--camera px py pz tx ty tz ux uy uz fov_deg] [--exposure 1]
The default camera is the Cornell box's (position 278 273 -800, looking along +z, 39.3 degree field of view).
"""
import argparse
import math
import sys

import vtk
from vtk.util import numpy_support


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


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("vtp")
    p.add_argument("png")
    p.add_argument("--field", default="B")
    p.add_argument("--smooth", action="store_true", help="use the point field (Gouraud shading)")
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--exposure", type=float, default=1.0)
    p.add_argument("--camera", type=float, nargs=10,
                   default=[278, 273, -800, 278, 273, 0, 0, 1, 0, 2 * math.degrees(math.atan(0.0125 / 0.035))])
    a = p.parse_args()

    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(a.vtp)
    reader.Update()
    poly = reader.GetOutput()
    data = poly.GetPointData() if a.smooth else poly.GetCellData()
    field = data.GetArray(a.field)
    if field is None or field.GetNumberOfComponents() != 3:
        sys.exit(f"{a.vtp}: no 3-component {'point' if a.smooth else 'cell'} field '{a.field}'")
    data.SetScalars(colours(field, a.exposure))

    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(poly)
    mapper.SetColorModeToDirectScalars()
    mapper.SetScalarModeToUsePointData() if a.smooth else mapper.SetScalarModeToUseCellData()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetLighting(False)  # show the radiosity itself, not a shaded surface
    if a.smooth:
        prop.SetInterpolationToGouraud()

    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0, 0, 0)
    cam = renderer.GetActiveCamera()
    c = a.camera
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
