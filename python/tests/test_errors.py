"""Bad input raises the right exception, with the spec's code and byte offset."""
import threading
import time
import warnings

import numpy as np
import pytest

import dbss


def chunk(data, kind, nth=0):
    """(offset, length) of the nth chunk of `kind` in the table of contents."""
    rows = [c for c in dbss.info(data)["chunks"] if c["type"] == kind]
    return rows[nth]["offset"], rows[nth]["length"]


def test_truncated_file(encoded):
    data = encoded[1]
    cut = data[:300]
    with pytest.raises(dbss.TruncatedError) as e:
        dbss.decode(cut)
    assert e.value.code == "truncated" and e.value.code_value == 9 and e.value.offset == 300
    assert isinstance(e.value, dbss.Error)
    # Cut inside level 2: level 1 is still there, with a warning; level 2 raises.
    start, length = chunk(data, "LEVL", 1)
    cut = data[:start + length // 2]
    with pytest.warns(dbss.PartialFileWarning):
        v, _ = dbss.decode(cut)
    assert np.array_equal(v, dbss.decode(data, 1)[0])
    with pytest.raises(dbss.TruncatedError):
        dbss.decode(cut, level=2)


def test_damaged_chunk(encoded):
    data = bytearray(encoded[1])
    start, length = chunk(bytes(data), "LEVL", 1)
    data[start + length // 2] ^= 0x10
    with pytest.raises(dbss.ChecksumMismatchError) as e:
        dbss.decode(bytes(data), level=2)
    assert e.value.code == "checksum_mismatch" and e.value.code_value == 5
    assert start <= e.value.offset <= start + length + 16  # the damaged chunk, its CRC at most
    with pytest.warns(dbss.PartialFileWarning):
        v, _ = dbss.decode(bytes(data))
    assert len(v) == dbss.info(encoded[1])["level_table"][1]["vertices"]
    # The streaming decoder raises where the damage is and keeps what came before.
    d = dbss.Decoder()
    with pytest.raises(dbss.ChecksumMismatchError):
        d.push(bytes(data))
    assert d.levels_ready == 1 and isinstance(d.error, dbss.ChecksumMismatchError)
    assert np.array_equal(d.level(1)[0], dbss.decode(encoded[1], 1)[0])
    with pytest.raises(dbss.ChecksumMismatchError):
        d.level(2)
    info = dbss.info(bytes(data))
    assert info["complete"] is False and info["status"].startswith("checksum_mismatch")


def test_not_a_dbss_file():
    with pytest.raises(dbss.BadSignatureError) as e:
        dbss.decode(b"PK\x03\x04 not a dbss file at all")
    assert e.value.offset == 0 and e.value.code_value == 2
    with pytest.raises(dbss.TruncatedError) as e:
        dbss.decode(b"")
    assert e.value.offset == 0
    with pytest.raises(TypeError):
        dbss.decode("a string is not bytes")


def test_level_outside_the_file(encoded):
    with pytest.raises(ValueError, match="level 3 is not in the file"):
        dbss.decode(encoded[1], 3)
    with pytest.raises(ValueError):
        dbss.decode(encoded[1], -1)
    d = dbss.Decoder()
    d.push(encoded[1][:100])
    with pytest.raises(dbss.TruncatedError, match="no control mesh yet"):
        d.level(0)


def test_bad_input_files(tmp_path):
    with pytest.raises(dbss.IoError) as e:
        dbss.encode_file(tmp_path / "missing.xyz", tmp_path / "out.dbss")
    assert isinstance(e.value, OSError) and "missing.xyz" in str(e.value)
    bad = tmp_path / "bad.xyz"
    bad.write_text("0 0 0\n1 1 1\nnot a number\n")
    with pytest.raises(dbss.InvalidArgumentError, match="bad.xyz") as e:
        dbss.encode_file(bad, tmp_path / "out.dbss")
    assert isinstance(e.value, ValueError)
    assert not (tmp_path / "out.dbss").exists()


def test_wrong_arrays_and_options(torus_points):
    with pytest.raises(TypeError, match="float32 or float64"):
        dbss.encode(torus_points.astype(np.int32))
    with pytest.raises(ValueError, match="N x 3"):
        dbss.encode(torus_points[:, :2])
    with pytest.raises(ValueError, match="N x 3"):
        dbss.encode(torus_points.reshape(2, -1, 3))
    pts = torus_points.copy()
    pts[10, 1] = np.nan
    with pytest.raises(ValueError, match="point 10 is not finite"):
        dbss.encode(pts)
    with pytest.raises(dbss.InvalidArgumentError, match="at least 4 points"):
        dbss.encode(torus_points[:3])
    pts = torus_points.astype(np.float32)
    pts[7, 2] = 1e20  # finite in float32, past the coordinate bound
    with pytest.raises(dbss.InvalidArgumentError, match="point 7 has a coordinate that is NaN, infinite or over 1e15"):
        dbss.encode(pts)
    with pytest.raises(TypeError, match="'levlz'"):
        dbss.encode(torus_points, levlz=2)
    with pytest.raises(ValueError, match="--grid needs a whole number"):
        dbss.encode(torus_points, grid=1)
    with pytest.raises(ValueError, match="--grid-shift needs a number"):
        dbss.encode(torus_points, grid=30, grid_shift=1.5)
    with pytest.raises(ValueError, match="grid_shift moves a given grid's cells: it needs grid"):
        dbss.encode(torus_points, grid_shift=0.5)
    with pytest.raises(ValueError, match="--error needs"):
        dbss.encode(torus_points, error=0.5)
    with pytest.raises(ValueError, match="--surface needs"):
        dbss.encode(torus_points, surface="round")
    with pytest.raises(TypeError, match="not a bool"):
        dbss.encode(torus_points, levels=True)
    with pytest.raises(TypeError, match="'fast'"):
        dbss.encode_file("x.xyz", "y.dbss", fast=True)
    with pytest.raises(ValueError, match="faces"):
        dbss.encode((torus_points, np.zeros((4, 2), np.uint32)))


def test_gil_released_while_encoding(torus_points):
    # While another thread encodes, this one keeps running: the longest pause
    # it sees is far shorter than the encode (held GIL: a pause as long as it).
    done = threading.Event()
    took = []

    def work():
        t = time.perf_counter()
        dbss.encode(torus_points, levels=3)
        took.append(time.perf_counter() - t)
        done.set()

    worker = threading.Thread(target=work)
    last = time.perf_counter()
    longest = 0.0
    worker.start()
    while not done.is_set():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
    worker.join()
    assert took[0] > 0.2, "the encode is too quick for this test to tell"
    assert longest < 0.4 * took[0]
