# Shared by bench/device_lease.sh and bench/dem/loaded_baseline.sh (sourced): the spread of a
# measurement over processes. Empty lines on stdin (runs that failed and printed nothing) are left out.

# min / median / max, then "(K of N)" when fewer than N ($1) numbers came; "failed" when none did.
summary() {
  grep . | sort -g | awk -v want="${1:-0}" '{v[++k] = $1} END {
    if (!k) {printf "failed"; exit}
    printf "%.4g / %.4g / %.4g", v[1], v[int((k + 1) / 2)], v[k]; if (k < want) printf " (%d of %d)", k, want }'
}

# The median alone (nothing when no number came).
median() { grep . | sort -g | awk '{v[++k] = $1} END {if (k) printf "%.4g", v[int((k + 1) / 2)]}'; }
