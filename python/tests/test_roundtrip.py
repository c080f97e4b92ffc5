"""The module gives the command line's bytes and floats, bit for bit."""
import json

import numpy as np
import pytest

import dbss
from conftest import fnv1a64, read_ply


def test_encode_file_equals_the_command(cli, torus_xyz, encoded, tmp_path):
    out = tmp_path / "py.dbss"
    stats = dbss.encode_file(torus_xyz, out, levels=2)
    assert out.read_bytes() == encoded[1]
    assert stats["bytes"] == len(encoded[1])


def test_encode_array_equals_the_command(torus_points, encoded):
    # float64 from the text, rounded to float32 as the command reads it.
    data = dbss.encode(torus_points, levels=2, source_name="double-torus.xyz")
    assert data == encoded[1]
    assert dbss.encode(torus_points.astype(np.float32), levels=2, source_name="double-torus.xyz") == encoded[1]


def test_every_option_means_the_commands_flag(cli, torus_xyz, torus_points, tmp_path):
    flags = ["--levels", 1, "--grid", 30, "--error", 3e-4, "--effort", 5, "--control-faces", 200,
             "--control-bits", 14, "--surface", "closed", "--keep-outliers"]
    out = tmp_path / "cli.dbss"
    cli("encode", torus_xyz, "-o", out, *flags)
    data = dbss.encode(torus_points, levels=1, grid=30, error=3e-4, effort=5, control_faces=200, control_bits=14,
                       surface="closed", keep_outliers=True, source_name=torus_xyz.name)
    assert data == out.read_bytes()
    step = dbss.encode(torus_points, levels=1, step=0.002, source_name=torus_xyz.name)
    cli("encode", torus_xyz, "-o", out, "--levels", 1, "--step", 0.002)
    assert step == out.read_bytes()


def test_decode_equals_the_command_at_every_level(cli, encoded, tmp_path):
    path, data = encoded
    hashes = cli("info", path, "--hashes").stdout.decode().splitlines()
    assert len(hashes) == 3
    for level in range(3):
        v, f = dbss.decode(data, level)
        assert v.dtype == np.float32 and v.shape[1] == 3 and f.dtype == np.uint32 and f.shape[1] == 3
        assert hashes[level] == f"level {level} vertices {len(v)} triangles {len(f)} fnv1a64 {fnv1a64(v)}"
        ply = tmp_path / f"l{level}.ply"
        cli("decode", path, "-o", ply, "--level", level)
        cv, cf = read_ply(ply)
        assert np.array_equal(v.view(np.uint32), cv.view(np.uint32)) and np.array_equal(f, cf)
    finest_v, _ = dbss.decode(data)
    assert np.array_equal(finest_v, dbss.decode(data, 2)[0])


def test_info_has_the_fields_of_info_json(cli, encoded):
    path, data = encoded
    for flags, hashes in (([], False), (["--hashes"], True)):
        want = json.loads(cli("info", path, "--json", *flags).stdout)
        got = dbss.info(data, hashes=hashes)
        assert got.pop("file") is None and want.pop("file") == str(path)
        assert got == want
    assert dbss.info(path) == json.loads(cli("info", path, "--json").stdout)


def test_stats_per_stage_and_level(torus_points, encoded):
    data, stats = dbss.encode(torus_points, levels=2, source_name="double-torus.xyz", return_stats=True)
    assert data == encoded[1]
    info = dbss.info(data)
    assert stats["bytes"] == len(data) == info["bytes"]
    assert stats["level_count"] == 2 and len(stats["levels"]) == 3
    for row, want in zip(stats["levels"], info["level_table"]):
        assert row["level"] == want["level"] and row["vertices"] == want["vertices"]
        if row["level"] > 0:
            assert row["bytes"] == want["bytes"] and row["odd"] == want["odd"] and row["coding"] == want["coding"]
    assert stats["stages"]["draco"]["triangles"] == info["control"]["triangles"]
    assert stats["stages"]["triangulation"]["genus"] == 2
    for stage in ("outliers", "choose_grid", "cell_carving", "triangulation", "shrink_wrapping", "simplification",
                  "shaping", "projection", "draco", "levels", "self_check", "container"):
        assert stats["stages"][stage]["seconds"] >= 0
    # The control-mesh stages also give their CPU time (all threads summed),
    # the steadier figure on a loaded machine; a stage that ran took some.
    cpu = [stats["stages"][s]["cpu_seconds"] for s in ("choose_grid", "cell_carving", "triangulation",
                                                         "shrink_wrapping", "simplification", "shaping", "projection")]
    assert all(c >= 0 for c in cpu) and sum(cpu) > 0
    assert stats["stages"]["surface"]["doubtful_caps"] == 0
    shaping = stats["stages"]["shaping"]
    assert shaping["enabled"] and shaping["triangles"] == info["control"]["triangles"]
    assert 0 <= shaping["poor_share_after"] <= 1 and 3 <= shaping["max_valence_after"] <= 64


