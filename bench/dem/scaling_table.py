#!/usr/bin/env python3
"""Tables of bench/dem/device_scaling.sh's raw numbers (one key=value line per run).

Usage: scaling_table.py raw.txt
Prints markdown: per (packing, ranks) the median time per step of every code over its passes, the
step's split (mean over ranks, ms: force / neighbour / communication), the halo volume and the
per-rank peak memory (min / median / max, MB); then the parallel efficiencies: strong scaling
t(1) / (p t(p)) on one packing, weak scaling t(1 rank, 15 625 grains) / t(p ranks, 15 625 p grains).
"""
import statistics
import sys
from collections import defaultdict


def parse(path):
    runs = []
    with open(path) as f:
        for line in f:
            fields = dict(kv.split("=", 1) for kv in line.split() if "=" in kv)
            if "ms_per_step" in fields:
                runs.append(fields)
    return runs


def mean_part(value):
    """'mean/max' -> mean."""
    return float(value.split("/")[0])


def main(path):
    runs = parse(path)
    groups = defaultdict(list)
    for r in runs:
        groups[(r["packing"], int(r["ranks"]), r["build"])].append(r)
    builds = sorted({b for (_, _, b) in groups}, key=lambda b: (b == "lmp", b))
    configs = sorted({(p, n) for (p, n, _) in groups}, key=lambda c: (c[0].split("_")[0], int(groups_grains(groups, c)), c[1]))

    def median(config, build, key, part=float):
        rs = groups.get((config[0], config[1], build), [])
        values = [part(r[key]) for r in rs if key in r]
        return statistics.median(values) if values else None

    print("| packing | grains | ranks | code | runs | ms/step | force | neighbour | communication | halo KB/step | peak MB per rank (min/median/max) | / LAMMPS |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for c in configs:
        lammps = median(c, "lmp", "ms_per_step")
        for b in builds:
            rs = groups.get((c[0], c[1], b), [])
            if not rs:
                continue
            t = median(c, b, "ms_per_step")
            split = [median(c, b, k, mean_part) for k in ("force_ms", "neighbour_ms", "communication_ms")]
            halo = median(c, b, "halo_bytes_per_step")
            mem = [median(c, b, k) for k in ("peak_rss_mb_min", "peak_rss_mb_median", "peak_rss_mb_max")]
            ratio = f"{t / lammps:.3f}" if lammps and b != "lmp" else ""
            cells = [f"{x:.3f}" if x is not None else "" for x in split]
            cells.append(f"{halo / 1024:.1f}" if halo is not None else "")
            cells.append("/".join(f"{x:.0f}" if x is not None else "?" for x in mem))
            print(f"| {c[0]} | {rs[0]['grains']} | {c[1]} | {b} | {len(rs)} | {t:.3f} | " + " | ".join(cells) + f" | {ratio} |")

    print()
    print("| series | code | " + " | ".join(f"{p} ranks" for p in (1, 2, 4, 8, 16)) + " |")
    print("|---|---|" + "---|" * 5)
    for series, packing_of in (("strong 5e4", lambda p: "strong_5e4"), ("strong 2.5e5", lambda p: "weak_16"),
                               ("strong 1e7", lambda p: "strong_1e7"), ("weak 15625/rank", lambda p: f"weak_{p}")):
        for b in builds:
            base = median((packing_of(1) if series.startswith("weak") else packing_of(1), 1), b, "ms_per_step")
            cells = []
            for p in (1, 2, 4, 8, 16):
                t = median((packing_of(p), p), b, "ms_per_step")
                if t is None or base is None:
                    cells.append("")
                elif series.startswith("weak"):
                    cells.append(f"{100 * base / t:.0f} %")
                else:
                    cells.append(f"{100 * base / (p * t):.0f} %")
            print(f"| {series} | {b} | " + " | ".join(cells) + " |")


def groups_grains(groups, config):
    for (p, n, _), rs in groups.items():
        if (p, n) == config:
            return rs[0]["grains"]
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: scaling_table.py raw.txt")
    main(sys.argv[1])
