#!/usr/bin/env python3
"""Largest difference between `lagrange simulate`'s CSV and an FMU importer's result CSV.

    python3 bench/fmu_compare_csv.py simulate.csv importer.csv

Rows are matched by time (simulate's `t`, the importer's `time`, within 1e-9); every column both
files have is compared. Prints the run's largest |importer - simulate|, its column, and the number
of rows matched. Used by bench/fmu_importers.sh (docs/fmu.md).
"""
import csv
import sys


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = [h.strip().strip('"') for h in rows[0]]
    return header, [[float(x) for x in r] for r in rows[1:] if r]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    ref_header, ref = read(sys.argv[1])
    header, rows = read(sys.argv[2])
    t_ref, t_imp = ref_header.index("t"), header.index("time")
    common = [(ref_header.index(n), header.index(n), n) for n in header if n in ref_header]
    by_time = {round(r[t_ref], 9): r for r in ref}
    worst, where, matched = 0.0, "-", 0
    per_column = {}
    for row in rows:
        r = by_time.get(round(row[t_imp], 9))
        if r is None:
            continue
        matched += 1
        for i_ref, i_imp, n in common:
            d = abs(row[i_imp] - r[i_ref])
            per_column[n] = max(per_column.get(n, 0.0), d)
            if not d <= worst:
                worst, where = d, n
    print(f"  {sys.argv[2].rsplit('/', 1)[-1]}: {matched} of {len(rows)} rows on simulate's grid, "
          f"{len(common)} columns; largest |importer - simulate| {worst:.3g} ({where})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
