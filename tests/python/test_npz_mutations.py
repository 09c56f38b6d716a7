"""radwalk's .npz reader against scipy.sparse.load_npz on mutated files (formfactor/npz.h): from a fixed seed,
valid files are mutated (byte flips, truncations, edits of the zip and .npy size fields, and content edits whose
CRC-32 is made right again, so that the checks behind the CRC are reached too). Whenever radwalk accepts a file,
scipy must read the same matrix (same shape, indptr, indices and float32 bits) and find it valid
(check_format(full_check=True)); whenever scipy refuses a file or reads an invalid matrix, radwalk must refuse it.
radwalk's reading comes from tests/formfactor/npz_read_tool.cpp (one process for every file)."""
import io
import os
import random
import re
import struct
import subprocess
import warnings
import zipfile
import zlib

import numpy as np
import pytest
import scipy.sparse

from conftest import mesh, run_cli

TOOL = os.environ.get("RADWALK_NPZ_READ_TOOL")
SEED = 20261204
MUTATIONS_PER_BASE = 150


def radwalk_reads(n, paths):
    """radwalk's verdict on each file: ("ok", (indptr, indices, value bits)) or ("refused", message)."""
    result = subprocess.run([TOOL, str(n), *map(str, paths)], capture_output=True, text=True)
    assert result.returncode == 0, f"the reader failed (exit {result.returncode}): {result.stdout[-2000:]} {result.stderr}"
    lines = result.stdout.splitlines()
    assert len(lines) == len(paths), result.stdout[-2000:]
    verdicts = []
    for line in lines:
        kind, _, rest = line.partition(" ")
        if kind == "ok":
            indptr, indices, bits = rest.split(" ")
            parse = lambda s, base: [] if s == "-" else [int(x, base) for x in s.split(",")]
            verdicts.append(("ok", (parse(indptr, 10), parse(indices, 10), parse(bits, 16))))
        else:
            assert kind == "refused" and "\n" not in rest, line
            verdicts.append(("refused", rest))
    return verdicts


def scipy_reads(path):
    """scipy's matrix when it reads the file and finds it valid, else None."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            m = scipy.sparse.load_npz(path)
            if m.format != "csr":
                return None
            m.check_format(full_check=True)
            return m
    except Exception:  # any refusal: BadZipFile, ValueError, EOFError, NotImplementedError, UnicodeDecodeError ...
        return None


def layout(data):
    """Where each member's bytes are and where its CRC-32 is stored (directory entry and local header)."""
    members = []
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        at = z.start_dir
        for info in z.infolist():
            local = info.header_offset
            name_len, extra_len = struct.unpack_from("<HH", data, local + 26)
            begin = local + 30 + name_len + extra_len
            members.append({"begin": begin, "size": info.compress_size, "crc_at": [at + 16, local + 14],
                            "size_at": [at + 20, at + 24, local + 18, local + 22], "local": local, "central": at})
            n, e, c = struct.unpack_from("<HHH", data, at + 28)
            at += 46 + n + e + c
    return members


def with_crcs_fixed(data, members):
    data = bytearray(data)
    for m in members:
        crc = zlib.crc32(bytes(data[m["begin"]:m["begin"] + m["size"]])) & 0xffffffff
        for at in m["crc_at"]:
            struct.pack_into("<I", data, at, crc)
    return bytes(data)


