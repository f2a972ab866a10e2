#!/usr/bin/env bash
# Two dispersion tables point by point, where both are ok: relative differences of alpha_hat and
# c_hat and their distance in combined standard errors (z), then a summary per omega_hat (rms z and
# median |relative difference| over gamma_hat). Grid points match to 1e-9 relative, so tables on
# different but overlapping grids compare on their common points.
#
#   bench/table/compare_tables.sh A.h5 B.h5 [GAMMA_HATS]    e.g. GAMMA_HATS="1,100" lists those rows
#   SEDWAVE=build/bin/sedwave (default) is the binary that reads them (sedwave show).
# Units: dimensionless (docs/physics.md).
set -euo pipefail
sedwave=${SEDWAVE:-build/bin/sedwave}
a=$1 b=$2 rows=${3:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
awk -F, -v rows="$rows" '
  function key(w, g) { return sprintf("%.9e %.9e", w, g) }
  FNR == 1 { file++; next }
  file == 1 && $3 == "ok" { A[key($1, $2)] = $4 " " $5 " " $6 " " $7; next }
  file == 2 && $3 == "ok" && (key($1, $2) in A) {
    split(A[key($1, $2)], p, " ")
    da = ($4 - p[1]) / p[1]; dc = ($6 - p[3]) / p[3]
    za = ($4 - p[1]) / sqrt(p[2] ^ 2 + $5 ^ 2); zc = ($6 - p[3]) / sqrt(p[4] ^ 2 + $7 ^ 2)
    n[$1]++; sza[$1] += za * za; szc[$1] += zc * zc; all++
    if (za < 2 && za > -2) ina++
    if (zc < 2 && zc > -2) inc++
    ada[$1, n[$1]] = da < 0 ? -da : da; adc[$1, n[$1]] = dc < 0 ? -dc : dc
    if (rows != "") {
      split(rows, r, ","); for (k in r) if (($2 - r[k]) ^ 2 < 1e-18 * r[k] ^ 2)
        printf "%10.4g %9.3g  alpha %10.4g %10.4g (%+7.3f, z %+5.2f)  c %8.4g %8.4g (%+7.4f, z %+5.2f)\n", \
               $1, $2, p[1], $4, da, za, p[3], $6, dc, zc
    }
  }
  function median(arr, w, m,    i, j, t, v) {
    for (i = 1; i <= m; i++) v[i] = arr[w, i]
    for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (v[j] < v[i]) { t = v[i]; v[i] = v[j]; v[j] = t }
    return v[int((m + 1) / 2)]
  }
  END {
    for (w in n) printf "S %10.4g %4d %8.2f %8.2f %12.4f %12.4f\n", w, n[w], sqrt(sza[w] / n[w]), sqrt(szc[w] / n[w]), \
                        median(ada, w, n[w]), median(adc, w, n[w])
    if (all > 0) printf "T %d points ok in both; within 2 sigma: alpha %.1f %%, c %.1f %%\n", all, 100 * ina / all, 100 * inc / all
  }' <("$sedwave" show "$a" --values-only) <("$sedwave" show "$b" --values-only) > "$work/out"
grep -v '^[ST] ' "$work/out" || true
printf "%10s %4s %8s %8s %12s %12s\n" omega_hat n "rms z_a" "rms z_c" "med |da/a|" "med |dc/c|"
grep '^S ' "$work/out" | cut -c3- | sort -g
grep '^T ' "$work/out" | cut -c3- || echo "no point is ok in both tables"
