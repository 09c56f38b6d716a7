#!/usr/bin/env python3
# usage: /usr/bin/python3 bench/check_vtp.py FILE.vtp (the 10^7-patch runs of docs/scaling.md, "Ten million patches")
# Reads a radwalk .vtp with VTK's reader and prints what it holds: counts, arrays, active scalars, field data, and
# the area-weighted mean of B recomputed from the file's cell arrays (to compare with what the run printed).
import sys, time, vtk
from vtk.util.numpy_support import vtk_to_numpy
t = time.time()
r = vtk.vtkXMLPolyDataReader(); r.SetFileName(sys.argv[1])
errors = []
r.AddObserver("ErrorEvent", lambda o, e: errors.append(e))
r.Update()
p = r.GetOutput()
print("read in %.1f s, errors %d" % (time.time() - t, len(errors)))
print("cells", p.GetNumberOfCells(), "points", p.GetNumberOfPoints())
cd, pd, fd = p.GetCellData(), p.GetPointData(), p.GetFieldData()
print("cell arrays", [cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())], "scalars", cd.GetScalars().GetName())
print("point arrays", [pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())])
print("field data", [fd.GetAbstractArray(i).GetName() for i in range(fd.GetNumberOfArrays())])
A = vtk_to_numpy(cd.GetArray("area")); B = vtk_to_numpy(cd.GetArray("B_rgb"))  # B is the channel mean
print("area-weighted mean B =", (A[:, None] * B).sum(axis=0) / A.sum())