def test_decoder_fed_one_byte_at_a_time(encoded):
    data = encoded[1]
    d = dbss.Decoder()
    assert d.levels_ready == -1 and d.levels is None
    seen = []
    for i in range(len(data)):
        seen.append(d.push(data[i:i + 1]))
    d.finish()
    assert d.error is None and d.levels == 2
    assert seen == sorted(seen) and seen[-1] == 2 and set(seen) == {-1, 0, 1, 2}
    # Each level becomes ready exactly when the bytes that hold it have all arrived.
    for level in range(3):
        n = seen.index(level) + 1
        assert dbss.Decoder().push(data[:n]) == level and dbss.Decoder().push(data[:n - 1]) == level - 1
    for level in (2, 0, 1):
        v, f = d.level(level)
        wv, wf = dbss.decode(data, level)
        assert np.array_equal(v.view(np.uint32), wv.view(np.uint32)) and np.array_equal(f, wf)


def _torus_mesh(rings=48, sides=24, major=1.0, minor=0.4):
    u = 2 * np.pi * np.arange(rings)[:, None] / rings
    v = 2 * np.pi * np.arange(sides)[None, :] / sides
    xyz = np.stack([(major + minor * np.cos(v)) * np.cos(u), (major + minor * np.cos(v)) * np.sin(u),
                    minor * np.sin(v) + 0 * u], axis=-1).reshape(-1, 3).astype(np.float32)
    i, j = np.meshgrid(np.arange(rings), np.arange(sides), indexing="ij")
    a, b = i * sides + j, ((i + 1) % rings) * sides + j
    c, d = ((i + 1) % rings) * sides + (j + 1) % sides, i * sides + (j + 1) % sides
    faces = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return xyz, faces.astype(np.uint32)


def test_a_mesh_encodes_as_the_command_encodes_a_mesh_file(cli, tmp_path):
    # (vertices, faces) and encode_file on a file with faces take the mesh
    # path of `dbss encode`: the input's own control mesh, genus kept.
    xyz, faces = _torus_mesh()
    off = tmp_path / "torus.off"
    with open(off, "w") as f:
        f.write(f"OFF\n{len(xyz)} {len(faces)} 0\n")
        np.savetxt(f, xyz, fmt="%.9g")
        np.savetxt(f, np.hstack([np.full((len(faces), 1), 3), faces]), fmt="%d")
    out = tmp_path / "cli.dbss"
    cli("encode", off, "-o", out, "--levels", 2)
    data, stats = dbss.encode((xyz, faces), levels=2, source_name="torus.off", return_stats=True)
    assert data == out.read_bytes()
    assert stats["input"] == "mesh" and stats["mesh"]["genus"] == 1 and stats["mesh"]["components"] == 1
    py_out = tmp_path / "py.dbss"
    assert dbss.encode_file(off, py_out, levels=2)["mesh"]["genus"] == 1
    assert py_out.read_bytes() == out.read_bytes()
    # input="points" reconstructs from the vertices, as --input points does.
    cli("encode", off, "-o", out, "--levels", 1, "--input", "points")
    assert dbss.encode((xyz, faces), levels=1, input="points", source_name="torus.off") == out.read_bytes()
    with pytest.raises(ValueError, match="names vertex"):
        dbss.encode((xyz, np.array([[0, 1, len(xyz)]], np.uint32)))
