#!/usr/bin/env bash
# Example 13: from the seabed to the sonar.
#
# A propagation modeller needs the seabed as speeds, attenuations and density, or as a table of the
# reflection coefficient against angle. Here a medium sand (Buckingham's grain-shearing model, its
# 2005 reference sediment) becomes both: its shear wave beside its compressional wave, its bottom
# loss against grazing angle (alone, and under 2 m of soft mud), third-octave band averages, and the
# files BELLHOP and the other Acoustics Toolbox programs read.
#
#   examples/13-seabed-reflection/run.sh [SEDWAVE [OUT]]
source "$(dirname "$0")/../common.sh"

step "Which models have a shear wave"
run 0 "$SEDWAVE" models grain-shearing | grep -E '^grain-shearing|shear wave|bulk density'

step "The sand as a half-space under 1500 m/s water, 1 and 10 kHz, every degree"
run 0 "$SEDWAVE" reflect --model grain-shearing --frequency 1000,10000 --angle-step 1 --water-speed 1500 \
    --water-density 1025 --out sand
# The waves at 1 kHz, and GS's closed forms for the shear wave (Buckingham 2005):
#   c_s = sqrt(gamma_s/rho_0) (omega T)^(n/2) / cos(n pi/4),  alpha_s = omega tan(n pi/4) / c_s.
python3 - <<'PY' | tee closed_form.txt
import csv, math
rows = [r for r in csv.reader(l for l in open('sand/media.csv') if not l.startswith('#'))][1:]
part, f, cp, ap, cs, as_, rho = min(rows, key=lambda r: abs(math.log(float(r[1]) / 1000.0)))
f, cs, as_, rho = float(f), float(cs), float(as_), float(rho)
gamma_s, n = 4.588e7, 0.0851
omega = 2 * math.pi * f
c_closed = math.sqrt(gamma_s / rho) * omega ** (n / 2) / math.cos(n * math.pi / 4)
a_closed = omega * math.tan(n * math.pi / 4) / c_closed * 20 * math.log10(math.e)
print(f"at {f:.1f} Hz: c_s {cs:.2f} m/s (closed form {c_closed:.2f}), alpha_s {as_:.3f} dB/m (closed form {a_closed:.3f})")
PY
result sand_cs_1khz_m_per_s "$(sed -n 's/.*c_s \([0-9.]*\) m\/s.*/\1/p' closed_form.txt)"
check "the shear wave is GS's closed form" \
      "all(abs(float(a)/float(b)-1) < 1e-6 for a, b in [__import__('re').findall(r'([0-9.]+) m/s \(closed form ([0-9.]+)', open('closed_form.txt').read())[0], __import__('re').findall(r'([0-9.]+) dB/m \(closed form ([0-9.]+)', open('closed_form.txt').read())[0]])"
# R = -1 at grazing incidence; total reflection but for the shear wave's and the P wave's losses
# below the critical angle arccos(c_w/c_p); most energy enters the seabed above it.
python3 - <<'PY' | tee sand_angles.txt
import csv, math
rows = [r for r in csv.reader(l for l in open('sand/reflection.csv') if not l.startswith('#'))][1:]
loss = {(float(r[0]), float(r[1])): float(r[6]) for r in rows}
media = [r for r in csv.reader(l for l in open('sand/media.csv') if not l.startswith('#'))][1:]
cp = float(min(media, key=lambda r: abs(math.log(float(r[1]) / 1000.0)))[2])
critical = math.degrees(math.acos(1500.0 / cp))
steepest = max(range(1, 90), key=lambda a: loss[(1000.0, a + 1)] - loss[(1000.0, a)])
print(f"critical angle {critical:.2f} deg; steepest rise of the loss at 1 kHz between {steepest} and {steepest + 1} deg")
print(f"loss at 1 kHz: 0 deg {loss[(1000.0, 0.0)]:.4f} dB, 10 deg {loss[(1000.0, 10.0)]:.3f} dB, 90 deg {loss[(1000.0, 90.0)]:.3f} dB")
PY
result critical_angle_deg "$(sed -n 's/^critical angle \([0-9.]*\).*/\1/p' sand_angles.txt)"
result sand_loss_10deg_1khz_db "$(sed -n 's/.*10 deg \([0-9.]*\) dB.*/\1/p' sand_angles.txt)"
result sand_loss_90deg_1khz_db "$(sed -n 's/.*90 deg \([0-9.]*\) dB.*/\1/p' sand_angles.txt)"
check "no loss at grazing incidence (R = -1)" "'0 deg 0.0000 dB' in open('sand_angles.txt').read()"
check "the loss rises fastest at the critical angle" \
      "(lambda t: abs(float(t[0]) - float(t[1]) - 0.5) <= 1.0)(__import__('re').findall(r'critical angle ([0-9.]+) deg; steepest rise of the loss at 1 kHz between ([0-9]+)', open('sand_angles.txt').read())[0])"

step "2 m of soft mud (EDFM, porosity 0.7) over the sand at 3 kHz, with third-octave averages, and a BELLHOP table"
run 0 "$SEDWAVE" reflect --model grain-shearing --layer edfm --set l1.thickness=2 --set l1.porosity=0.7 \
    --frequency 3000 --band 0.3333 --band-samples 41 --angle-step 0.5 --out mud --brc mud.brc
