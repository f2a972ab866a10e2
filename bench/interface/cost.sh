#!/usr/bin/env bash
# Cost of the granular-solid interface (docs/performance.md, "The granular-solid interface"):
#  1. the adaptive step against a fixed step as small as the adaptive run's smallest (the fixed step
#     a run must take to stay stable through its stiffest moment), on example 11's frictional scene;
#  2. 1000 beads on a 260 x 40 (10 400-element) plate until the front has crossed the plate three
#     times, with and without friction;
#  3. the cost per grain-step of the granular medium alone (1000 beads on a 4 x 2-element plate).
# Prints a table; every run also leaves its log under OUT.
#
#   bench/interface/cost.sh [SEDWAVE [OUT]]
#   bench/interface/cost.sh --compare OLD_SEDWAVE NEW_SEDWAVE [RUNS=5 [NEW_RUN_KEYS [OLD_RUN_KEYS]]]
# The second form runs example 11 as shipped by two builds, alternating so that a change in the
# machine's load falls on both alike, and prints each build's median wall and CPU time, its ns per
# grain-step (CPU time over steps times grains), the machine's load, and what each run reported
# (plate share, energy balance, arrival at the middle probe). NEW_RUN_KEYS, e.g.
# 'scheme = "multirate"', are appended to the scene's [run] table for the new build, OLD_RUN_KEYS for
# the old one (the same keys on both: one scheme by two builds).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
if [ "${1:-}" = --compare ]; then
  OUT=$(mktemp -d)
  trap 'rm -rf "$OUT"' EXIT
  python3 - "$ROOT/examples/11-granular-plate/scene.toml" "$OUT" "$2" "$3" "${4:-5}" "${5:-}" "${6:-}" <<'PY'
import os, re, resource, statistics, subprocess, sys, time
scene, out, old, new = sys.argv[1:5]
runs, keys, old_keys = int(sys.argv[5]), sys.argv[6], sys.argv[7]
scenes = {"old": scene, "new": scene}
for name, extra in (("new", keys), ("old", old_keys)):
    if extra:  # [run] is the scene's last table
        scenes[name] = f"{out}/{name}_scene.toml"
        with open(scenes[name], "w") as f:
            f.write(open(scene).read() + "\n" + extra + "\n")
times = {"old": [], "new": []}
reported = {}
for r in range(runs):
    for name, exe in (("old", old), ("new", new)):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        log = subprocess.run([exe, "interface", scenes[name], "--out", f"{out}/{name}{r}.h5"], check=True,
                             capture_output=True, text=True).stdout
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
        grains, steps = re.search(r"(\d+) grains .*; (\d+) steps in", log).groups()
        times[name].append((wall, cpu, int(grains) * int(steps)))
        reported[name] = (steps, re.search(r"largest share in the plate (\S+); energy balance within (\S+) of", log).groups(),
                          re.search(r"x = 0.06 m.*arrival (\S+) s", log).group(1))
print(f"{'build':6} {'wall s':>8} {'CPU s':>8} {'ns/grain-step (CPU)':>20}   (median of {runs}, alternating)")
for name in ("old", "new"):
    wall = statistics.median(t[0] for t in times[name]); cpu = statistics.median(t[1] for t in times[name])
    print(f"{name:6} {wall:8.3f} {cpu:8.3f} {cpu / times[name][0][2] * 1e9:20.0f}")
