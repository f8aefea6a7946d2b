"""Compares two swell output folders bit for bit (scripts/bitwise): the checkpoint, the last
snapshot and the gauge CSVs. Prints one line; exit 1 if anything differs."""
import glob
import os
import sys

import h5py
import numpy as np


def datasets(path):
    out = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fiu":
            out[name] = obj[()]

    with h5py.File(path, "r") as f:
        f.visititems(visit)
    return out


def main():
    a, b, tag = sys.argv[1:4]
    pairs = [("checkpoint.h5", "checkpoint.h5")]
    last = [sorted(glob.glob(os.path.join(d, "snapshots", "*.h5")))[-1:] for d in (a, b)]
    differ, count = [], 0
    if last[0] and last[1]:
        pairs.append(tuple(os.path.relpath(p[0], d) for p, d in zip(last, (a, b))))
    if bool(last[0]) != bool(last[1]):
        differ.append("snapshots written by one run only")
    for fa_name, fb_name in pairs:
        f = fa_name if fa_name == fb_name else fa_name + " / " + fb_name
        if fa_name != fb_name:
            differ.append("last snapshot at another step: " + f)
            continue
        da, db = datasets(os.path.join(a, fa_name)), datasets(os.path.join(b, fb_name))
        if set(da) != set(db):
            differ.append(f + ": dataset names")
        for k in sorted(set(da) & set(db)):
            count += 1
            if da[k].shape != db[k].shape or not np.array_equal(da[k], db[k], equal_nan=True):
                differ.append(f + ":" + k)
    csvs = sorted(os.path.basename(p) for p in glob.glob(os.path.join(a, "gauges*.csv")))
    for c in csvs:
        with open(os.path.join(a, c), "rb") as fa, open(os.path.join(b, c), "rb") as fb:
            if fa.read() != fb.read():
                differ.append(c)
    verdict = "same bits" if not differ else "DIFFER: " + ", ".join(differ[:6])
    print(f"{tag}: {count} datasets, {len(csvs)} gauge files: {verdict}")
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
