"""python3 -m dbss.batch on a local Dask cluster of two workers: six inputs,
one broken; the five outputs equal the command line's byte for byte; a
re-run skips them; a user's scheduler takes the tasks when given."""
import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import ROOT


def write_inputs(folder, points):
    """Five readable files of four formats (one in a subfolder) and a broken one."""
    (folder / "sub").mkdir(parents=True)
    np.savetxt(folder / "full.xyz", points, fmt="%.9g")
    np.savetxt(folder / "sub" / "half.xyz", points[::2], fmt="%.9g")
    np.savetxt(folder / "odd.obj", points[1::2], fmt="v %.9g %.9g %.9g")
    stretched = points[::2] * np.array([2.0, 1.0, 1.5])
    with open(folder / "stretched.off", "w") as f:
        f.write(f"OFF\n{len(stretched)} 0 0\n")
        np.savetxt(f, stretched, fmt="%.9g")
    third = points[::3].astype("<f4")
    with open(folder / "third.ply", "wb") as f:
        f.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {len(third)}\n"
                "property float x\nproperty float y\nproperty float z\nend_header\n".encode())
        f.write(third.tobytes())
    (folder / "broken.ply").write_bytes(b"ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nend_header\n1\n")
    return ["full.xyz", "sub/half.xyz", "odd.obj", "stretched.off", "third.ply"]


def batch(*args):
    return subprocess.run([sys.executable, "-m", "dbss.batch", *map(str, args)], capture_output=True, text=True,
                          env=os.environ, timeout=300)


def expect_cli_bytes(cli, folder, out, good, *flags):
    for name in good:
        want = out.parent / "cli.dbss"
        cli("encode", folder / name, "-o", want, *flags)
        got = out / (name.rsplit(".", 1)[0] + ".dbss")
        assert got.read_bytes() == want.read_bytes(), name


def test_batch_on_a_local_cluster(cli, torus_points, tmp_path):
    folder, out = tmp_path / "in", tmp_path / "out"
    good = write_inputs(folder, torus_points)

    run = batch(folder, out, "--workers", 2, "--levels", 1)
    assert run.returncode == 1, run.stderr
    assert "6 files: 5 encoded, 0 skipped, 1 failed" in run.stdout
    assert "broken.ply" in run.stderr and "broken.ply" in run.stdout
    expect_cli_bytes(cli, folder, out, good, "--levels", 1)
    listing = sorted(p.relative_to(out).as_posix() for p in out.rglob("*") if p.is_file())
    assert listing == sorted(["dbss-batch.json"] + [g.rsplit(".", 1)[0] + ".dbss" for g in good])  # no temporaries

    # Same inputs and options: nothing encoded again, nothing rewritten.
    stamps = {p: p.stat().st_mtime_ns for p in out.rglob("*.dbss")}
    again = batch(folder, out, "--workers", 2, "--levels", 1)
    assert again.returncode == 1 and "6 files: 0 encoded, 5 skipped, 1 failed" in again.stdout
    assert stamps == {p: p.stat().st_mtime_ns for p in out.rglob("*.dbss")}
    # A changed input is encoded again, the rest skipped.
    np.savetxt(folder / "full.xyz", torus_points[::-1], fmt="%.9g")
    changed = batch(folder, out, "--workers", 2, "--levels", 1)
    assert "6 files: 1 encoded, 4 skipped, 1 failed" in changed.stdout
    expect_cli_bytes(cli, folder, out, ["full.xyz"], "--levels", 1)


def test_batch_on_a_running_scheduler(cli, torus_points, tmp_path):
    from dask.distributed import LocalCluster

    folder, out = tmp_path / "in", tmp_path / "out"
    good = write_inputs(folder, torus_points)
    (folder / "broken.ply").unlink()
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        run = batch(folder, out, "--scheduler", cluster.scheduler_address, "--levels", 2, "--error", 2e-4)
        assert run.returncode == 0, run.stderr
        assert "5 files: 5 encoded, 0 skipped, 0 failed" in run.stdout
        # Other options: every file again.
        run = batch(folder, out, "--scheduler", cluster.scheduler_address, "--levels", 1)
        assert "5 files: 5 encoded, 0 skipped, 0 failed" in run.stdout
    expect_cli_bytes(cli, folder, out, good, "--levels", 1)


def test_batch_refuses_bad_options(tmp_path):
    run = batch(tmp_path, tmp_path / "out", "--grid", 1)
    assert run.returncode == 2 and "--grid needs a whole number" in run.stderr
    run = batch(tmp_path / "missing", tmp_path / "out")
    assert run.returncode == 2 and "not a directory" in run.stderr
