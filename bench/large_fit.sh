#!/usr/bin/env bash
# A large observation file fitted by `sedwave invert`: the file is made, then fitted, and the time of
# every stage is printed (parsing, global search, polish, each likelihood profile, outputs) from the
# progress lines invert prints for large files, with the wall time of the whole command. One core
# (--threads is for the posterior; the fit is serial).
#
#   bench/large_fit.sh SEDWAVE [rows=1000000] [frequencies=250] [work dir=/tmp/sedwave-large-fit]
#
# The data: the lattice chain (kappa 1.2e6 N/m, d 0.3 mm, gamma 0.21 kg/s: c0 about 1700 m/s,
# gamma_hat about 1) from `sedwave synthesize` at FREQUENCIES log-spaced frequencies from 67 kHz to
# 1.35 MHz (omega_hat 0.075 to 1.5: the band sees the dispersion), each repeated until ROWS rows, as
# repeated pings of one broadband measurement give: every row its own noise (5 % log-normal in
# attenuation, 1 % in speed), its sigma stated. kappa, d and gamma are fitted. FREQUENCIES = ROWS/2
# makes every row's frequency its own (no two rows alike).
set -euo pipefail
sedwave="$1"; rows="${2:-1000000}"; frequencies="${3:-250}"; work="${4:-/tmp/sedwave-large-fit}"
mkdir -p "$work"
"$sedwave" synthesize --kappa 1.2e6 --d 3e-4 --gamma 0.21 --from 6.7e4 --to 1.35e6 --points "$frequencies" \
  --alpha-noise 1e-9 --speed-noise 1e-9 --out "$work/band.csv" > /dev/null
python3 - "$work/band.csv" "$work/observations.csv" "$rows" <<'PY'
import math, random, sys
band, out, rows = sys.argv[1], sys.argv[2], int(sys.argv[3])
lines = [l.rstrip('\n').split(',') for l in open(band) if l[0] not in '#q']
random.seed(20090501)
with open(out, 'w') as f:
    f.write('# repeated pings of one band (bench/large_fit.sh); SI units\nquantity,frequency,frequency_unit,value,value_unit,sigma\n')
    for k in range(rows):
        q, hz, _, value, unit, _ = lines[k % len(lines)]
        value = float(value)
        if q == 'attenuation':
            noisy = value * math.exp(0.05 * random.gauss(0.0, 1.0))
            f.write(f'{q},{hz},Hz,{noisy!r},{unit},{0.05 * noisy!r}\n')
        else:
            f.write(f'{q},{hz},Hz,{value * (1.0 + 0.01 * random.gauss(0.0, 1.0))!r},{unit},{0.01 * value!r}\n')
PY
echo "$(grep -vc '^#' "$work/observations.csv") lines (header included) in $work/observations.csv, $frequencies frequencies"
# The command runs under a small Python driver that reads its progress lines as they come and stamps
# each with the wall time and the command's own CPU time (/proc/PID/stat: user + system) so far. The
# fit's own wall time (its summary line) ends the last stage; what follows is the analysis after the
# profiles and writing the outputs. CPU time is what one core spends; wall time also counts what a
# busy machine takes away.
python3 - "$sedwave" "$work" <<'PY'
import os, subprocess, sys, time
sedwave, work = sys.argv[1], sys.argv[2]
tick = os.sysconf('SC_CLK_TCK')
start = time.monotonic()
with open(f'{work}/stdout', 'w') as out:
    p = subprocess.Popen([sedwave, 'invert', f'{work}/observations.csv', '--no-plot', '--out', f'{work}/fit'],
                         stdout=out, stderr=subprocess.PIPE, text=True)
    def cpu():
        try:
            fields = open(f'/proc/{p.pid}/stat').read().rsplit(')', 1)[1].split()
            return (int(fields[11]) + int(fields[12])) / tick
        except OSError:
            return None
    marks = []  # (wall, cpu, stage)
    for line in p.stderr:
        marks.append((time.monotonic() - start, cpu(), line.rstrip('\n').split(' s: ', 1)[-1]))
    _, status, usage = os.wait4(p.pid, 0)
    total_wall, total_cpu = time.monotonic() - start, usage.ru_utime + usage.ru_stime
code = os.waitstatus_to_exitcode(status)
if code not in (0, 3):
    sys.exit(f'invert exited {code}: ' + ''.join(m[2] + '\n' for m in marks))
summary = next(l for l in open(f'{work}/stdout') if l.startswith('sedwave invert: model'))
fit_wall = float(summary.rsplit(', ', 1)[1].split()[0]) / 1000
print(f'{"wall s":>8} {"CPU s":>8}  stage')
rows = [(marks[0][0], marks[0][1], 'reading the file, setup')]
for (w0, c0, stage), (w1, c1, _) in zip(marks, marks[1:]):
    rows.append((w1 - w0, c1 - c0, stage))
fit_end = marks[0][0] + fit_wall
rows.append((fit_end - marks[-1][0], None, marks[-1][2]))
rows.append((total_wall - fit_end, None, 'analysis after the profiles, writing the outputs (CPU: with the stage above)'))
rows.append((total_wall, total_cpu, 'whole command'))
last_cpu = marks[-1][1]
for wall, cpu_s, stage in rows:
    if stage.startswith('analysis after'):
        cpu_s = total_cpu - last_cpu
    print(f'{wall:8.1f} {"" if cpu_s is None else f"{cpu_s:8.1f}":>8}  {stage}')
PY
grep -E "^  (kappa|d|gamma) " "$work/stdout" || true
