#!/usr/bin/env python3
"""Speed against error of the two schemes (run.scheme) on one small case: 6 steel beads (3 struck at
1 m/s) on a 25 x 8 mm aluminium plate of 10 x 4 elements through the paper's rigid-layer contact,
friction mu = 0.3, k_s = 100 s/m, rotation, 40 us. Each scheme at theta = 0.4 ... 0.0125; the error
is against velocity Verlet at theta = 0.0015 on the same mesh (both schemes converge to the same
solution; mesh convergence is another question): the energy transmitted to the plate by the end (in
it or through its edges), relative, and the force on the plate over the run's 1000 samples, as the
largest difference over the largest force. CPU seconds of each run (the process's user + system
time); then, per scheme, the CPU time at which each error first falls below 1e-2, 1e-4 and 1e-6
(interpolated in log-log between the runs that bracket it; "<" when the coarsest run is already
below, "-" when the finest is not).

    bench/interface/scheme_error.py [SEDWAVE [OUT]]
"""
import math
import os
import resource
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sedwave = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/bin/sedwave"))
out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.environ.get("TMPDIR", "/tmp"), "sedwave-scheme-error")
os.makedirs(out, exist_ok=True)

SCENE = """[plate]
length_x = 0.025
length_y = 0.008
elements_x = 10
elements_y = 4
contact = "rigid_layers"
[packing]
rows = 2
columns = 3
x_offset = 2.5e-3
[contact]
friction = 0.3
tanh_velocity_scale = 100
[drive]
speed = 1.0
[run]
duration = 4e-5
tolerance = {theta}
scheme = "{scheme}"
"""


def run(scheme, theta):
    """(CPU seconds, transmitted energy at the end [J], force on the plate per sample [N])."""
    tag = os.path.join(out, f"{scheme}_{theta}")
    with open(tag + ".toml", "w") as f:
        f.write(SCENE.format(theta=theta, scheme=scheme))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sedwave, "interface", tag + ".toml", "--out", tag + ".h5", "--csv", tag, "--quiet",
                    "--max-steps", "1e9"], check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    rows = [[float(x) for x in line.split(",")] for line in open(os.path.join(tag, "energies.csv"))
            if not line.startswith("#")]
    return cpu, rows[-1][4] + rows[-1][5] + rows[-1][8], [r[10] for r in rows]


def time_to(target, points):
    """CPU time where the error first falls below target, points = [(cpu, error)] from coarse to fine."""
    if points[0][1] <= target:
        return "<%.2g" % points[0][0]
    for (c0, e0), (c1, e1) in zip(points, points[1:]):
        if e1 <= target < e0:
            s = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return "%.2g" % math.exp(math.log(c0) + s * (math.log(c1) - math.log(c0)))
    return "-"


_, ref_energy, ref_force = run("velocity_verlet", 0.0015)
peak = max(ref_force)
print(f"reference: velocity_verlet at theta 0.0015, transmitted {ref_energy:.9g} J, peak force {peak:.6g} N")
print(f"{'scheme':16} {'theta':>7} {'cpu s':>7} {'energy err':>11} {'force err':>10}")
summary = []
for scheme in ("velocity_verlet", "newmark_rk4"):
    energy_points, force_points = [], []
    for theta in (0.4, 0.2, 0.1, 0.05, 0.025, 0.0125):
        cpu, energy, force = run(scheme, theta)
        e = abs(energy / ref_energy - 1)
        f = max(abs(a - b) for a, b in zip(force, ref_force)) / peak
        energy_points.append((cpu, e))
        force_points.append((cpu, f))
        print(f"{scheme:16} {theta:>7} {cpu:>7.3f} {e:>11.3g} {f:>10.3g}")
    summary.append((scheme, energy_points, force_points))
print(f"\n{'cpu s to reach':16} {'energy 1e-2':>11} {'1e-4':>7} {'1e-6':>7} {'force 1e-2':>11} {'1e-4':>7} {'1e-6':>7}")
for scheme, energy_points, force_points in summary:
    cells = [time_to(t, energy_points) for t in (1e-2, 1e-4, 1e-6)] + [time_to(t, force_points) for t in (1e-2, 1e-4, 1e-6)]
    print(f"{scheme:16} {cells[0]:>11} {cells[1]:>7} {cells[2]:>7} {cells[3]:>11} {cells[4]:>7} {cells[5]:>7}")