head -4 mud.brc
python3 - <<'PY' | tee mud_checks.txt
import csv
rows = [r for r in csv.reader(l for l in open('mud/reflection.csv') if not l.startswith('#'))][1:]
brc = [l.split() for l in open('mud.brc')][1:]
# The table BELLHOP reads: |R| as computed, phase -arg R (its e^{+i omega t}), unwrapped.
worst = max(abs(float(b[1]) - float(r[4])) + abs(((float(b[2]) + float(r[5]) + 180) % 360) - 180) for b, r in zip(brc, rows))
print(f"brc rows {len(brc)}, largest difference from reflection.csv {worst:.2e}")
band = {float(r[1]): float(r[8]) for r in rows}
single = {float(r[1]): float(r[6]) for r in rows}
print(f"loss at 5 deg: {single[5.0]:.3f} dB at 3 kHz, {band[5.0]:.3f} dB third-octave average")
print(f"largest band power {max(float(r[7]) for r in rows):.6f}")
PY
result mud_loss_5deg_3khz_db "$(sed -n 's/^loss at 5 deg: \([0-9.]*\) dB.*/\1/p' mud_checks.txt)"
result mud_band_loss_5deg_db "$(sed -n 's/.*dB at 3 kHz, \([0-9.]*\) dB third.*/\1/p' mud_checks.txt)"
check "the .brc table is the coefficient computed, with BELLHOP's phase sign" \
      "float(open('mud_checks.txt').read().split('reflection.csv ')[1].split()[0]) < 1e-6"  # 10 printed digits
check "band averages of |R|^2 stay within [0, 1]" \
      "0 <= float(open('mud_checks.txt').read().split('largest band power ')[1].split()[0]) <= 1"

step "An Acoustics Toolbox environment: the sand's half-space line in each attenuation unit at 3 kHz"
for unit in W M F Q N; do
  run 0 "$SEDWAVE" reflect --model grain-shearing --frequency 3000 --angle-step 10 --out env_$unit \
      --env sand_$unit.env --water-depth 100 --env-unit $unit >/dev/null
  printf '%s: %s   %s\n' "$unit" "$(sed -n 4p sand_$unit.env | cut -d' ' -f1)" "$(tail -1 sand_$unit.env | cut -d/ -f1)"
done | tee env_lines.txt
# The toolbox's own conversions (misc/AttenMod.f90, CRCI) take every line back to one alpha_p in Np/m.
python3 - <<'PY' | tee env_alpha.txt
import math
f = 3000.0
for line in open('env_lines.txt'):
    unit, rest = line.split(':', 1)
    z, cp, cs, rho, ap, as_ = map(float, rest.split()[1:7])
    np_per_m = {'N': ap, 'M': ap / 8.6858896, 'F': ap * f / 8685.8896, 'W': ap * f / (8.6858896 * cp),
                'Q': 2 * math.pi * f / (2 * cp * ap)}[unit]
    print(f"{unit} alpha_p {np_per_m:.8f} Np/m")
PY
check "every unit gives the same attenuation" \
      "(lambda v: max(v) / min(v) - 1 < 1e-7)([float(l.split()[2]) for l in open('env_alpha.txt')])"
result sand_alpha_p_3khz_np_per_m "$(sed -n 's/^N alpha_p \([0-9.]*\).*/\1/p' env_alpha.txt)"
step "Reflection data back to the seabed: the mud's thickness and porosity from noisy bottom loss"
# Bottom loss of the mud over the sand at 1, 2 and 4 kHz and twelve grazing angles, 0.5 dB noise;
# then a fit of the layer's thickness and porosity (the sand held at its values). The interference
# of the layer makes chi^2 many-valleyed in thickness: the search bounds say what the site allows.
run 0 "$SEDWAVE" synthesize --model layered:edfm+grain-shearing --set l1.thickness=2 --set l1.porosity=0.7 \
    --from 1000 --to 4000 --points 3 --grazing-angles 5,10,15,20,25,30,35,40,50,60,70,80 --reflection-only \
    --bottom-loss-sigma 0.5 --seed 1 --out mud_observations.csv
run 0 "$SEDWAVE" invert mud_observations.csv --model layered:edfm+grain-shearing --fit l1.porosity,l1.thickness \
    --bounds l1.thickness=0.5,5 --out mud_fit | grep -E '^  l1\.(thickness|porosity) |^chi2'
python3 - <<'PY' | tee mud_fit.txt
import json
fit = json.load(open('mud_fit/fit.json'))
p = fit['parameters']
for name, truth in (('l1.thickness', 2.0), ('l1.porosity', 0.7)):
    v, s = p[name]['value'], p[name]['sigma']
    print(f"{name} {v:.5g} +- {s:.2g} (truth {truth}, {abs(v - truth) / s:.2f} sigma away)")
PY
result mud_thickness_fit_m "$(sed -n 's/^l1.thickness \([0-9.]*\) .*/\1/p' mud_fit.txt)"
check "the fit finds the truth within three of its sigmas" \
      "all(float(l.split('(truth ')[1].split(', ')[1].split()[0]) < 3 for l in open('mud_fit.txt'))"
# The fitted seabed handed on: its bottom loss at 3 kHz from the fit report, as BELLHOP reads it.
run 0 "$SEDWAVE" reflect --model layered:edfm+grain-shearing --from-fit mud_fit/fit.json --frequency 3000 \
    --angle-step 0.5 --out mud_fitted --brc mud_fitted.brc >/dev/null
python3 - <<'PY' | tee mud_fitted.txt
import csv
rows = [r for r in csv.reader(l for l in open('mud_fitted/reflection.csv') if not l.startswith('#'))][1:]
print(f"fitted seabed: loss at 5 deg {dict((float(r[1]), float(r[6])) for r in rows)[5.0]:.3f} dB at 3 kHz")
PY
check "the fitted seabed reflects as the true one (5 deg, 3 kHz) within 0.5 dB" \
      "abs(float(open('mud_fitted.txt').read().split('5 deg ')[1].split()[0]) - float(open('mud_checks.txt').read().split('loss at 5 deg: ')[1].split()[0])) < 0.5"
finish