w = [statistics.median(t[i] for t in times[n]) for n in ("old", "new") for i in (0, 1)]
print(f"old / new: wall {w[0] / w[2]:.2f}x, CPU {w[1] / w[3]:.2f}x; load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
for name in ("old", "new"):
    steps, (share, balance), arrival = reported[name]
    print(f"{name}: {steps} steps, plate share {share}, energy balance within {balance}, arrival at x = 0.06 m {arrival} s"
          + (f" ({keys})" if keys and name == "new" else "") + (f" ({old_keys})" if old_keys and name == "old" else ""))
PY
  exit 0
fi
SEDWAVE=$(realpath "${1:-$ROOT/build/bin/sedwave}")
OUT=${2:-${TMPDIR:-/tmp}/sedwave-bench-interface}
mkdir -p "$OUT" && cd "$OUT"
SCENE=$ROOT/examples/11-granular-plate/scene.toml

field() { sed -n "s/.*$2 \([-0-9.e+]*\).*/\1/p" "$1" | head -1; }
steps() { sed -n 's/.* elements; \([0-9]*\) steps in \([0-9.]*\) s/\1 \2/p' "$1"; }

"$SEDWAVE" interface "$SCENE" --out adaptive.h5 > adaptive.log
read -r n_adaptive t_adaptive <<<"$(steps adaptive.log)"
smallest=$(sed -n 's/^step \(\S*\) \.\. .*/\1/p' adaptive.log)
"$SEDWAVE" interface "$SCENE" --fixed-step "$smallest" --out fixed.h5 > fixed.log
read -r n_fixed t_fixed <<<"$(steps fixed.log)"
arrival() { sed -n 's/probe at x = 0.06 m.*arrival \(\S*\) s/\1/p' "$1"; }
share() { field "$1" "largest share in the plate"; }

# 1000 beads: 20 rows of 50 on a 0.26 m plate, 1 mm elements; the front reaches the plate near
# 180 us at 1 m/s and crosses its 40 mm depth in 7.4 us at c_L.
big_scene() {
  sed -e 's/^length_x = 0.12 .*/length_x = 0.26/' -e 's/^elements_x = 120 .*/elements_x = 260/' \
      -e 's/^rows = 10$/rows = 20/' -e 's/^columns = 20$/columns = 50/' \
      -e 's/^duration = 3e-4$/duration = 2.2e-4/' -e 's/^probe_x = .*/probe_x = [0.13]/' \
      -e "s/^friction = 0.3$/friction = $1/" "$SCENE"
}
big_scene 0.3 > big_friction.toml
big_scene 0.0 > big_frictionless.toml
"$SEDWAVE" interface big_friction.toml --out big_friction.h5 > big_friction.log
"$SEDWAVE" interface big_frictionless.toml --out big_frictionless.h5 > big_frictionless.log

# The granular medium alone: 1000 beads over a plate of 8 elements, frictionless, 10 times longer
# (6000 steps) and sampled 20 times, so that setting up and writing do not count.
sed -e 's/^elements_x = 260$/elements_x = 4/' -e 's/^elements_y = 40$/elements_y = 2/' \
    -e 's/^duration = 2.2e-4$/duration = 4.4e-3/' -e 's/^output_interval = .*/output_interval = 2.2e-4/' \
    big_frictionless.toml > grains_only.toml
"$SEDWAVE" interface grains_only.toml --out grains_only.h5 > grains_only.log

printf '%-44s %10s %10s %12s %s\n' run steps seconds "us/step" "notes"
row() {  # LABEL LOG NOTES
  read -r n t <<<"$(steps "$2")"
  printf '%-44s %10s %10s %12.2f %s\n' "$1" "$n" "$t" "$(python3 -c "print($t / $n * 1e6)")" "$3"
}
row "example 11, adaptive (tolerance 0.2)" adaptive.log "arrival $(arrival adaptive.log) s, plate share $(share adaptive.log)"
row "example 11, fixed step $smallest s" fixed.log "arrival $(arrival fixed.log) s, plate share $(share fixed.log)"
row "1000 beads, 10400 elements, friction" big_friction.log "arrival $(sed -n 's/probe.*arrival \(\S*\) s/\1/p' big_friction.log) s"
row "1000 beads, 10400 elements, frictionless" big_frictionless.log "arrival $(sed -n 's/probe.*arrival \(\S*\) s/\1/p' big_frictionless.log) s"
row "1000 beads, 8 elements, frictionless" grains_only.log \
    "$(python3 -c "n, t = $(steps grains_only.log | tr ' ' ','); print(f'{t / n / 1000 * 1e9:.0f} ns per grain-step')")"
printf 'adaptive speedup over the fixed step: %.1fx in wall time (%s against %s steps)\n' \
  "$(python3 -c "print($t_fixed / $t_adaptive)")" "$n_adaptive" "$n_fixed"
