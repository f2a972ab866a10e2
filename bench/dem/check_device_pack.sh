#!/usr/bin/env bash
# Checks a pack made by bench/dem/pack_for_device.sh here, as if on a bare machine: in a private
# mount namespace (root needed) the system's Open MPI, PMIx, LAMMPS and every library the pack
# carries are hidden (bind-mounted over with /dev/null or an empty folder), Python 3.11 too (LAMMPS
# links libpython but must not start it), and run.sh runs from an empty environment on two ranks at
# most, with short runs.
#
# Usage: bench/dem/check_device_pack.sh [pack-dir]   (default .device); OUT (default a temp folder)
# Inside, the scaling script's own table step fails (the hidden libraries include some that this
# machine's python3 needs); the table is made afterwards, outside.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
CARRY=$(cd "${1:-$ROOT/.device}" && pwd)
TREE=$CARRY.tree
OUT=${OUT:-$(mktemp -d /tmp/sedwave-pack-check.XXXXXX)}
ARCH=x86_64-linux-gnu

hide=()
for f in "$TREE"/lib/*; do
  for dir in /usr/lib/$ARCH /lib/$ARCH; do
    [[ -e $dir/$(basename "$f") ]] && hide+=("$(realpath "$dir/$(basename "$f")")")
  done
done
for f in /usr/bin/lmp /usr/bin/orterun /usr/bin/orted /usr/bin/ompi_info "$(realpath /usr/bin/lmp)"; do
  [[ -e $f ]] && hide+=("$(realpath "$f")")
done
mapfile -t hide < <(printf '%s\n' "${hide[@]}" | sort -u)
empty_dirs=(/usr/lib/$ARCH/openmpi /usr/lib/$ARCH/pmix2 /usr/share/openmpi /etc/openmpi /usr/lib/python3.11)

script=$(mktemp /tmp/sedwave-pack-check.XXXXXX.sh)
{
  echo 'set -e'
  echo 'empty=$(mktemp -d)'
  for f in "${hide[@]}"; do echo "mount --bind /dev/null '$f'"; done
  for d in "${empty_dirs[@]}"; do [[ -d $d ]] && echo "mount --bind \"\$empty\" '$d'"; done
  echo "if command -v lmp >/dev/null && lmp -h >/dev/null 2>&1; then echo 'system LAMMPS still visible' >&2; exit 1; fi"
  echo "env -i PATH=/usr/bin:/bin HOME=/tmp OUT='$OUT' BUDGET_S=\${BUDGET_S:-240} PASSES=1 RANKS='${RANKS:-1 2}' STEPS_DIVISOR=\${STEPS_DIVISOR:-20} PACK_TREE=/tmp/sedwave-pack-check-tree bash '$CARRY/run.sh'"
} >"$script"
echo "hiding ${#hide[@]} system files and ${#empty_dirs[@]} folders; output in $OUT"
unshare -m --propagation private bash "$script"
rm -f "$script"
# The table is made out here: the hidden libraries include some that this machine's python3 needs.
python3 "$ROOT/bench/dem/scaling_table.py" "$OUT/raw.txt"
grep -c . "$OUT/raw.txt" | xargs echo "runs recorded:"
