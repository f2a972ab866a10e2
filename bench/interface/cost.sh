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
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
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
