"""The ParaView test: every kind of radwalk output opened in a real ParaView (pvpython), checked, rendered.

Usage (run_paraview_test.sh does this, under xvfb-run): pvpython check_outputs.py WORK SOURCE_DIR
WORK holds the outputs run_paraview_test.sh made with radwalk. Checks, for each file: the arrays, their types,
components and component names, their ranges, the active scalars (what ParaView colours by on Apply: the
one-component B, the channel mean of B_rgb, with its unit), the field data; that ParaView's Calculator evaluates
the array names; the ParaView state files (the figure in one step: the point field B in Viridis over the range of
the non-emitting patches, a colour bar titled with the unit, smooth shading, and the camera of the one camera rule,
pathtrace's fit, which scripts/camera_rule.py computes for paraview_render.py: Cornell box, a closed cube, open
parallel squares); and
renders B_srgb from the Cornell box's camera with scripts/paraview_render.py, comparing the image with the path
tracer's PNG of the same view region by region. Writes WORK/screenshots/*.png. Exit 0 when every check passed, 1
otherwise.

Image tolerance (documented in docs/paraview.md): the radiosity solution is constant per patch and its form factors are
Monte Carlo estimates, the path tracer's image is noisy and box-filtered, so pixels differ; region means do not.
For each of five regions (left wall, right wall, back wall, ceiling, floor) the mean sRGB colour of the ParaView
render must be within 8/255 per channel of the path tracer's (measured: within 2/255), the left wall must be red
and the right wall green in both, and the light (pixels saturated in all channels) must lie where the path
tracer's is: centroids within 1.5 pixels, every ParaView light pixel within 1 pixel of a path-traced one.
"""
import importlib.util
import math
import os
import sys

import numpy as np
from paraview import servermanager
from paraview import simple as pv
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import VTK_DOUBLE, VTK_ID_TYPE, VTK_LONG, VTK_LONG_LONG, VTK_UNSIGNED_CHAR
from vtkmodules.vtkIOImage import vtkPNGReader

WORK, SOURCE = sys.argv[1], sys.argv[2]
SHOTS = os.path.join(WORK, "screenshots")
os.makedirs(SHOTS, exist_ok=True)
passed, failed = [0], []


def check(condition, what):
    if condition:
        passed[0] += 1
    else:
        failed.append(what)
        print(f"FAIL: {what}", flush=True)
    return condition


def path(name):
    return os.path.join(WORK, name)


