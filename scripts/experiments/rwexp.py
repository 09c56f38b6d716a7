"""Shared helpers of the radwalk experiments: import the radwalk Python module (import_radwalk), the options every
script shares (parser), tables (write_csv, read_table for redrawing a chart from a script's own CSV, table for the
terminal), statistics of repeats (median_spread) and chart conventions (matplotlib's Agg backend, no display
needed; log_ticks, infinite_marker, save).

Every experiment script runs on the module (no radwalk program, no files read back) and takes --out DIR (default:
results/<experiment>/ under the current directory), --threads, --seed and --scale."""

import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after use("Agg"))
import numpy as np  # noqa: E402

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
MESHES = os.path.join(REPO, "meshes")
SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes")


def import_radwalk():
    """The radwalk Python module: from PYTHONPATH (an installed one), else from build/python of this checkout."""
    try:
        import radwalk
    except ImportError:
        sys.path.insert(0, os.path.join(REPO, "build", "python"))
        try:
            import radwalk
        except ImportError:
            sys.exit("the radwalk Python module is not built: run scripts/build.sh (needs pybind11-dev), or set "
                     "PYTHONPATH to where it is installed")
    return radwalk


def parser(experiment, description):
    """argparse parser with the options every experiment shares; the script adds --scale and its own."""
    p = argparse.ArgumentParser(description=description, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default=os.path.join("results", experiment), help="results folder")
    p.add_argument("--threads", type=int, default=2, help="threads (default 2; 0 = all cores)")
    p.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    return p


class Folder:
    """A results folder (made when missing)."""

    def __init__(self, out):
        self.out = out
        os.makedirs(out, exist_ok=True)

    def path(self, *parts):
        return os.path.join(self.out, *parts)


def read_table(path):
    """A script's own CSV (write_csv) as a list of dicts, by the csv module: numbers as float (empty cells NaN),
    text as str. For redrawing charts; radwalk's outputs are not read back (the module returns them)."""
    def value(v):
        try:
            return float(v) if v != "" else math.nan
        except ValueError:
            return v
    with open(path, newline="") as f:
        return [{k: value(v) for k, v in row.items()} for row in csv.DictReader(f)]


def write_csv(path, rows, fields=None, digits=6):
    """Rows (dicts) as CSV, floats with `digits` significant digits (12: as radwalk's own CSVs), empty if not finite."""
    fields = fields or list(rows[0].keys())
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: fmt(r.get(k, ""), digits) for k in fields})


def fmt(v, digits=6):
    if isinstance(v, float):
        return "" if not math.isfinite(v) else f"{v:.{digits}g}"
    return v


def median_spread(values):
    """Median and the (min, max) of repeated measurements (timings: at least 3 repeats, docs/experiments.md convention)."""
    v = np.asarray(values, dtype=float)
    return float(np.median(v)), float(v.min()), float(v.max())


def rms_relative_error(B, B_ref):
    """RMS over (patch, channel) pairs with B_ref > 0 of (B - B_ref) / B_ref; NaN entries of B count as errors
    of 1 (a patch a method did not estimate is 100 % wrong)."""
    mask = B_ref > 0
    rel = (B[mask] - B_ref[mask]) / B_ref[mask]
    rel = np.where(np.isfinite(rel), rel, 1.0)
    return float(np.sqrt(np.mean(rel ** 2)))


def table(rows, fields, title=None):
    """Aligned text table for the terminal."""
    cells = [[fmt(r.get(k, "")) if not isinstance(r.get(k), float) else f"{r[k]:.4g}" for k in fields]
             for r in rows]
    widths = [max([len(k)] + [len(str(c[i])) for c in cells]) for i, k in enumerate(fields)]
    lines = [title] if title else []
    lines.append("  ".join(k.rjust(w) for k, w in zip(fields, widths)))
    lines += ["  ".join(str(c).rjust(w) for c, w in zip(row, widths)) for row in cells]
    return "\n".join(lines)


def log_ticks(ax, x=True, y=True):
    """Readable ticks on log axes (call after setting the limits): plain numbers (1, 10, 0.01, 2, 5) at 1, 2, 5
    times the decades when the axis spans under two decades, at the decades otherwise (every second or third one
    beyond seven decades); minor ticks unlabelled."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    def label(v, _):
        return f"{v:g}" if 1e-3 <= v < 1e5 else f"1e{int(round(math.log10(v)))}"
    for on, axis, limits in ((x, ax.xaxis, ax.get_xlim()), (y, ax.yaxis, ax.get_ylim())):
        if on and axis.get_scale() == "log":
            decades = math.log10(max(limits) / min(limits))
            subs = (1.0, 2.0, 5.0) if decades < 2 else (1.0,)
            # At most about 7 labels on a wide axis (every second or third decade), so that they do not touch.
            axis.set_major_locator(LogLocator(base=10, subs=subs, numticks=15 if decades <= 7 else 7))
            axis.set_major_formatter(FuncFormatter(label))
            axis.set_minor_formatter(NullFormatter())


def length_unit(scene):
    """The unit of a scene's lengths for labels: mm for the bundled Cornell box and the experiments' spot_room
    (both modelled in mm), else "units"."""
    name = os.path.basename(str(scene))
    return "mm" if name.startswith(("cornell_box", "spot_room")) else "units"


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")
