#!/usr/bin/env bash
# Example 06: a driven table on two MPI ranks.
#
# `sedwave table` fills a grid of (omega_hat, gamma_hat) points with driven channel runs; under
# `mpirun -np P` the points are shared out by a task farm (rank 0 hands out points and computes
# too; docs/tables.md, "The task farm"). Each point is one run of examples/03, so the table's
# values do not depend on how many ranks computed them: here they must equal the shipped table
# (data/tables/thesis_w3_small.h5, made from the same packing) at the same points.
#
#   examples/06-mpi-table/run.sh [SEDWAVE [OUT]]      (MPIRUN=... to choose the launcher)
source "$(dirname "$0")/../common.sh"

step "A grid file: three frequencies at one damping"
# The grid names its scene (here by absolute path: the scene stays in data/scenes/) and the two
# axes, as lists or as { from, to, points } (log-spaced); docs/tables.md, "The grid file".
cat > grid.toml <<TOML
scene = "$DATA/scenes/table_small_scene.toml"
omega_hat = [0.2, 0.4, 0.8]
gamma_hat = [0.3]
TOML
cat grid.toml | sed "s|$DATA|data|"

step "Fill it on two ranks"
# Every point is journalled (grid.h5.journal) as soon as it is finished, then written into the
# HDF5 table; the progress lines say which rank group computed it.
run 0 "$MPIRUN" -np 2 "$SEDWAVE" table grid.toml --packing "$DATA/tables/thesis_w3_small.packing.h5" \
    --out table.h5 | tee table.log
check "the farm ran on 2 ranks" "'on 2 rank(s)' in open('table.log').read()"
check "all 3 points are ok" "open('table.log').read().count(': ok ') == 3"

step "The table as CSV, beside the shipped one"
"$SEDWAVE" show --values-only table.h5 | tee ours.csv
"$SEDWAVE" show --values-only "$DATA/tables/thesis_w3_small.h5" > shipped.csv
# Each point must equal the shipped table's to a tenth of its own sigma.
python3 - <<'PY' | tee -a "$OUT/results.txt"
import csv
key = lambda r: (round(float(r['omega_hat']), 9), round(float(r['gamma_hat']), 9))
ours = {key(r): r for r in csv.DictReader(open('ours.csv'))}
shipped = {key(r): r for r in csv.DictReader(open('shipped.csv'))}
for k, r in sorted(ours.items()):
    s = shipped[k]
    for q in ('alpha_hat', 'c_hat'):
        d = abs(float(r[q]) - float(s[q])) / float(s['sigma_' + q])
        print(f"{q}_at_{k[0]:g}  {float(r[q]):.6f}")
        print(f"distance_{q}_at_{k[0]:g}_in_sigma  {d:.4f}")
PY
check "every value within sigma/10 of the shipped table" \
      "all(float(l.split()[1]) < 0.1 for l in open('results.txt') if l.startswith('distance_'))"
finish
