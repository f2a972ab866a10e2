#!/usr/bin/env bash
# Packs what bench/dem/device_scaling.sh, bench/dem/tiled_channel.sh and bench/device_lease.sh need
# on a bare x86-64 Linux machine (glibc >= this one's, no MPI, no LAMMPS, no network) into one
# folder: dem_bench, sedwave (for bench/compare_threads.sh), stream_triad, Debian's Open MPI (mpirun, orted, the
# MCA components and help files, PMIx and its components), LAMMPS (lmp, liblammps), every shared
# library they need apart from glibc's own, and the packings of the scaling study.
#
# Usage: bench/dem/pack_for_device.sh [build-dir] [pack-dir]
#   build-dir  a Release build with SEDWAVE_BUILD_BENCH=ON (default: build); dem_bench is built there
#   pack-dir   the folder to fill (default: .device at the repository root, which git is told to
#              ignore through .git/info/exclude so that it travels only when named). It receives
#              pack.tar.xz (the tree, about a third of its unpacked size) and run.sh, which unpacks
#              it into /tmp and runs device_scaling.sh there; the unpacked tree stays in
#              pack-dir.tree (also ignored) for checking here.
# EXTRA_BENCH="name=/path/to/dem_bench ..." adds further engine builds (e.g. the code before a
# change), which the scaling script runs side by side with dem_bench.
#
# Relocation: Open MPI finds its components, help files and configuration below OPAL_PREFIX and
# OPAL_SYSCONFDIR, PMIx below PMIX_INSTALL_PREFIX; pack-dir/env.sh sets them from its own location.
# The pack is checked here by bench/dem/check_device_pack.sh (a private mount namespace in which the
# system's copies of everything packed are hidden).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=$(cd "${1:-$ROOT/build}" && pwd)
CARRY=${2:-$ROOT/.device}
PACK=$CARRY.tree
ARCH=x86_64-linux-gnu
OMPI=/usr/lib/$ARCH/openmpi
PMIX=/usr/lib/$ARCH/pmix2

for tool in lmp orterun strip ldd; do
  command -v "$tool" >/dev/null || { echo "pack_for_device: $tool is missing (apt-get install lammps openmpi-bin binutils)" >&2; exit 1; }
done
cmake --build "$BUILD" --target dem_bench sedwave >/dev/null

# Keep the pack out of git without touching .gitignore (the device copies ignored paths only when
# they are named in carry).
exclude="$(cd "$ROOT" && realpath "$(git rev-parse --git-common-dir)")/info/exclude"
mkdir -p "$(dirname "$exclude")"
for dir in "$CARRY" "$PACK"; do
  rel=$(realpath -m --relative-to="$ROOT" "$dir")
  grep -qxF "/$rel/" "$exclude" 2>/dev/null || echo "/$rel/" >>"$exclude"
done

rm -rf "$PACK" "$CARRY"
mkdir -p "$PACK/usr/bin" "$PACK/lib" "$PACK/usr/lib/$ARCH" "$PACK/etc" "$PACK/usr/share" "$PACK/packings"

# ---- programs -----------------------------------------------------------------------------------
cp "$BUILD/bin/dem_bench" "$PACK/usr/bin/dem_bench"
cp "$BUILD/bin/sedwave" "$PACK/usr/bin/sedwave"
for extra in ${EXTRA_BENCH:-}; do cp "${extra#*=}" "$PACK/usr/bin/dem_bench_${extra%%=*}"; done
cp "$(readlink -f "$(command -v lmp)")" "$PACK/usr/bin/lmp"
cp /usr/bin/orterun /usr/bin/orted /usr/bin/ompi_info "$PACK/usr/bin/"
ln -s orterun "$PACK/usr/bin/mpirun"
cc -O2 -Wall -Wextra -Werror -o "$PACK/usr/bin/peak_rss" "$ROOT/bench/dem/peak_rss.c"
cc -O2 -Wall -Wextra -Werror -o "$PACK/usr/bin/stream_triad" "$ROOT/bench/dem/stream_triad.c"
# The scaling script and what it reads, so that the pack runs from any checkout.
mkdir -p "$PACK/bench"
cp "$ROOT"/bench/dem/{device_scaling.sh,tiled_channel.sh,in.thesis.lmp,scaling_table.py} "$PACK/bench/"

