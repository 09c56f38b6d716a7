#!/usr/bin/env python3
"""The first bounce on the spot-lit room's floor next to the wall that holds the light (scenes/spot_room.obj).

The light is a patch of the wall x = 0 (y 10..50 mm, z 230..270 mm, normal +x, emitted radiosity E); the floor is
y = 0 (normal +y). The irradiance a floor point (x, 0, z) gets from it, in units of E, is the point-to-polygon form
factor
    F(x) = integral over the light of cos_light cos_floor / (pi r^2) dA = integral of x y / (pi r^4) dA,
computed here by the midpoint rule (0.25 mm cells) at z = 250 (the light's middle). The script prints F's peak and
its averages over the floor strips [0, w] beside the wall: what the floor patch of width w next to the wall shoots,
as a constant, into the 10 mm wall strip below the light, which sees mostly the floor within about 10 mm of the
wall (docs/hierarchy.md, the spot-lit room's strip).
Usage: python3 scripts/experiments/spot_strip_profile.py
"""
import numpy as np

cell = 0.25
ys = np.arange(10 + cell / 2, 50, cell)
zs = np.arange(230 + cell / 2, 270, cell)
Y, Z = (a.ravel() for a in np.meshgrid(ys, zs))


def F(x, z=250.0):
    r2 = x * x + Y * Y + (Z - z) ** 2
    return float(np.sum(x * Y / (np.pi * r2 * r2)) * cell * cell)


xs = np.concatenate([np.linspace(0.05, 5, 100), np.linspace(5.05, 100, 400)])
f = np.array([F(x) for x in xs])
print("peak F = %.4f at x = %.1f mm; F(1 mm) = %.4f, F(3 mm) = %.4f" % (f.max(), xs[f.argmax()], F(1.0), F(3.0)))
for w in (5, 10, 25, 50):
    m = xs <= w
    print("average of F over the floor strip [0, %g] mm beside the wall: %.4f" % (w, np.trapz(f[m], xs[m]) / (xs[m][-1] - xs[m][0])))
