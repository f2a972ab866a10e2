#!/usr/bin/env bash
# Long channels from periodic cells (docs/linear.md, "Channels of 10^5 to 10^6 grains").
#
#   bench/linear/tiled_channels.sh validate   five 2000-grain cells, each stacked 5 times (10^4-grain
#                                             channels), on the grid of the shipped driven table,
#                                             compared point by point with that table (five directly
#                                             prepared 10^4-grain channels): about 3 min on one core
#   bench/linear/tiled_channels.sh long       the 10^6-grain channels of data/scenes/long_w3.toml, one
#                                             member table each (about 11 GB and 15 min per member),
#                                             merged, and compared with the shipped long-wavelength
#                                             table: about 1.5 h on one core
# WORK=DIR keeps the packings and tables there (default: a new temporary folder, kept); BUILD=DIR picks
# the build (default build). Units: dimensionless (docs/physics.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${BUILD:-$root/build}
sedwave=$build/bin/sedwave
work=${WORK:-$(mktemp -d /tmp/sedwave-tiled.XXXXXX)}
mkdir -p "$work"
compare() { SEDWAVE=$sedwave "$root/bench/table/compare_tables.sh" "$@"; }
echo "# work folder: $work"

case ${1:-} in
  validate)
    # The field scene with the column replaced by 5 copies of a 2000-grain cell; the same grid.
    "$root/bench/linear/stacked_field_scene.sh" 10000 > "$work/tiled2k.toml"
    sed -e 's/^scene = .*/scene = "tiled2k.toml"/' "$root/data/scenes/field_w3_driven.toml" > "$work/tiled2k_grid.toml"
    start=$(date +%s)
    "$sedwave" table "$work/tiled2k_grid.toml" --engine linear --packing "$work/tiled2k.packing.h5" \
        --out "$work/tiled2k.h5" --quiet
    echo "# 5 cells prepared, tiled and solved at 273 points in $(( $(date +%s) - start )) s"
    echo "# A = shipped direct 10^4-grain channels, B = tiled 2000-grain cells (rows gamma_hat = 1, 100)"
    compare "$root/data/tables/field_w3_driven.h5" "$work/tiled2k.h5" 1,100
    ;;
  long)
    for k in 0 1 2 3 4; do
      start=$(date +%s)
      "$sedwave" table "$root/data/scenes/long_w3_grid.toml" --engine linear --member $k \
          --packing "$work/long_packing.h5" --out "$work/long.member$k.h5" --quiet
      echo "# member $k: $(( $(date +%s) - start )) s"
    done
    rm -f "$work/long_w3.h5"
    "$sedwave" merge "$work"/long.member{0,1,2,3,4}.h5 --out "$work/long_w3.h5"
    "$sedwave" show "$work/long_w3.h5"
    echo "# A = long-wavelength limit of the shipped 10^4-grain packings, B = driven 10^6-grain channels"
    compare "$root/data/tables/field_w3_long_wavelength.h5" "$work/long_w3.h5" 0.01,1,10,100,1000
    ;;
  *) echo "usage: $0 validate|long" >&2; exit 2 ;;
esac