# ---- Open MPI and PMIx trees (components, help files, configuration) -----------------------------
mkdir -p "$PACK$OMPI/lib" "$PACK$PMIX/lib"
# Components for fabrics a single node does not use (UCX, libfabric, verbs, PSM) and OpenSHMEM's
# would pull in large libraries; Open MPI simply does not find them.
skip='atomic_|btl_ofi|btl_openib|mtl_|osc_ucx|pml_ucx|spml_|sshmem_|memheap_|scoll_'
mkdir -p "$PACK$OMPI/lib/openmpi3"
for c in "$OMPI"/lib/openmpi3/*.so; do
  [[ $(basename "$c") =~ $skip ]] || cp "$c" "$PACK$OMPI/lib/openmpi3/"
done
cp -r "$PMIX/lib/pmix" "$PACK$PMIX/lib/"
cp -r "$PMIX/share" "$PACK$PMIX/"
cp -r /usr/share/openmpi "$PACK/usr/share/"
cp -r /etc/openmpi "$PACK/etc/"
# Single node, run as root, possibly in a container with a small /dev/shm: shared memory through
# /tmp, the packed transports only. PMIx finds its components through PMIX_PKGLIBDIR (env.sh), not
# the absolute path of Debian's configuration.
conf=$PACK/etc/openmpi/openmpi-mca-params.conf
grep -v -E '^ *(btl|pml|mtl) *=' /etc/openmpi/openmpi-mca-params.conf >"$conf"
cat >>"$conf" <<'EOF'
btl = self,vader
pml = ob1
btl_vader_backing_directory = /tmp
rmaps_base_oversubscribe = 1
EOF
sed -i '/^ *mca_base_component_path *=/d' "$PACK$PMIX/share/pmix-mca-params.conf"

# ---- shared libraries: every dependency outside glibc, resolved here ------------------------------
glibc='^(ld-linux-x86-64|libc|libm|libpthread|libdl|librt|libresolv|libutil|libanl|libnsl|libmvec)\.so'
is_elf() { [[ $(head -c 4 "$1" | od -An -c | tr -d ' ') == '177ELF' ]]; }
mapfile -t elves < <(find "$PACK" -type f | while read -r f; do is_elf "$f" && echo "$f"; done)
declare -A seen=()
for f in "${elves[@]}"; do
  while read -r name path; do
    [[ -z $path || $name =~ $glibc || -n ${seen[$name]:-} ]] && continue
    seen[$name]=1
    cp -L "$path" "$PACK/lib/$name"
  done < <(LD_LIBRARY_PATH="$OMPI/lib:$PMIX/lib" ldd "$f" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}')
done
if LD_LIBRARY_PATH="$PACK/lib:$PACK$OMPI/lib" ldd "${elves[@]}" 2>/dev/null | grep -q 'not found'; then
  echo "pack_for_device: unresolved libraries:" >&2
  LD_LIBRARY_PATH="$PACK/lib:$PACK$OMPI/lib" ldd "${elves[@]}" | grep -B30 'not found' >&2
  exit 1
fi
find "$PACK" -type f | while read -r f; do is_elf "$f" && strip --strip-unneeded "$f" 2>/dev/null || true; done

# ---- environment --------------------------------------------------------------------------------
cat >"$PACK/env.sh" <<EOF
# Sourced by bench/dem/device_scaling.sh: the packed Open MPI, PMIx and libraries, relocated.
PACK=\$(cd "\$(dirname "\${BASH_SOURCE[0]}")" && pwd)
export OPAL_PREFIX=\$PACK/usr OPAL_SYSCONFDIR=\$PACK/etc/openmpi
# PMIx's own directories (Debian's are absolute, so each is set, not only the prefix).
PMIX_TREE=\$PACK$PMIX
export PMIX_PREFIX=\$PMIX_TREE PMIX_INSTALL_PREFIX=\$PMIX_TREE PMIX_EXEC_PREFIX=\$PMIX_TREE
export PMIX_LIBDIR=\$PMIX_TREE/lib PMIX_PKGLIBDIR=\$PMIX_TREE/lib/pmix PMIX_DATADIR=\$PMIX_TREE/share
export PMIX_DATAROOTDIR=\$PMIX_TREE/share PMIX_PKGDATADIR=\$PMIX_TREE/share/pmix PMIX_SYSCONFDIR=\$PMIX_TREE/share
export PATH=\$PACK/usr/bin:\$PATH
# Only for the programs started through pack_env: the system's own tools keep their libraries.
PACK_LIBS=\$PACK/lib:\$PACK$OMPI/lib:\$PACK$PMIX/lib
pack_env() { env LD_LIBRARY_PATH="\$PACK_LIBS" "\$@"; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
EOF

# ---- packings: prepared (relaxed) here, stacked there ---------------------------------------------
# 15 625 grains (one rank's share in the weak-scaling series; 16 stacked copies are the 2.5e5
# strong-scaling packing) and 5e4 grains. Prepared once per build folder (the preparation does not
# depend on the engine's parallel code).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$BUILD/device-packings"
for n in 15625 50000; do
  prepared=$BUILD/device-packings/packing_$n.data
  [[ -s $prepared ]] || mpirun -np 1 "$BUILD/bin/dem_bench" prepare "$n" "$prepared" >/dev/null
  cp "$prepared" "$PACK/packings/"
done
"$BUILD/bin/dem_bench" params >"$PACK/packings/params.txt"

mkdir -p "$CARRY"
tar -C "$PACK" -c . | xz -T2 -2 >"$CARRY/pack.tar.xz"
cat >"$CARRY/run.sh" <<'EOF'
#!/usr/bin/env bash
# Unpacks pack.tar.xz (made by bench/dem/pack_for_device.sh) into /tmp (PACK_TREE) and runs the
# scaling study from there; arguments and environment (OUT, BUDGET_S, PASSES, RANKS) go to
# device_scaling.sh. UNPACK_ONLY=1 stops after unpacking.
set -euo pipefail
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
TREE=${PACK_TREE:-/tmp/sedwave-dem-pack}
rm -rf "$TREE"
mkdir -p "$TREE"
if tar --version >/dev/null 2>&1 && command -v xz >/dev/null; then
  tar -C "$TREE" -xJf "$HERE/pack.tar.xz"
else
  python3 -c 'import sys, tarfile; tarfile.open(sys.argv[1]).extractall(sys.argv[2])' "$HERE/pack.tar.xz" "$TREE"
fi
[[ ${UNPACK_ONLY:-0} == 1 ]] && exit 0
exec bash "$TREE/bench/device_scaling.sh" "$TREE" "$@"
EOF
chmod +x "$CARRY/run.sh"
echo "unpacked: $(du -sh "$PACK" | cut -f1); carried ($CARRY): $(du -sh "$CARRY" | cut -f1)"
du -s --block-size=1M "$CARRY" | awk '$1 > 64 {print "pack_for_device: over 64 MiB" > "/dev/stderr"; exit 1}'
