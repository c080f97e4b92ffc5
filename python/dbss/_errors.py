"""dbss errors as Python exceptions.

Every error the C++ codec reports carries a pinned code (spec/dbss-format.md,
`dbss::ErrorCode`) and, when it is about a byte of the input, that byte's
offset.  Each code has its own subclass of :class:`Error`, e.g.
``ChecksumMismatchError`` or ``TruncatedError``; ``InvalidArgumentError`` is
also a ``ValueError`` and ``IoError`` an ``OSError``.
"""


class Error(Exception):
    """A dbss error.

    Attributes: ``code`` (the code's name, e.g. ``"checksum_mismatch"``),
    ``code_value`` (its pinned number), ``offset`` (byte offset in the input,
    or None) and ``message``.
    """

    code = None
    code_value = None

    def __init__(self, message, offset=None):
        super().__init__(message)
        self.message = message
        self.offset = offset

    def __str__(self):
        where = "" if self.offset is None else f" at byte {self.offset}"
        return f"{self.code}{where}: {self.message}"


class PartialFileWarning(UserWarning):
    """A damaged or truncated file was decoded to its finest verified level."""


# Extra Python bases for codes that match a built-in exception.
_EXTRA_BASES = {"invalid_argument": (ValueError,), "io": (OSError,)}
_BY_VALUE = {}


def _class_name(code):
    return "".join(part.capitalize() for part in code.split("_")) + "Error"


def _make_classes(codes):
    classes = {}
    for name, value in sorted(codes.items(), key=lambda kv: kv[1]):
        if value == 0:
            continue  # ok
        cls = type(_class_name(name), (Error,) + _EXTRA_BASES.get(name, ()),
                   {"code": name, "code_value": value,
                    "__doc__": f"dbss error code {value} ({name}).",
                    "__module__": "dbss"})
        classes[cls.__name__] = cls
        _BY_VALUE[value] = cls
    return classes


def from_status(value, name, offset, message):
    """The exception instance for a C++ Status (called by the module)."""
    cls = _BY_VALUE.get(value)
    if cls is None:  # a code newer than this package: still an Error
        cls = type(_class_name(name), (Error,), {"code": name, "code_value": value})
    return cls(message, offset)
