#!/usr/bin/env python3
"""Speed against error of the two schemes (run.scheme). The base case: 6 steel beads (3 struck at
1 m/s) on a 25 x 8 mm aluminium plate of 10 x 4 elements through the paper's rigid-layer contact,
friction mu = 0.3, k_s = 100 s/m, rotation, 40 us. Each scheme at theta = 0.4 ... 0.0125; the error
is against velocity Verlet at a much smaller theta on the same mesh (both schemes converge to the
same solution; mesh convergence is another question): the energy transmitted to the plate by the
end (in it or through its edges), relative, and the force on the plate over the run's 1000 samples,
as the largest difference over the largest force. CPU seconds of each run (the process's user +
system time); then, per scheme, the CPU time at which each error first falls below 1e-2, 1e-4 and
1e-6 (interpolated in log-log between the runs that bracket it; "<" when the coarsest run is
already below, "-" when the finest is not). With --hard, the same for the hard cases: k_s v = 1e3,
steel beads on a plate 1000 times softer, beads 1000 times softer than the plate, a finer mesh
(elements a quarter of the bead radius), a precompressed chain and a precompressed hexagonal packing
between side walls. About 15 s, and with --hard
about 25 minutes (Newmark-RK4 on the finer mesh is the most of it).

    bench/interface/scheme_error.py [SEDWAVE [OUT]] [--hard] [--only=NAME-PART]
"""
import math
import os
import resource
import subprocess
import sys

hard = "--hard" in sys.argv
only = [a.split("=", 1)[1] for a in sys.argv[1:] if a.startswith("--only=")]
args = [a for a in sys.argv[1:] if a != "--hard" and not a.startswith("--only=")]
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sedwave = os.path.abspath(args[0] if args else os.path.join(root, "build/bin/sedwave"))
out = args[1] if len(args) > 1 else os.path.join(os.environ.get("TMPDIR", "/tmp"), "sedwave-scheme-error")
os.makedirs(out, exist_ok=True)

BASE = """[plate]
youngs_modulus = {plate_modulus}
length_x = 0.025
length_y = 0.0075
elements_x = {nx}
elements_y = {ny}
contact = "rigid_layers"
[packing]
rows = 2
columns = 3
x_offset = 2.5e-3
youngs_modulus = {bead_modulus}
[contact]
friction = 0.3
tanh_velocity_scale = {ks}
[drive]
speed = 1.0
[run]
duration = 4e-5
"""
# Three beads standing on the plate in a chain, pressed by 5 N on the top one and brought to rest
# (frictionless: a chain has no slip), then the top one struck.
CHAIN = """[plate]
length_x = 0.02
length_y = 0.01
elements_x = 8
elements_y = 4
contact = "rigid_layers"
[plate.edges]
bottom = "clamped"
[packing]
rows = 1
columns = 3
orientation = "rows_perpendicular"
x_offset = 0.0075
precompression = 5.0
[drive]
speed = 0.5
width = 1
[run]
duration = 2e-5
"""
# Twenty beads in four rows between aluminium side walls, 5 N on each bead of the top row, brought to
# rest (frictionless relaxation), then the middle top bead struck; friction along the walls as between beads.
HEX = """[plate]
length_x = 0.036
length_y = 0.009
elements_x = 12
elements_y = 3
[plate.edges]
bottom = "clamped"
[packing]
rows = 4
columns = 5
precompression = 5.0
[contact]
friction = 0.3
tanh_velocity_scale = 100
[walls]
sides = "both"
[drive]
speed = 0.5
width = 1
[run]
duration = 4e-5
"""
base = dict(plate_modulus=70e9, bead_modulus=200e9, nx=10, ny=3, ks=100)
THETAS = (0.4, 0.2, 0.1, 0.05, 0.025, 0.0125)
CASES = [("base (k_s v = 100)", BASE.format(**base), 0.0015, THETAS)]
if hard:
    CASES += [
        ("k_s v = 1e3", BASE.format(**dict(base, ks=1000)), 0.003, THETAS),
        ("plate 1e3 softer", BASE.format(**dict(base, plate_modulus=200e6)), 0.003, THETAS),
        # Soft beads: contacts 1000^(2/5) = 16 times longer, so ten times the run.
        ("beads 1e3 softer", BASE.format(**dict(base, bead_modulus=70e6)).replace("duration = 4e-5", "duration = 4e-4"),
         0.003, THETAS),
        ("elements r/4", BASE.format(**dict(base, nx=40, ny=12)), 0.003, THETAS),
        # The relaxation's 2e5-step budget allows theta >= 0.01 here.
        ("precompressed chain", CHAIN, 0.01, THETAS[:4]),
        # The relaxation's 2e5-step budget allows theta >= 0.0125 here.
        ("precompressed hexagonal packing", HEX, 0.0125, THETAS[:4]),
    ]


def run(scene, scheme, theta):
    """(CPU seconds, transmitted energy at the end [J], force on the plate per sample [N])."""
    tag = os.path.join(out, f"{scheme}_{theta}")
    with open(tag + ".toml", "w") as f:
        f.write(scene + f'tolerance = {theta}\nscheme = "{scheme}"\n')
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


for name, scene, ref_theta, thetas in CASES:
    if only and not any(o in name for o in only):
        continue
    _, ref_energy, ref_force = run(scene, "velocity_verlet", ref_theta)
    peak = max(ref_force)
    print(f"\n{name}: reference velocity_verlet at theta {ref_theta}, transmitted {ref_energy:.6g} J, "
          f"peak force {peak:.6g} N")
    print(f"{'scheme':16} {'theta':>7} {'cpu s':>7} {'energy err':>11} {'force err':>10}")
    summary = []
    for scheme in ("velocity_verlet", "newmark_rk4"):
        energy_points, force_points = [], []
        for theta in thetas:
            cpu, energy, force = run(scene, scheme, theta)
            e = abs(energy / ref_energy - 1)
            f = max(abs(a - b) for a, b in zip(force, ref_force)) / peak
            energy_points.append((cpu, e))
            force_points.append((cpu, f))
            print(f"{scheme:16} {theta:>7} {cpu:>7.3f} {e:>11.3g} {f:>10.3g}")
        summary.append((scheme, energy_points, force_points))
    print(f"{'cpu s to reach':16} {'energy 1e-2':>11} {'1e-4':>7} {'1e-6':>7} {'force 1e-2':>11} {'1e-4':>7} {'1e-6':>7}")
    for scheme, energy_points, force_points in summary:
        cells = [time_to(t, energy_points) for t in (1e-2, 1e-4, 1e-6)] + [time_to(t, force_points) for t in (1e-2, 1e-4, 1e-6)]
        print(f"{scheme:16} {cells[0]:>11} {cells[1]:>7} {cells[2]:>7} {cells[3]:>11} {cells[4]:>7} {cells[5]:>7}")
