"""Shared helpers of the radwalk experiments: import the radwalk Python module (import_radwalk); find and run the
radwalk program (Radwalk) and read CSV tables (read_csv), for adaptive_patching.py, the one script not yet on the
module, and for redrawing charts from a script's own CSV; write CSV tables, and set up matplotlib (Agg backend,
no display needed).

Every experiment script takes --out DIR (default: results/<experiment>/ under the current directory), --threads
and --seed; those that run the program also --radwalk PATH (default: $RADWALK, else build/apps/radwalk under the
repository root)."""

import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

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


def parser(experiment, description, program=True):
    """argparse parser with the options every experiment shares (--radwalk only for those that run the program)."""
    p = argparse.ArgumentParser(description=description)
    if program:
        p.add_argument("--radwalk", default=os.environ.get("RADWALK", os.path.join(REPO, "build", "apps", "radwalk")),
                       help="radwalk program (default: $RADWALK, else build/apps/radwalk)")
    p.add_argument("--out", default=os.path.join("results", experiment), help="results folder")
    p.add_argument("--threads", type=int, default=2, help="threads per radwalk run (default 2)")
    p.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    return p


class Folder:
    """A results folder (for redrawing charts without running radwalk)."""

    def __init__(self, out):
        self.out = out

    def path(self, *parts):
        return os.path.join(self.out, *parts)


class Radwalk:
    """Runs the radwalk program; every call's command line is logged to OUT/commands.txt."""

    def __init__(self, exe, out, threads):
        self.exe = os.path.abspath(exe)
        if not os.access(self.exe, os.X_OK):
            sys.exit(f"radwalk program not found at {self.exe} (build it, or pass --radwalk / set RADWALK)")
        self.out = out
        self.threads = threads
        os.makedirs(out, exist_ok=True)
        self.log = open(os.path.join(out, "commands.txt"), "w")

    def path(self, *parts):
        return os.path.join(self.out, *parts)

    def run(self, args, json_file=None, ok_codes=(0,)):
        """Runs `radwalk -q ARGS --threads T [--json FILE]`. Returns a dict: rc, stderr, wall (s), json (or None)."""
        cmd = [self.exe, "-q"] + [str(a) for a in args] + ["--threads", str(self.threads)]
        if json_file:
            cmd += ["--json", json_file]
            if os.path.exists(json_file):
                os.remove(json_file)
        self.log.write(" ".join(cmd) + "\n")
        self.log.flush()
        t0 = time.perf_counter()
        r = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if r.returncode not in ok_codes:
            sys.exit(f"radwalk failed (exit {r.returncode}): {' '.join(cmd)}\n{r.stderr}")
        js = None
        if json_file and os.path.exists(json_file):
            with open(json_file) as f:
                js = json.load(f)
        return {"rc": r.returncode, "stderr": r.stderr.strip(), "wall": wall, "json": js}


def read_csv(path):
    """Rows of a CSV as dicts; numeric-looking values become float, empty cells NaN; the run_id column (the run
    that wrote the file, hexadecimal digits) stays text."""
    rows = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            out = {}
            for k, v in row.items():
                if k == "run_id":
                    out[k] = v
                    continue
                try:
                    out[k] = float(v) if v != "" else math.nan
                except ValueError:
                    out[k] = v
            rows.append(out)
    return rows


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
    widths = [max(len(k), *(len(str(c[i])) for c in cells)) for i, k in enumerate(fields)]
    lines = [title] if title else []
    lines.append("  ".join(k.rjust(w) for k, w in zip(fields, widths)))
    lines += ["  ".join(str(c).rjust(w) for c, w in zip(row, widths)) for row in cells]
    return "\n".join(lines)


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(f"wrote {path}")
