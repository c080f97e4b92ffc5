"""Fixtures for the dbss Python tests: the command line to compare with and
small point sets.  Run with PYTHONPATH=<build>/python (scripts/test.sh)."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

import dbss

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def cli():
    """Runs build/bin/dbss (next to the module: <build>/python/dbss -> <build>/bin),
    or DBSS_CLI; returns the CompletedProcess."""
    exe = os.environ.get("DBSS_CLI") or str(pathlib.Path(dbss.__file__).resolve().parents[2] / "bin" / "dbss")
    assert os.access(exe, os.X_OK), f"the dbss command is not at {exe} (set DBSS_CLI)"

    def run(*args, check=True):
        return subprocess.run([exe, *map(str, args)], capture_output=True, check=check)

    return run


@pytest.fixture(scope="session")
def torus_xyz():
    """The shipped genus-2 example: 8,000 points."""
    return ROOT / "examples" / "double-torus.xyz"


@pytest.fixture(scope="session")
def torus_points(torus_xyz):
    return np.loadtxt(torus_xyz)


@pytest.fixture(scope="session")
def encoded(cli, torus_xyz, tmp_path_factory):
    """The example encoded by the command at 2 levels: (path, bytes)."""
    out = tmp_path_factory.mktemp("cli") / "double-torus.dbss"
    cli("encode", torus_xyz, "-o", out, "--levels", 2)
    return out, out.read_bytes()


def read_ply(path):
    """The binary PLY `dbss decode` writes: (vertices float32, faces uint32)."""
    data = pathlib.Path(path).read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().split("\n")
    nv = int(next(line for line in header if line.startswith("element vertex")).split()[2])
    nf = int(next(line for line in header if line.startswith("element face")).split()[2])
    v = np.frombuffer(data, "<f4", nv * 3, end).reshape(nv, 3)
    faces = np.frombuffer(data, [("n", "u1"), ("i", "<u4", 3)], nf, end + nv * 12)
    assert (faces["n"] == 3).all()
    return v, faces["i"]


def fnv1a64(floats):
    """spec/decoding.md section 8: FNV-1a 64 of the little-endian float32 bytes."""
    h = 0xCBF29CE484222325
    for b in np.ascontiguousarray(floats, "<f4").tobytes():
        h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"
