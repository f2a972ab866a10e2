#!/usr/bin/env python3
"""Where the paper's step criterion (eqs. 29a,b) fails: one steel-sized bead struck at 1 m/s onto a
rigid layer of an aluminium plate, advanced by `run.scheme = "newmark_rk4"` with fixed steps of
c times the paper's bound 2/omega_p (omega_p^2 = (3/2) k delta_max^(1/2) / M_node, the granule's own
sensitivity neglected) and, for comparison, of the bound with the bead's inverse mass added,
omega^2 = (3/2) k delta_max^(1/2) (1/m_b + 1/M_node). Beads from heavier to much lighter than the
node under them (bead density 7850, 780, 78 kg/m^3) on a fine and a coarse mesh. Prints, per run,
the worst energy balance over the run or that the run blew up (stopped by sedwave's energy check).

    bench/interface/paper_step_bound.py [SEDWAVE [OUT]]
"""
import math
import os
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sedwave = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build/bin/sedwave"))
out = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.environ.get("TMPDIR", "/tmp"), "sedwave-paper-step-bound")
os.makedirs(out, exist_ok=True)

SCENE = """[plate]
length_x = 0.02
length_y = 0.01
elements_x = {nx}
elements_y = {ny}
contact = "rigid_layers"
[plate.edges]
bottom = "clamped"
left = "free"
right = "free"
[packing]
rows = 1
columns = 1
x_offset = 0.0075
lift = 1e-6
density = {density}
[drive]
speed = 1.0
[run]
duration = 3e-5
output_interval = 1.5e-5
snapshots = 1
scheme = "newmark_rk4"
fixed_step = {step:.6g}
"""

E, nu, r, v = 200e9, 0.3, 2.5e-3, 1.0  # the bead; the plate: aluminium 2700 kg/m^3, 5 mm thick
e_star = E / (1 - nu * nu)             # the rigid layer's modulus
k = 4 / 3 * e_star * math.sqrt(r)
print(f"{'mesh':>5} {'rho_b':>6} {'m_b/M':>7} {'paper s':>9} {'full s':>9}  "
      + "  ".join(f"{c:>4} x paper" for c in (0.5, 1, 2)) + "  " + "  ".join(f"{c:>3} x full" for c in (0.5, 1)))
for nx, ny in ((8, 4), (2, 1)):
    node = 2700 * 5e-3 * (0.02 / nx) * (0.01 / ny) / 2  # a top edge node's lumped mass
    for density in (7850, 780, 78):
        m = 4 / 3 * math.pi * r ** 3 * density
        reduced = 1 / (1 / m + 1 / node)
        delta = (15 * reduced * v * v / (16 * e_star * math.sqrt(r))) ** 0.4
        paper = 2 / math.sqrt(1.5 * k * math.sqrt(delta) / node)
        full = 2 / math.sqrt(1.5 * k * math.sqrt(delta) * (1 / m + 1 / node))
        cells = []
        for step in [c * paper for c in (0.5, 1, 2)] + [c * full for c in (0.5, 1)]:
            path = os.path.join(out, "bead.toml")
            with open(path, "w") as f:
                f.write(SCENE.format(nx=nx, ny=ny, density=density, step=step))
            run = subprocess.run([sedwave, "interface", path, "--out", os.path.join(out, "bead.h5")],
                                 capture_output=True, text=True)
            text = run.stdout + run.stderr
            if run.returncode != 0:
                cells.append("blew up" if "energy balance is off" in text else f"exit {run.returncode}")
            else:
                cells.append(text.split("energy balance within ")[1].split()[0])
        print(f"{nx}x{ny:<3} {density:>6} {m / node:>7.3g} {paper:>9.3g} {full:>9.3g}  "
              + "  ".join(f"{c:>11}" for c in cells[:3]) + "  " + "  ".join(f"{c:>10}" for c in cells[3:]))