def mutate(rng, data, members):
    """One mutation of `data`: its kind and the mutated bytes."""
    kind = rng.choice(["flip", "flip", "truncate", "zip size field", "npy shape", "content", "content",
                       "content header"])
    out = bytearray(data)
    if kind == "flip":
        for _ in range(rng.choice([1, 1, 2, 4])):
            out[rng.randrange(len(out))] ^= 1 << rng.randrange(8)
    elif kind == "truncate":
        out = out[:rng.randrange(len(out))]
    elif kind == "zip size field":
        m = rng.choice(members)
        fields = m["size_at"] + [m["central"] + 42, len(data) - 22 + 10, len(data) - 22 + 12, len(data) - 22 + 16]
        at = rng.choice(fields)
        old = struct.unpack_from("<I", out, at)[0]
        new = rng.choice([0, 1, old + 1, old - 1, old + 64, 0xffffffff, 0x7fffffff, rng.randrange(1 << 32)])
        struct.pack_into("<I", out, at, new & 0xffffffff)
        if rng.random() < 0.5 and len(data) > 98:  # the ZIP64 end record's count, size or offset
            at = len(data) - 22 - 20 - 56 + rng.choice([24, 32, 40, 48])
            struct.pack_into("<Q", out, at, rng.choice([0, 1, rng.randrange(1 << 40), (1 << 64) - 1]))
    elif kind == "npy shape":
        text = bytes(out)
        found = [m for m in re.finditer(rb"'shape': \((\d+)", text)]
        m = rng.choice(found)
        value = int(m.group(1))
        new = str(rng.choice([0, value + 1, max(value - 1, 0), value * 2, 10 ** 9, 36, 37])).encode()
        new = new[:len(m.group(1))].rjust(len(m.group(1)), b" ")  # same length: the layout stays
        out[m.start(1):m.end(1)] = new
        out = bytearray(with_crcs_fixed(bytes(out), members))
    elif kind in ("content", "content header"):
        m = rng.choice(members)
        span = range(m["begin"], m["begin"] + m["size"])
        if kind == "content header":
            span = range(m["begin"], min(m["begin"] + 128, m["begin"] + m["size"]))
        for _ in range(rng.choice([1, 1, 2])):
            at = rng.choice(span)
            out[at] = rng.choice([out[at] ^ (1 << rng.randrange(8)), rng.randrange(256), ord(" "), ord(","),
                                  ord("("), ord(")"), ord("'"), 0])
        out = bytearray(with_crcs_fixed(bytes(out), members))
    return kind, bytes(out)


def bases(tmp_path):
    """Valid files: radwalk's own (CLI), scipy's save_npz (float32 and float64 data, int32 and int64 indices)."""
    run_cli("formfactors", mesh("cube.obj"), "--rays", 200, "--seed", 5, "-o", tmp_path / "radwalk.npz")
    F = scipy.sparse.load_npz(tmp_path / "radwalk.npz")
    n = F.shape[0]
    out = [("radwalk", n, (tmp_path / "radwalk.npz").read_bytes())]
    G = F.astype(np.float64)
    G.indices = G.indices.astype(np.int64)
    G.indptr = G.indptr.astype(np.int64)
    scipy.sparse.save_npz(tmp_path / "scipy64.npz", G, compressed=False)
    scipy.sparse.save_npz(tmp_path / "scipy32.npz", F, compressed=False)
    out.append(("scipy64", n, (tmp_path / "scipy64.npz").read_bytes()))
    out.append(("scipy32", n, (tmp_path / "scipy32.npz").read_bytes()))
    return out


@pytest.mark.skipif(TOOL is None, reason="RADWALK_NPZ_READ_TOOL is not set (run through CTest)")
def test_what_radwalk_accepts_scipy_reads_as_the_same_matrix(tmp_path):
    rng = random.Random(SEED)
    accepted = refused_both = 0
    kinds_accepted = set()
    for name, n, data in bases(tmp_path):
        members = layout(data)
        cases = [("unchanged", data)] + [mutate(rng, data, members) for _ in range(MUTATIONS_PER_BASE)]
        paths = []
        for k, (_, bytes_) in enumerate(cases):
            path = tmp_path / f"{name}-{k}.npz"
            path.write_bytes(bytes_)
            paths.append(path)
        verdicts = radwalk_reads(n, paths)
        assert verdicts[0][0] == "ok", f"{name}: radwalk refuses the valid file: {verdicts[0][1]}"
        for (kind, _), path, (verdict, what) in zip(cases, paths, verdicts):
            m = scipy_reads(path)
            where = f"{path.name} ({kind})"
            if verdict == "ok":
                assert m is not None, f"{where}: radwalk accepts a file scipy refuses or reads as invalid"
                indptr, indices, bits = what
                assert m.shape == (n, n), f"{where}: scipy reads shape {m.shape}"
                assert list(m.indptr) == indptr, f"{where}: indptr differs"
                assert list(m.indices) == indices, f"{where}: indices differ"
                assert list(m.data.astype(np.float32).view(np.uint32)) == bits, f"{where}: values differ"
                accepted += 1
                kinds_accepted.add(kind)
            elif m is None:
                refused_both += 1
            path.unlink()
    # Not vacuous: both outcomes occur, and some mutated files are accepted by both readers.
    print("accepted", accepted, "refused by both", refused_both, "kinds accepted", sorted(kinds_accepted))
    assert accepted > 3 and refused_both > 100, (accepted, refused_both)
    assert kinds_accepted - {"unchanged"}, kinds_accepted
    for name in ("radwalk.npz", "scipy64.npz", "scipy32.npz"):
        (tmp_path / name).unlink()