def load_render_script(name="paraview_render"):
    spec = importlib.util.spec_from_file_location(name, os.path.join(SOURCE, "scripts", name + ".py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def open_vtp(name):
    reader = pv.XMLPolyDataReader(FileName=[path(name)])
    reader.UpdatePipeline()
    return reader, servermanager.Fetch(reader)


def srgb8(linear):
    c = np.clip(np.nan_to_num(linear, nan=0.0), 0, 1)
    s = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return np.rint(255 * s).astype(int)


def field_value(data, name):
    a = data.GetFieldData().GetAbstractArray(name)
    if a is None:
        return None
    v = a.GetVariantValue(0)
    return v.ToString() if a.IsA("vtkStringArray") else v.ToDouble()


def check_array(data, where, name, kind, components, lo=None, hi=None):
    """kind: 'int' (64-bit integer), 'real' (double) or 'uchar'; lo/hi bound the values (NaN left out)."""
    attrs = data.GetCellData() if where == "cell" else data.GetPointData()
    a = attrs.GetArray(name)
    if not check(a is not None, f"{where} array {name} present"):
        return None
    types = {"int": (VTK_LONG_LONG, VTK_LONG, VTK_ID_TYPE), "real": (VTK_DOUBLE,), "uchar": (VTK_UNSIGNED_CHAR,)}
    check(a.GetDataType() in types[kind] and a.GetDataTypeSize() == (1 if kind == "uchar" else 8),
          f"{where} array {name} is {kind} (got {a.GetDataTypeAsString()})")
    if not check(a.GetNumberOfComponents() == components, f"{where} array {name} has {components} components "
                                                          f"(got {a.GetNumberOfComponents()})"):
        return None
    if components == 3 and kind != "int" and name != "normal":
        names = [a.GetComponentName(c) for c in range(3)]
        check(names == ["R", "G", "B"], f"{where} array {name} components are R, G, B (got {names})")
    values = vtk_to_numpy(a).astype(float)
    finite = values[np.isfinite(values)]
    if lo is not None:
        check(finite.size == 0 or finite.min() >= lo, f"{where} array {name} >= {lo} (min {finite.min()})")
    if hi is not None:
        check(finite.size == 0 or finite.max() <= hi, f"{where} array {name} <= {hi} (max {finite.max()})")
    return values.reshape(a.GetNumberOfTuples(), components)


def check_no_point_array(data, name):
    check(data.GetPointData().GetArray(name) is None, f"no point array for {name}")


def check_names_usable(data, label):
    for attrs in (data.GetCellData(), data.GetPointData(), data.GetFieldData()):
        for k in range(attrs.GetNumberOfArrays()):
            name = attrs.GetArrayName(k)
            check(name.isidentifier() and name != "var", f"{label}: array name {name!r} usable in Calculator/Python")


def check_ready(reader, data, label, patches=None):
    """Common to every file with the radiosity: the active scalars B, one component, the channel mean of the RGB
    triple B_rgb (W per square length unit: for grey data the radiosity itself, not the magnitude sqrt(3) B);
    B_srgb = sRGB(B_rgb / pi); ParaView colours by B on Show, over B's range. Returns B_rgb (N x 3)."""
    n = data.GetNumberOfCells()
    if patches is not None:
        check(n == patches, f"{label}: {patches} cells (got {n})")
    scalars = data.GetCellData().GetScalars()
    check(scalars is not None and scalars.GetName() == "B", f"{label}: active cell scalars are B")
    mean = check_array(data, "cell", "B", "real", 1, lo=0)
    if mean is not None:
        from vtkmodules.vtkCommonCore import vtkDataArray
        info = data.GetCellData().GetArray("B").GetInformation()
        units = info.Get(vtkDataArray.UNITS_LABEL()) if info.Has(vtkDataArray.UNITS_LABEL()) else None
        check(units == "W/unit^2", f"{label}: B's UNITS_LABEL is W/unit^2 (got {units!r})")
    B = check_array(data, "cell", "B_rgb", "real", 3, lo=0)
    if mean is not None and B is not None:
        check(np.allclose(mean[:, 0], B.mean(axis=1), rtol=1e-15, atol=0), f"{label}: B == mean of B_rgb's channels")
    srgb = check_array(data, "cell", "B_srgb", "uchar", 3, lo=0, hi=255)
    if B is not None and srgb is not None:
        check(np.array_equal(srgb, srgb8(B / math.pi)), f"{label}: B_srgb == sRGB(B_rgb / pi) exactly")
    check_array(data, "point", "B", "real", 1, lo=0)
    Bp = check_array(data, "point", "B_rgb", "real", 3, lo=0)
    sp = check_array(data, "point", "B_srgb", "uchar", 3)
    if Bp is not None and sp is not None:
        check(np.array_equal(sp, srgb8(Bp / math.pi)), f"{label}: point B_srgb == sRGB(point B_rgb / pi)")
    patch = check_array(data, "cell", "patch", "int", 1, lo=0, hi=n - 1)
    if patch is not None:
        check(np.array_equal(patch[:, 0], np.arange(n)), f"{label}: patch = cell index")
    check_array(data, "cell", "face", "int", 1, lo=0)
    check_array(data, "cell", "area", "real", 1, lo=1e-12)
    check_array(data, "cell", "normal", "real", 3, lo=-1, hi=1)
    check_array(data, "cell", "rho", "real", 3, lo=0, hi=1)
    check_array(data, "cell", "E", "real", 3, lo=0)
    for name in ("patch", "face", "area", "normal"):
        check_no_point_array(data, name)
    check_names_usable(data, label)
    # What ParaView does on Apply: colour by the active scalars.
    view = pv.CreateView("RenderView")
    display = pv.Show(reader, view)
    check(list(display.ColorArrayName) == ["CELLS", "B"], f"{label}: ParaView colours by cell B on Show "
                                                              f"(got {list(display.ColorArrayName)})")
    info = reader.CellData["B"] if "B" in reader.CellData.keys() else None
    check(info is not None and info.GetNumberOfComponents() == 1, f"{label}: the colouring array B has 1 component")
    if info is not None and mean is not None:
        check(np.allclose(info.GetRange(0), [np.nanmin(mean), np.nanmax(mean)]),
              f"{label}: ParaView's range of B is the channel mean's ({info.GetRange(0)})")
    pv.Delete(view)
    return B


def check_common_metadata(data, label, command):
    check(field_value(data, "radwalk_version") not in (None, ""), f"{label}: field radwalk_version")
    check(field_value(data, "git_commit") not in (None, ""), f"{label}: field git_commit")
    check(field_value(data, "command") == command, f"{label}: field command == {command}")
    line = field_value(data, "command_line") or ""
    check(f" {command} " in line, f"{label}: field command_line names the command ({line!r})")
    check(field_value(data, "seed") is not None, f"{label}: field seed")
    check("unit" in (field_value(data, "length_unit") or "") and "W per" in (field_value(data, "B_unit") or ""),
          f"{label}: fields length_unit and B_unit")
    seed = data.GetFieldData().GetArray("seed")
    check(seed is not None and seed.GetDataType() in (VTK_LONG_LONG, VTK_LONG, VTK_ID_TYPE),
          f"{label}: field seed is an integer")
    timings = [data.GetFieldData().GetArrayName(k) for k in range(data.GetFieldData().GetNumberOfArrays())]
    check(any(t.startswith("seconds_") for t in timings), f"{label}: stage timings in the field data")


def calculator_range(reader, attribute, function):
    calc = pv.Calculator(Input=reader)
    calc.AttributeType = attribute
    calc.ResultArrayName = "result"
    calc.Function = function
    calc.UpdatePipeline()
    data = calc.CellData if attribute == "Cell Data" else calc.PointData
    ok = "result" in data.keys()
    r = data["result"].GetRange() if ok else None
    pv.Delete(calc)
    return r


def check_series(pvd, label, time_key, expect_steps=None):
    """The .pvd opens in ParaView with its times; each step file has its per-step field data."""
    import xml.etree.ElementTree as ET
    entries = [(float(e.get("timestep")), e.get("file")) for e in ET.parse(path(pvd)).getroot().iter("DataSet")]
    check(len(entries) > 1, f"{label}: more than one step")
    if expect_steps is not None:
        check(len(entries) == expect_steps, f"{label}: {expect_steps} steps (got {len(entries)})")
    reader = pv.PVDReader(FileName=path(pvd))
    times = reader.TimestepValues
    times = [times] if isinstance(times, float) else list(times)
    check(times == [t for t, _ in entries], f"{label}: ParaView reads the {len(entries)} times")
    reader.UpdatePipeline(times[-1])
    check(all(k in reader.CellData.keys() for k in ("B", "B_rgb", "B_srgb")), f"{label}: last step has B, B_rgb, B_srgb")
    check(reader.CellData["B"].GetNumberOfComponents() == 1, f"{label}: last step's B has one component")
    steps = []
    for t, f in entries:
        _, data = open_vtp(os.path.join(os.path.dirname(pvd), f))
        value = field_value(data, time_key)
        check(value == t, f"{label}: {f} field {time_key} == time {t} (got {value})")
        steps.append(data)
    pv.Delete(reader)
    return steps


def read_png(name):
    r = vtkPNGReader()
    r.SetFileName(name)
    r.Update()
    image = r.GetOutput()
    w, h, _ = image.GetDimensions()
    a = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(h, w, -1)
    return a[::-1, :, :3].astype(float)  # row 0 at the top


REGIONS = {  # (x0, x1, y0, y1) as fractions of the image, y from the top, Cornell box camera
    "left wall": (0.03, 0.12, 0.30, 0.70),
    "right wall": (0.88, 0.97, 0.30, 0.70),
    "back wall": (0.35, 0.65, 0.20, 0.38),
    "ceiling": (0.15, 0.35, 0.03, 0.10),
    "floor": (0.10, 0.45, 0.90, 0.97),
}


def compare_with_path_tracer(paraview_png, path_traced_png):
    a, b = read_png(paraview_png), read_png(path_traced_png)
    if not check(a.shape == b.shape, f"images have the same size ({a.shape} vs {b.shape})"):
        return
    h, w, _ = a.shape
    means = {}
    for name, (x0, x1, y0, y1) in REGIONS.items():
        ma = a[int(y0 * h):int(y1 * h), int(x0 * w):int(x1 * w)].reshape(-1, 3).mean(axis=0)
        mb = b[int(y0 * h):int(y1 * h), int(x0 * w):int(x1 * w)].reshape(-1, 3).mean(axis=0)
        means[name] = (ma, mb)
        print(f"  {name:10s} ParaView {np.round(ma, 1)}  path tracer {np.round(mb, 1)}", flush=True)
        check(np.abs(ma - mb).max() <= 8, f"{name}: mean colour within 8/255 of the path tracer's")
    for name, (c, other) in (("left wall", (0, 1)), ("right wall", (1, 0))):
        for m in means[name]:
            check(m[c] > m[other] + 20 and m[c] > m[2] + 20, f"{name} is {'red' if c == 0 else 'green'} "
                                                              f"({np.round(m, 1)})")
    la, lb = (a >= 250).all(axis=2), (b >= 250).all(axis=2)
    if check(la.any() and lb.any(), "the light is visible (saturated) in both images"):
        ca = np.array(np.nonzero(la)).mean(axis=1)
        cb = np.array(np.nonzero(lb)).mean(axis=1)
        print(f"  light: ParaView {la.sum()} px at {np.round(ca, 2)}, path tracer {lb.sum()} px at {np.round(cb, 2)}")
        check(np.abs(ca - cb).max() <= 1.5, "light centroids within 1.5 pixels")
        grown = lb.copy()
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                grown |= np.roll(np.roll(lb, dy, axis=0), dx, axis=1)
        check(not (la & ~grown).any(), "every ParaView light pixel within 1 pixel of a path-traced one")


VIRIDIS_LOW = (0.267004, 0.004874, 0.329415)  # the first colour of ParaView's "Viridis (matplotlib)"


def bounds_of(name):
    reader, data = open_vtp(name)
    b = data.GetBounds()
    pv.Delete(reader)
    return (b[0], b[2], b[4]), (b[1], b[3], b[5])


def check_state(name, vtp, label):
    """Loads the state `name` (written for `vtp`) as ParaView does and checks the figure: coloured by the
    one-component B (the point field, smooth), Viridis over the range of B on the non-emitting cells (so below
    every emitter's B), a visible colour bar titled B with its unit, and the camera of the one camera rule
    (scripts/camera_rule.py on the data). Returns (view, camera as 10 numbers)."""
    import camera_rule  # scripts/, on sys.path once paraview_render.py is loaded
    for proxy in list(pv.GetSources().values()):
        pv.Delete(proxy)
    state = path(name)
    namespace = {"__file__": state, "__name__": "__radwalk_state__"}
    exec(compile(open(state).read(), state, "exec"), namespace)
    view, display = namespace["view"], namespace["display"]
    data = servermanager.Fetch(namespace["reader"])
    B = vtk_to_numpy(data.GetCellData().GetArray("B")).astype(float)
    emits = (vtk_to_numpy(data.GetCellData().GetArray("E")) > 0).any(axis=1)
    lit = B[~emits] if (~emits).any() else B
    check(B.ndim == 1, f"{label}: B has one component")
    check(list(display.ColorArrayName) == ["POINTS", "B"], f"{label}: coloured by the point field B "
                                                           f"(got {list(display.ColorArrayName)})")
    check(display.Interpolation == "Gouraud", f"{label}: smooth shading (got {display.Interpolation})")
    lut = pv.GetColorTransferFunction("B")
    points = list(lut.RGBPoints)
    check(np.isclose(points[0], lit.min()) and np.isclose(points[-4], lit.max()),
          f"{label}: colour map range {points[0]:.4g}..{points[-4]:.4g} == B over the non-emitting patches "
          f"{lit.min():.4g}..{lit.max():.4g}")
    if emits.any() and (~emits).any():
        check(points[-4] < B[emits].min(), f"{label}: the range excludes the emitters ({points[-4]:.4g} < "
                                           f"{B[emits].min():.4g})")
    check(np.allclose(points[1:4], VIRIDIS_LOW, atol=2e-3), f"{label}: Viridis (first colour {points[1:4]})")
    bar = pv.GetScalarBar(lut, view)
    check(bar.Visibility == 1, f"{label}: the colour bar is visible")
    check(bar.Title.startswith("B") and "W/" in bar.Title, f"{label}: colour bar title with the unit ({bar.Title!r})")
    camera = (list(view.CameraPosition) + list(view.CameraFocalPoint) + list(view.CameraViewUp) +
              [view.CameraViewAngle])
    rule = camera_rule.camera_rule(data)
    # The state's camera is the C++ fit (apps/scene_camera.h, Embree in single precision), the rule's the same
    # fit in Python on the data (VTK in double precision): they agree to 1e-6 of the scene's size.
    lo, hi = camera_rule.bounds(data)
    size = float(np.linalg.norm(np.subtract(hi, lo)))
    check(same_camera(camera, rule, size, label),
          f"{label}: the state's camera == scripts/camera_rule.py's ({camera} vs {rule})")
    return view, camera


def same_camera(a, b, size, label):
    """Two cameras as 10 numbers agree to 1e-6 of the scene's size. In the closed cube, a symmetric room, the lit
    directions tie to within which of two walls a probe through their common edge hits, which ParaView's VTK and
    Embree decide differently: there only the position and the view angle are compared (tests/python/
    test_camera_rule.py compares the whole camera, the cube's too, with Debian's VTK)."""
    if label.endswith("closed cube") or label.endswith("(closed cube)"):
        return np.allclose(a[0:3], b[0:3], atol=1e-6 * size) and np.isclose(a[9], b[9], rtol=1e-6)
    return np.allclose(a, b, rtol=1e-6, atol=1e-6 * size)


def main():
    render = load_render_script()
    render_vtp = load_render_script("render_vtp")

    print("solve .vtp (direct, Cornell box, 1070 patches)", flush=True)
    reader, data = open_vtp("solve.vtp")
    B = check_ready(reader, data, "solve.vtp", patches=1070)
    check_common_metadata(data, "solve.vtp", "solve")
    check(field_value(data, "method") == "direct", "solve.vtp: field method == direct")
    check((field_value(data, "residual") or 1) < 1e-10, "solve.vtp: field residual < 1e-10")
    check((field_value(data, "rays") or 0) == 1070 * 2000, "solve.vtp: field rays == 1070 x 2000")
    for name in ("row_sum", "reciprocity_error", "row_std_error"):
        check_array(data, "cell", name, "real", 1, lo=0)
    for name in ("rays", "escaped", "back_hits"):
        check_array(data, "cell", name, "int", 1, lo=0)
        check_no_point_array(data, name)
    if B is not None:
        check(B.max() > 50 and np.median(B) < 5, "solve.vtp: B range: the light (> 50) above the room (median < 5)")
    r = calculator_range(reader, "Cell Data", "B_rgb_R - E_R")
    check(r is not None and r[0] > -1e-9, f"solve.vtp: Calculator evaluates B_rgb_R - E_R >= 0 (got {r})")
    # Smooth point field: across the light's edge, the ceiling's points never take the light's values.
    points = check_array(data, "point", "B_rgb", "real", 3)
    emitter = vtk_to_numpy(data.GetCellData().GetArray("E"))[:, 0] > 0
    if points is not None:
        from vtkmodules.vtkCommonCore import vtkIdList
        ids = vtkIdList()
        worst = 0.0
        light_min = B[emitter, 0].min()
        for i in np.nonzero(~emitter)[0]:
            data.GetCellPoints(int(i), ids)
            for k in range(ids.GetNumberOfIds()):
                worst = max(worst, points[ids.GetId(k), 0])
        check(worst < light_min / 4, f"solve.vtp: no ceiling point takes the light's value (max {worst:.3g}, "
                                     f"light {light_min:.3g})")
    pv.Delete(reader)

    print("ParaView states: the figure in one step, and the one camera rule", flush=True)
    view, state_camera = check_state("solve.py", "solve.vtp", "state (Cornell box)")
    check(np.allclose(state_camera[:3], [278, 273, -800]), f"state: Cornell camera (got {state_camera[:3]})")
    check(abs(state_camera[9] - 39.3077) < 1e-3, f"state: view angle 39.31 (got {state_camera[9]})")
    view.ViewSize = [400, 400]
    pv.Render(view)
    pv.SaveScreenshot(os.path.join(SHOTS, "state_cornell_box.png"), view, ImageResolution=[400, 400],
                      TransparentBackground=0)
    check(np.allclose(view.CameraPosition, [278, 273, -800]), "state: camera kept after rendering")
    pv.Delete(view)
    for name, label, where in (("cube", "closed cube", "inside"), ("squares", "parallel squares", "outside")):
        view, state_camera = check_state(name + ".py", name + ".vtp", f"state ({label})")
        pv.Delete(view)
        lo, hi = bounds_of(name + ".vtp")
        inside = all(lo[d] < state_camera[d] < hi[d] for d in range(3))
        size = float(np.linalg.norm(np.subtract(hi, lo)))  # the C++ fit (Embree) and the Python one (VTK) agree
        #                                                   to 1e-6 of the scene's size
        check(inside == (where == "inside"), f"state ({label}): camera {where} ({state_camera[:3]})")
        camera = render.render(path(name + ".vtp"), os.path.join(SHOTS, f"camera_rule_{name}.png"), 200, 200)
        check(same_camera(camera, state_camera, size, label),
              f"{label}: paraview_render.py's default camera == the state's ({camera} vs {state_camera})")
        reader, data = open_vtp(name + ".vtp")
        camera = render_vtp.fit_camera(data)
        check(same_camera(camera, state_camera, size, label),
              f"{label}: render_vtp.py's default camera == the state's ({camera} vs {state_camera})")
        pv.Delete(reader)

    print("paraview_render.py: solve.vtp against the path tracer's image", flush=True)
    shot = os.path.join(WORK, "paraview_128.png")
    camera = render.render(path("solve.vtp"), shot, 128, 128)
    check(abs(camera[9] - 39.3077) < 1e-3 and camera[:3] == [278, 273, -800], "render: the Cornell camera")
    compare_with_path_tracer(shot, path("pathtrace_128.png"))
    # Exact sRGB through the Calculator (exposure != 1 takes that path) agrees with B_srgb to one level.
    calc_shot = os.path.join(WORK, "paraview_128_calculator.png")
    render.render(path("solve.vtp"), calc_shot, 128, 128, exposure=1.0 + 1e-12)
    check(np.abs(read_png(calc_shot) - read_png(shot)).max() <= 1, "render: Calculator sRGB == B_srgb to 1/255")
    render.render(path("refined.vtp"), os.path.join(SHOTS, "refined_smooth.png"), 400, 400, smooth=True)
    try:
        render.render(path("patches.vtp"), os.path.join(WORK, "never.png"))
        check(False, "render: a file without B is refused")
    except SystemExit as e:
        check("no cell field B" in str(e), f"render: a clear message for a file without B ({e})")

    print("refined .vtp (T-junctions)", flush=True)
    reader, data = open_vtp("refined.vtp")
    check_ready(reader, data, "refined.vtp")
    check_array(data, "cell", "jump", "real", 1, lo=0)
    sizes = [data.GetCell(i).GetNumberOfPoints() for i in range(data.GetNumberOfCells())]
    check(max(sizes) > 4, f"refined.vtp: T-junction points inserted into polygons (largest has {max(sizes)})")
    pv.Delete(reader)

    print("progressive .pvd (gauss-seidel)", flush=True)
    steps = check_series("progressive/solve.pvd", "progressive", "iteration")
    residuals = [field_value(d, "residual") for d in steps]
    elapsed = [field_value(d, "elapsed_seconds") for d in steps]
    check(all(r is not None for r in residuals) and residuals[-1] < 1e-10 < residuals[0],
          f"progressive: residual per step falls below 1e-10 ({residuals[0]:.3g} -> {residuals[-1]:.3g})")
    check(all(b >= a for a, b in zip(elapsed, elapsed[1:])), "progressive: elapsed_seconds increases")
    shot = os.path.join(WORK, "progressive_last.png")
    render.render(path("progressive/solve.pvd"), shot, 64, 64)
    check(os.path.exists(shot), "render: a .pvd renders (last step)")
    try:
        render.render(path("progressive/solve.pvd"), shot, 64, 64, step=10000)
        check(False, "render: a step out of range is refused")
    except SystemExit as e:
        check("out of range" in str(e), f"render: clear message for a step out of range ({e})")

    print("random-walk .vtp with error bars (gather-expected-value, --theory)", flush=True)
    reader, data = open_vtp("random_walk.vtp")
    B = check_ready(reader, data, "random_walk.vtp", patches=360)
    check_common_metadata(data, "random_walk.vtp", "solve")
    check(field_value(data, "method") == "gather-expected-value", "random_walk.vtp: field method")
    check(field_value(data, "walks_per_patch") == 200, "random_walk.vtp: field walks_per_patch == 200")
    check((field_value(data, "B_se_relative_rms") or 0) > 0, "random_walk.vtp: field B_se_relative_rms")
    se = check_array(data, "cell", "B_se", "real", 3, lo=0)
    var = check_array(data, "cell", "B_var", "real", 3, lo=0)
    check_array(data, "cell", "B_var_theory", "real", 3, lo=-1e-9)
    check(data.GetCellData().GetArray("var") is None, "random_walk.vtp: no array named var")
    if se is not None and var is not None:
        # B_se is the walks' sqrt(B_var / walks) and the form factors' noise in quadrature (docs/accuracy.md).
        walks_se = np.sqrt(var / 200)
        check(np.all(se >= walks_se * (1 - 1e-9)) and np.any(se > walks_se),
              "random_walk.vtp: B_se >= sqrt(B_var / walks), with the form factors' noise added")
    r = calculator_range(reader, "Cell Data", "B_var_R / 200")
    check(r is not None, "random_walk.vtp: Calculator evaluates B_var_R / 200")
    pv.Delete(reader)
    steps = check_series("random_walk_series/solve.pvd", "random-walk series", "count")
    rel = [field_value(d, "B_se_relative_rms") for d in steps]
    check(rel[-1] < rel[0] / 4, f"random-walk series: relative standard error falls ({rel[0]:.3g} -> {rel[-1]:.3g})")

    print("compare .vtp", flush=True)
    reader, data = open_vtp("compare.vtp")
    check_names_usable(data, "compare.vtp")
    check_common_metadata(data, "compare.vtp", "compare")
    check("gather-absorption" in (field_value(data, "estimators") or ""), "compare.vtp: original estimator names")
    for m in ("gather_absorption", "gather_expected_value", "shoot_collision"):
        for prefix in ("mean_", "var_", "var_theory_", "z_"):
            check_array(data, "cell", prefix + m, "real", 3)
    check_array(data, "cell", "B_reference", "real", 3, lo=0)
    r = calculator_range(reader, "Cell Data", "mean_gather_absorption_R - B_reference_R")
    check(r is not None, "compare.vtp: Calculator evaluates mean_gather_absorption_R - B_reference_R")
    pv.Delete(reader)

    print("path-tracer .vtp", flush=True)
    reader, data = open_vtp("pathtrace.vtp")
    check_ready(reader, data, "pathtrace.vtp", patches=360)
    check_common_metadata(data, "pathtrace.vtp", "pathtrace")
    check(field_value(data, "method") == "pathtrace-mis", "pathtrace.vtp: field method == pathtrace-mis")
    check(field_value(data, "spp") == 16, "pathtrace.vtp: field spp == 16")
    check_array(data, "cell", "B_se", "real", 3, lo=0)
    check_array(data, "cell", "B_var", "real", 3, lo=0)
    pv.Delete(reader)
    check_series("pathtrace_series/pathtrace.pvd", "path-tracer series", "count", expect_steps=4)

    print("form-factor diagnostics .vtp", flush=True)
    reader, data = open_vtp("formfactors.vtp")
    check_common_metadata(data, "formfactors.vtp", "formfactors")
    check(data.GetCellData().GetScalars() is None, "formfactors.vtp: no active scalars (no B)")
    check_array(data, "cell", "row_sum", "real", 1, lo=0, hi=1 + 1e-6)
    check_array(data, "cell", "row_sum", "real", 1)
    check_array(data, "point", "row_sum", "real", 1)
    for name in ("rays", "escaped", "back_hits", "patch", "face"):
        check_array(data, "cell", name, "int", 1, lo=0)
        check_no_point_array(data, name)
    check_names_usable(data, "formfactors.vtp")
    pv.Delete(reader)

    print(f"{passed[0]} passed, {len(failed)} failed", flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
