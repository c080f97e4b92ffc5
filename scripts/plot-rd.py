#!/usr/bin/env python3
"""Draws bench/rd_bench's CSV: one PNG per shape, error against bytes on
log-log axes, a line per method (dbss through its levels, each peer through
its Draco quantizations).  Needs Debian's python3-matplotlib.

usage: plot-rd.py RD.csv [OUT_DIR]   (writes OUT_DIR/rd-SHAPE.png, default: beside the CSV)
"""
import csv
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {"dbss": ("tab:blue", "o"), "advancing front": ("tab:orange", "s"), "Poisson": ("tab:green", "^")}


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    path = sys.argv[1]
    out_dir = sys.argv[2] if len(sys.argv) == 3 else os.path.dirname(os.path.abspath(path))
    shapes = OrderedDict()  # shape -> method -> [(bytes, error, setting)]
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            shapes.setdefault(row["shape"], OrderedDict()).setdefault(row["method"], []).append(
                (int(row["bytes"]), float(row["error"]), row["setting"]))
    os.makedirs(out_dir, exist_ok=True)
    for shape, methods in shapes.items():
        fig, ax = plt.subplots(figsize=(5.5, 4), dpi=100)
        for method, points in methods.items():
            if method != "dbss":
                points = sorted(points)  # by bytes: coarse quantization first
            color, marker = STYLE.get(method, (None, "x"))
            ax.plot([p[0] / 1000 for p in points], [p[1] for p in points], marker=marker, color=color, label=method)
            for b, e, setting in points:
                ax.annotate(setting.replace("qp ", ""), (b / 1000, e), textcoords="offset points", xytext=(3, 3),
                            fontsize=7, color=color)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("KB (dbss: prefix that decodes the level; peers: Draco file)")
        ax.set_ylabel("mean two-sided error / diagonal")
        ax.set_title(f"{shape}: error against the true mesh")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        out = os.path.join(out_dir, f"rd-{shape}.png")
        fig.savefig(out)
        plt.close(fig)
        print(f"plot-rd: {out}")


if __name__ == "__main__":
    main()
