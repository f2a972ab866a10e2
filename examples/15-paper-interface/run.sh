#!/usr/bin/env bash
# Example 15: the scenario of Wang, Zhang & Vakakis (Granular Matter 23, 21, 2021), appendix 2, with
# the paper's grain-plate contact (rigid layers at the plate's nodes). First the monolithic plate under
# a uniform impulse of 20 000 N/m held for 1 us; then the granular-solid interface, its five struck
# beads at 0.3414 m/s (the impulse's energy: README.md), 0.5 and 1 m/s. Each run prints its energy
# partition; the checks compare the impulse's work with the plane-wave closed form and with the five
# beads' kinetic energy, and the interface's transmission with the plate's.
#
#   examples/15-paper-interface/run.sh [SEDWAVE [OUT]]
source "$(dirname "$0")/../common.sh"

step "The monolithic plate under the impulse"
run 0 "$SEDWAVE" interface "$EXAMPLE_DIR/monolithic.toml" --out monolithic.h5 | tee monolithic.log

speeds="0.3414 0.5 1"
for v in $speeds; do
  step "The interface, five beads struck at $v m/s"
  run 0 "$SEDWAVE" interface "$EXAMPLE_DIR/interface.toml" --speed $v --out interface_$v.h5 | tee interface_$v.log
done

# summary FILE PATTERN: the first number after PATTERN in a run's log.
summary() { sed -n "s/.*$2 \([-0-9.e+]*\).*/\1/p" "$1" | head -1; }
# transmitted FILE: the share of the input in the plate or absorbed by its edges at the end.
transmitted() { sed -n 's/.*, plate \([0-9.]*\), friction.*absorbed by the plate.s edges \([0-9.]*\) of it/\1 + \2/p' "$1"; }
arrival() { sed -n 's/probe at .*arrival \(\S*\) s/\1/p' "$1"; }

step "The energy equivalence"
work=$(summary monolithic.log "input energy")
span=$(sed -n 's/.*over x = \(\S*\) \.\. \(\S*\) m.*/\2 - \1/p' monolithic.log)
# The five beads' kinetic energy at 0.3414 m/s, and the impulse's work on an elastic half-plane in
# plane stress: a line load q on a span L held for tau moves the edge at q / (rho c_L t), so it does
# the work L q^2 tau / (rho c_L t) (c_L = sqrt(E / (rho (1 - nu^2)))), less at the span's ends.
read -r beads plane_wave < <(python3 -c "
import math
r, rho_b, v = 2.5e-3, 7850, 0.3414
E, nu, rho, t, q, tau, L = 70e9, 0.33, 2700, 4.5e-3, 2e4, 1e-6, $span
c = math.sqrt(E / (rho * (1 - nu * nu)))
print('%.6g %.6g' % (5 * 0.5 * (4 / 3) * math.pi * r**3 * rho_b * v * v, L * q * q * tau / (rho * c * t)))")
echo "impulse's work $work J; plane-wave closed form $plane_wave J; five beads at 0.3414 m/s $beads J"
result impulse_work_J "$work"
check "the impulse's work is the plane-wave closed form's, less a little at the span's ends" \
      "0.95 < $work / $plane_wave < 1.0"
check "0.3414 m/s on the five beads carries the impulse's energy (within 1 %)" "abs($work / $beads - 1) < 0.01"

step "Transmission"
mono_arrival=$(arrival monolithic.log)
mono_share=$(transmitted monolithic.log)
check "the monolithic plate's balance closes to 1e-3 (the pulse's sharp ends load the highest modes)" \
      "$(summary monolithic.log "energy balance within") < 1e-3"
result monolithic_arrival_s "$mono_arrival"
declare -A share arrive
for v in $speeds; do
  share[$v]=$(python3 -c "print(round($(transmitted interface_$v.log), 4))")
  arrive[$v]=$(arrival interface_$v.log)
  check "energy balance closes to 1e-5 of the input at $v m/s" "$(summary interface_$v.log "energy balance within") < 1e-5"
  result transmitted_$v "${share[$v]}"
  result arrival_$v "${arrive[$v]}"
done
echo "transmitted at 100 us: monolithic $(python3 -c "print($mono_share)"); interface ${share[0.3414]}, ${share[0.5]}, ${share[1]}"
check "the granular medium delays the front more than fivefold" "${arrive[0.3414]} > 5 * $mono_arrival"
check "it transmits less than half of what the plate takes in from the same energy" \
      "${share[0.3414]} < 0.5 * ($mono_share)"
check "a stronger strike arrives sooner (the granular medium softens)" "${arrive[1]} < ${arrive[0.5]} < ${arrive[0.3414]}"
check "a stronger strike transmits a larger share" "${share[0.3414]} < ${share[0.5]} < ${share[1]}"
finish
