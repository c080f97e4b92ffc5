"""Encodes every point or mesh file of a folder on Dask, one task per file.

    python3 -m dbss.batch INPUT_DIR OUTPUT_DIR [--scheduler ADDRESS]
                          [--workers N] [--threads T] [encode options]

Without --scheduler a local cluster runs on this machine (--workers
processes, one thread each); with it, the tasks go to a running Dask
scheduler whose workers can ``import dbss`` and see both folders at the
same paths.  INPUT_DIR is searched
recursively for .ply, .obj, .off, .xyz and .stl files; INPUT_DIR/a/b.ply is
encoded to OUTPUT_DIR/a/b.dbss exactly as ``dbss encode INPUT_DIR/a/b.ply -o
OUTPUT_DIR/a/b.dbss [encode options]`` would, and written atomically.  A
file that fails is reported with its error and the others go on.

A re-run skips a file whose output is already there from the same input
bytes, options and encoder version.  The .dbss format has no field for the
options as given (its `meta` chunk records the resolved parameters, e.g. the
grid chosen), so they are recorded in a sidecar, OUTPUT_DIR/dbss-batch.json,
with the input's and the output's SHA-256.

Exit status: 0 every file encoded or skipped, 1 some file failed, 2 bad
usage.
"""

import argparse
import hashlib
import json
import os
import pathlib
import sys
import tempfile
import time

MANIFEST = "dbss-batch.json"
EXTENSIONS = (".ply", ".obj", ".off", ".xyz", ".stl")

# The options of `dbss encode` that change the output, as (flag, keyword, takes a value).
ENCODE_FLAGS = [
    ("--levels", "levels", True), ("--error", "error", True), ("--step", "step", True),
    ("--grid", "grid", True), ("--grid-shift", "grid_shift", True), ("--control-faces", "control_faces", True),
    ("--control-bits", "control_bits", True), ("--effort", "effort", True),
    ("--surface", "surface", True), ("--keep-outliers", "keep_outliers", False),
    ("--crease-angle", "crease_angle", True),
    ("--strict", "strict", False),
]


def encode_task(src, dst, options, threads):
    """One file (runs on a worker): a result dict, never an exception, so one
    bad file cannot fail the batch."""
    import dbss  # on the worker

    start = time.perf_counter()
    try:
        stats = dbss.encode_file(src, dst, threads=threads, **options)
    except Exception as e:  # dbss.Error for bad input (its text names the code); anything else too
        error = str(e) if isinstance(e, dbss.Error) else f"{type(e).__name__}: {e}"
        return {"ok": False, "error": error, "seconds": time.perf_counter() - start}
    return {"ok": True, "bytes_out": stats["bytes"], "output_sha256": sha256(dst),
            "warnings": [w["code"] for w in stats["warnings"]], "seconds": time.perf_counter() - start}


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def find_inputs(root):
    """Supported files under `root`, sorted, as paths relative to it."""
    found = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames.sort()
        for name in filenames:
            if name.lower().endswith(EXTENSIONS):
                found.append(pathlib.Path(dirpath, name).relative_to(root))
    return sorted(found)


def read_manifest(out_dir):
    try:
        with open(out_dir / MANIFEST) as f:
            data = json.load(f)
        return data if isinstance(data, dict) else {}
    except (OSError, ValueError):
        return {}  # none yet, or unreadable: encode everything


def write_manifest(out_dir, manifest):
    """Atomically: a temporary file renamed over the old one."""
    fd, tmp = tempfile.mkstemp(prefix=".dbss-batch-", dir=out_dir)
    try:
        os.fchmod(fd, 0o644)
        with os.fdopen(fd, "w") as f:
            json.dump(manifest, f, indent=1, sort_keys=True)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, out_dir / MANIFEST)
    except BaseException:
        os.unlink(tmp)
        raise


class Progress:
    """A bar on stderr when it is a terminal; nothing otherwise."""

    def __init__(self, total):
        self.total, self.done, self.on = total, 0, sys.stderr.isatty() and total > 0

    def step(self, name):
        self.done += 1
        if self.on:
            width = 30
            filled = width * self.done // self.total
            sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} {name[-40:]:<40}")
            sys.stderr.flush()

    def message(self, text):
        """A line above the bar (the bar is redrawn by the next step)."""
        sys.stderr.write(("\r\033[K" if self.on else "") + text + "\n")

    def close(self):
        if self.on:
            sys.stderr.write("\n")


