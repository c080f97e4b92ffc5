"""dbss: Displaced Butterfly Subdivision Surfaces for Python.

A thin layer over the C++ codec (the module ``dbss._dbss``): the same
encoder as ``dbss encode`` and the same decoder as ``dbss decode``, so the
bytes and the decoded floats are those of the command line.

    data = dbss.encode(points, levels=2, error=1e-4)       # bytes
    vertices, faces = dbss.decode(data)                    # float32 Vx3, uint32 Fx3
    dbss.info(data)["level_table"]                         # as `dbss info --json`

Encode options are the flags of ``dbss encode`` as keywords (``levels``,
``error``, ``step``, ``grid``, ``grid_shift``, ``control_faces``, ``control_bits``,
``effort``, ``surface``, ``keep_outliers``, ``crease_angle``, ``strict``), plus
``source_name`` (the `meta` chunk's "source") and ``threads``.  Creases
are on by default, as on the command line (``crease_angle=30``);
``crease_angle="off"`` turns them off.  They are
read by the command's own parser, so bad values raise ValueError with its
message; an unknown keyword raises TypeError.  Errors from the codec raise a
subclass of :class:`dbss.Error` carrying the code and byte offset.
"""

import os as _os

import numpy as _np

from . import _dbss
from . import _errors
from ._errors import Error, PartialFileWarning

globals().update(_errors._make_classes(_dbss.error_codes()))

__version__ = _dbss.__version__

Decoder = _dbss.Decoder
Decoder.__doc__ = """Streaming decoder: ``push(bytes)`` as bytes arrive (returns
``levels_ready``), ``levels_ready`` (finest level verified so far, -1 before
the control mesh), ``levels`` (levels the header declares, None before it),
``level(l)`` -> (vertices, faces), ``finish()`` at the end of the stream
(raises if it was cut), ``error`` (the first error, or None).  A damaged
chunk raises from ``push``; the levels verified before it stay usable."""


def _points_array(points):
    """An N x 3 C-contiguous float32 array from the caller's points, and the
    faces of a (vertices, faces) mesh (None for points)."""
    faces = None
    if isinstance(points, tuple) and len(points) == 2:
        vertices, faces = points
        faces = _np.asarray(faces)
        if faces.ndim != 2 or faces.shape[1] != 3 or faces.dtype.kind not in "iu":
            raise ValueError(f"faces must be an F x 3 integer array, got shape {faces.shape} of {faces.dtype}")
        points = vertices
    arr = _np.asarray(points)
    if arr.dtype not in (_np.float32, _np.float64):
        raise TypeError(f"points must be float32 or float64, got {arr.dtype}")
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"points must be an N x 3 array, got shape {arr.shape}")
    # float64 rounds to the nearest float32, as the command reads text.
    return _np.ascontiguousarray(arr, dtype=_np.float32), faces


def encode(points, *, levels=None, error=None, return_stats=False, **options):
    """Encodes points (N x 3 float32/float64) or a (vertices, faces) mesh
    (faces F x 3 integers; encoded as ``dbss encode`` encodes a mesh file,
    unless ``input="points"``) and returns the .dbss bytes; with
    ``return_stats=True``, ``(bytes, stats)``.  ``levels``: a number 0..8 or
    "auto" (default, as the command); ``error``: relative to the diagonal
    (default 1e-4).  The GIL is released while encoding."""
    options.update(levels=levels, error=error)
    arr, faces = _points_array(points)
    return _dbss.encode(arr, options, bool(return_stats), faces)


def encode_file(path, out_path, **options):
    """Encodes a .ply/.obj/.off/.xyz/.stl/.glb/.gltf file into ``out_path``
    (written atomically) exactly as ``dbss encode path -o out_path`` with the
    same options (a file with faces as a mesh unless ``input="points"``),
    and returns the statistics per stage and level."""
    return _dbss.encode_file(_os.fspath(path), _os.fspath(out_path), options)


def check_options(**options):
    """Raises TypeError/ValueError for options encode() would refuse."""
    _dbss.check_options(options)


def decode(data, level=None):
    """Decodes ``level`` (default: the finest in the file) of a .dbss file's
    bytes to ``(vertices float32 V x 3, faces uint32 F x 3)``.  A damaged or
    truncated file gives its finest verified level with a
    :class:`PartialFileWarning` (or raises when ``level`` was not
    verified)."""
    return _dbss.decode(data, level)


def info(data, *, hashes=False):
    """The fields of ``dbss info --json`` as a dict, for bytes or a path.
    ``hashes=True`` adds each level's "fnv1a64" (as ``--hashes``)."""
    name = None
    if isinstance(data, (str, _os.PathLike)):
        name = _os.fspath(data)
        with open(name, "rb") as f:
            data = f.read()
    return _dbss.info(data, name, bool(hashes))
