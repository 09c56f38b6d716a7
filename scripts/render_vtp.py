#!/usr/bin/python3
"""Render a radwalk .vtp solution to PNG with VTK (no ParaView needed).

Colours are the radiance B/pi of each patch (the cell field B_rgb, the radiosity's RGB triple, or the
area-weighted point field with --smooth), times --exposure, sRGB-encoded and clamped: the same mapping as
`radwalk pathtrace --image`, so a radiosity solution and a path-traced image of the same scene can be compared
side by side.

Usage (Debian's VTK is an X build: run it under scripts/with_xvfb.sh when there is no display; it ends its X
server whatever happens to the render):
    scripts/with_xvfb.sh /usr/bin/python3 scripts/render_vtp.py cb.vtp cb.png [--smooth]
        [--field B_rgb] [--size 512] [--camera px py pz tx ty tz ux uy uz fov_deg] [--exposure 1]
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


def fit_camera(poly, field=None):
    """The camera for the data: the one camera rule (scripts/camera_rule.py; `field` is not used)."""
    return camera_rule(poly)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("vtp")
    p.add_argument("png")
    p.add_argument("--field", default="B_rgb", help="3-component field (default B_rgb, the radiosity's RGB triple)")
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
