#!/usr/bin/env python3
"""Packing-to-packing spread of the shipped ensemble tables, and the ensemble a target needs.

A table made over n packings stores the standard error of the mean, sigma = s / sqrt(n), where s is
the spread of one packing's alpha_hat or c_hat about the ensemble mean. This prints the quartiles of
the relative spread s / value over each table's ok points (s = sigma sqrt(n), n from the table's
`packings` attribute) and the packings n = (s / eps)^2 that bring the table's relative sigma down
to eps = 1 % and 0.3 %.

Usage: bench/table/packing_spread.py [build/bin/sedwave] (run from the repository root)
"""
import csv
import io
import math
import statistics
import subprocess
import sys

SEDWAVE = sys.argv[1] if len(sys.argv) > 1 else "build/bin/sedwave"
TABLES = ["data/tables/field_w3_long_wavelength.h5", "data/tables/field_w3_driven.h5",
          "data/tables/long_w3.h5", "data/tables/linear_w3.h5"]


def read(table):
    text = subprocess.run([SEDWAVE, "show", table], check=True, capture_output=True, text=True).stdout
    sigma_line = next(line for line in text.splitlines() if line.startswith("# sigma:"))
    words = sigma_line.split()
    packings = int(words[words.index("over") + 1])
    rows = csv.DictReader(io.StringIO("\n".join(l for l in text.splitlines() if not l.startswith("#"))))
    return packings, [r for r in rows if r["status"] == "ok"]


def quartiles(values):
    q = statistics.quantiles(values, n=4)
    return q[0], q[1], q[2]


print(f"{'table':<34} {'n':>2} {'points':>6}  {'s/alpha_hat (25/50/75 %)':>26}  {'s/c_hat (25/50/75 %)':>22}"
      f"  {'n for c_hat to 1 % / 0.3 % (median s)':>38}")
for table in TABLES:
    n, rows = read(table)
    rel_a = [float(r["sigma_alpha_hat"]) / float(r["alpha_hat"]) * math.sqrt(n) for r in rows]
    rel_c = [float(r["sigma_c_hat"]) / float(r["c_hat"]) * math.sqrt(n) for r in rows]
    qa, qc = quartiles(rel_a), quartiles(rel_c)
    need = [math.ceil((qc[1] / eps) ** 2) for eps in (0.01, 0.003)]
    print(f"{table.split('/')[-1]:<34} {n:>2} {len(rows):>6}  "
          f"{' / '.join(f'{100 * q:.1f}' for q in qa):>24} %  {' / '.join(f'{100 * q:.1f}' for q in qc):>20} %"
          f"  {need[0]:>18} / {need[1]:<18}")
