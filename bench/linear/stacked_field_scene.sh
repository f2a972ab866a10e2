#!/usr/bin/env bash
# Prints data/scenes/field_w3.toml with its column stacked from a periodic 2000-grain cell
# (docs/linear.md, "Channels of 10^5 to 10^6 grains"): GRAINS flow grains, MEMBERS packings (seeds
# 1, 2, ...; default the scene's 5). The benches that compare stacked with direct channels use it.
#
#   bench/linear/stacked_field_scene.sh GRAINS [MEMBERS] > scene.toml
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
grains=${1:?usage: $0 GRAINS [MEMBERS]}
members=${2:-5}
sed -e "s/^grains = 10000/grains = $grains/" -e "s/^ensemble = 5/ensemble = $members/" \
    -e 's/^seed = 1$/seed = 1\n\n[geometry.periodic_cell]\ngrains = 2000/' "$root/data/scenes/field_w3.toml"