def parse_args(argv):
    p = argparse.ArgumentParser(prog="python3 -m dbss.batch", description=__doc__.split("\n\n")[0],
                                epilog="Encode options are those of `dbss encode` (see `dbss encode --help`).")
    p.add_argument("input_dir", type=pathlib.Path)
    p.add_argument("output_dir", type=pathlib.Path)
    p.add_argument("--scheduler", metavar="ADDRESS", help="a running Dask scheduler, e.g. tcp://host:8786")
    p.add_argument("--workers", type=int, default=0, help="local cluster: worker processes (default: the cores, at most the files)")
    p.add_argument("--threads", type=int, default=1, help="encoder threads per file (default 1)")
    p.add_argument("--force", action="store_true", help="encode even files already encoded with the same options")
    for flag, key, value in ENCODE_FLAGS:
        if value:
            p.add_argument(flag, dest=key, metavar=key.upper())
        else:
            p.add_argument(flag, dest=key, action="store_true", default=None)
    args = p.parse_args(argv)
    # Absolute, so workers started elsewhere find the files (on a shared file system).
    args.input_dir, args.output_dir = args.input_dir.absolute(), args.output_dir.absolute()
    options = {key: getattr(args, key) for _, key, _ in ENCODE_FLAGS if getattr(args, key) is not None}
    return p, args, options


def summary(rows, out):
    """The table at the end: one row per file, then the totals."""
    w = max([len("file")] + [len(r["file"]) for r in rows])
    out.write(f"\n{'file':<{w}}  {'status':<8} {'bytes in':>12} {'bytes out':>12} {'seconds':>8}  error\n")
    for r in rows:
        out.write(f"{r['file']:<{w}}  {r['status']:<8} {r['bytes_in']:>12} {r.get('bytes_out', '-'):>12} "
                  f"{r.get('seconds', 0):>8.2f}  {r.get('error', '')}\n")
    count = {s: sum(r["status"] == s for r in rows) for s in ("encoded", "skipped", "failed")}
    bytes_in = sum(r["bytes_in"] for r in rows)
    bytes_out = sum(r.get("bytes_out", 0) for r in rows)
    out.write(f"{len(rows)} files: {count['encoded']} encoded, {count['skipped']} skipped, {count['failed']} failed; "
              f"{bytes_in} bytes in, {bytes_out} bytes out\n")
    return count


def main(argv=None):
    parser, args, options = parse_args(argv)
    import dbss

    try:
        dbss.check_options(threads=args.threads, **options)
    except (TypeError, ValueError) as e:
        parser.error(str(e))
    if not args.input_dir.is_dir():
        parser.error(f"{args.input_dir}: not a directory")
    args.output_dir.mkdir(parents=True, exist_ok=True)
    inputs = find_inputs(args.input_dir)
    # What decides whether an output can be reused.
    # "defaults" changes when the encoder's defaults do under one version
    # (2: creases on at 30 degrees), so outputs written under the old
    # defaults are not taken for new ones.
    key = json.dumps({"options": options, "encoder": dbss.__version__, "defaults": 2}, sort_keys=True)
    manifest = read_manifest(args.output_dir)

    rows, todo, owner = [], [], {}
    for rel in inputs:
        src, dst_rel = args.input_dir / rel, rel.with_suffix(".dbss").as_posix()
        row = {"file": rel.as_posix(), "bytes_in": src.stat().st_size}
        rows.append(row)
        if dst_rel in owner:  # a.ply and a.xyz would both be a.dbss
            row.update(status="failed", error=f"same output {dst_rel} as {owner[dst_rel]}")
            continue
        owner[dst_rel] = row["file"]
        dst = args.output_dir / dst_rel
        row.update(src=str(src), dst=str(dst), out=dst_rel, input_sha256=sha256(src))
        seen = manifest.get(dst_rel)
        if (not args.force and seen and dst.is_file() and seen.get("key") == key
                and seen.get("input_sha256") == row["input_sha256"] and seen.get("output_sha256") == sha256(dst)):
            row.update(status="skipped", bytes_out=dst.stat().st_size)
            continue
        dst.parent.mkdir(parents=True, exist_ok=True)
        todo.append(row)

    if todo:
        from dask.distributed import Client, LocalCluster, as_completed

        cluster = None
        if args.scheduler:
            client = Client(args.scheduler)
        else:
            workers = args.workers or max(1, min(os.cpu_count() or 1, len(todo)))
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client = Client(cluster)
        try:
            futures = {client.submit(encode_task, r["src"], r["dst"], options, args.threads, pure=False,
                                     key=f"dbss-encode-{i}-{r['out']}"): r for i, r in enumerate(todo)}
            progress = Progress(len(futures))
            for future in as_completed(futures):
                row = futures[future]
                try:
                    result = future.result()
                except Exception as e:  # the worker died (a crash) or was lost
                    result = {"ok": False, "error": f"{type(e).__name__}: {e}"}
                row["seconds"] = result.get("seconds", 0)
                if result["ok"]:
                    row.update(status="encoded", bytes_out=result["bytes_out"])
                    manifest[row["out"]] = {"key": key, "input": row["file"], "input_sha256": row["input_sha256"],
                                            "output_sha256": result["output_sha256"]}
                    write_manifest(args.output_dir, manifest)
                else:
                    row.update(status="failed", error=result["error"])
                    progress.message(f"dbss.batch: {row['src']}: {result['error']}")
                progress.step(row["file"])
            progress.close()
        finally:
            client.close()
            if cluster is not None:
                cluster.close()

    count = summary(rows, sys.stdout)
    return 1 if count["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
