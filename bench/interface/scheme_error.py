#!/usr/bin/env python3
"""Speed against error of the two schemes (run.scheme), case by case.

Each case is a scene swept over the adaptive step's tolerance theta with each scheme; the error is
against velocity Verlet at a much smaller theta on the same mesh (both schemes converge to the same
solution), in two quantities: the energy transmitted to the plate by the end (in it or through its
edges), relative, and the force on the plate over the run's samples, as the largest difference over
the largest force. The reference's own error is estimated by running it again at twice its theta
(the change, printed as "reference's own error"). Mesh convergence is reported apart: the reference
again on a mesh with half the element size, against the same-mesh reference (an error of the mesh,
not of the step).

Times are CPU seconds of each run (the process's user + system time, start-up of about 0.03 s
included; wall seconds are printed beside them). Per scheme, the CPU time at which each error first
falls below 1e-2, 1e-4 and 1e-6, interpolated in log-log between the two measured runs that bracket
it ("<t" when the coarsest run, at t seconds, is already below; "-" when the finest is not; a "?"
follows a target below the reference's own error, which the sweep cannot resolve).

The base case: 6 steel beads (3 struck at 1 m/s) on a 25 x 7.5 mm aluminium plate of 10 x 3
elements through the paper's rigid-layer contact, friction mu = 0.3, k_s = 100 s/m, rotation,
40 us. With --hard the hard cases too (CASES below; one entry adds one). --figure=PATH draws error
against CPU time, one panel per case, both schemes (matplotlib; where the running python lacks it,
the figure is drawn by /usr/bin/python3 from the sweep's JSON). About 15 s; with --hard about 123
runs in 65 minutes of CPU on a shared 2-core machine (the r/8 mesh's 13 runs 47 of them, its three
Newmark-RK4 runs 29), so it is a benchmark, not a test. A run sedwave flags (exit 3: a contact patch
wider than half an element, as on the r/16 mesh of the r/8 case's check) is kept and marked.

    bench/interface/scheme_error.py [SEDWAVE [OUT]] [--hard] [--only=NAME-PART] [--figure=PATH]
    bench/interface/scheme_error.py --plot OUT/scheme_error.json PATH
"""
import json
import math
import os
import re
import resource
import subprocess
import sys
import time

SCHEMES = ("velocity_verlet", "newmark_rk4")
TARGETS = (1e-2, 1e-4, 1e-6)

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
duration = {duration}
"""
# Three beads standing on the plate in a chain, pressed by 5 N on the top one and brought to rest
# (frictionless: a chain has no slip; damped with a 10 us time constant, which comes to rest within
# the relaxation's 2e5 steps down to theta = 0.005), then the top one struck.
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
relaxation_time = 1e-5
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
base = dict(plate_modulus=70e9, bead_modulus=200e9, nx=10, ny=3, ks=100, duration=4e-5)
THETAS = (0.4, 0.2, 0.1, 0.05, 0.025, 0.0125)


def case(name, scene, reference_theta, thetas=THETAS, newmark_thetas=None, mesh_theta=None):
    """One row of the table: the scene (a [run] table last, without tolerance or scheme), the
    reference's theta, the thetas swept (velocity Verlet; Newmark-RK4 the same unless given), and
    the theta of the mesh comparison (the reference's unless given: then h and h/2 both at it)."""
    return dict(name=name, scene=scene, reference_theta=reference_theta, mesh_theta=mesh_theta,
                thetas={"velocity_verlet": thetas, "newmark_rk4": newmark_thetas or thetas})


CASES = [case("base (k_s v = 100)", BASE.format(**base), 0.0015)]
HARD = [
    case("k_s v = 1e3", BASE.format(**dict(base, ks=1e3)), 0.003),
    # The friction limit falls as 1/k_s: 10 us (the impact and the first rebounds) keeps these short.
    case("k_s v = 1e4, 10 us", BASE.format(**dict(base, ks=1e4, duration=1e-5)), 0.00625,
         THETAS[:5], THETAS[:3]),
    case("k_s v = 1e5, 10 us", BASE.format(**dict(base, ks=1e5, duration=1e-5)), 0.025, THETAS[:4], THETAS[:2]),
    # Below theta = 0.0067 of the contact's limit the samples (40 ns) no longer cap the step: the
    # sweep goes down to 0.0015 to get under it.
    case("plate 1e3 softer", BASE.format(**dict(base, plate_modulus=200e6)), 0.0004,
         THETAS + (0.00625, 0.003, 0.0015), THETAS + (0.00625,)),
    # Soft beads: contacts 1000^(2/5) = 16 times longer, so ten times the run.
    case("beads 1e3 softer, 400 us", BASE.format(**dict(base, bead_modulus=70e6, duration=4e-4)), 0.003),
    case("elements r/4", BASE.format(**dict(base, nx=40, ny=12)), 0.003, THETAS, THETAS[:3]),
    # h = r/8: its mesh check (h/2 = r/16, 160 x 48) at theta = 0.025, where the step's own error
    # (below 1e-7 on the r/4 mesh) is far under the mesh's.
    case("elements r/8", BASE.format(**dict(base, nx=80, ny=24)), 0.003, THETAS, THETAS[:3], mesh_theta=0.025),
    # The finer mesh halves the plate's limit, so the relaxation needs theta >= 0.01 there.
    case("precompressed chain", CHAIN, 0.005, mesh_theta=0.02),
    # The relaxation's 2e5-step budget allows theta >= 0.0125 here, and 0.025 on the finer mesh.
    case("precompressed hexagonal packing", HEX, 0.0125, THETAS[:4], mesh_theta=0.025),
]


def refined(scene):
    """The scene on a mesh with half the element size (every old node kept, so beads stay over nodes)."""
    return re.sub(r"^(elements_[xy]) = (\d+)$", lambda m: f"{m.group(1)} = {2 * int(m.group(2))}", scene,
                  flags=re.M)


def slug(text):
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_")


def run(sedwave, out, tag, scene, scheme, theta):
    """(CPU seconds, wall seconds, transmitted energy at the end [J], force on the plate per sample [N],
    flagged): flagged when sedwave exits 3, a run completed but outside its contact model (a contact
    patch wider than half an element, which sedwave prints)."""
    path = os.path.join(out, f"{tag}_{scheme}_{theta}")
    with open(path + ".toml", "w") as f:
        f.write(scene + f'tolerance = {theta}\nscheme = "{scheme}"\n')
    before, start = resource.getrusage(resource.RUSAGE_CHILDREN), time.monotonic()
    command = [sedwave, "interface", path + ".toml", "--out", path + ".h5", "--csv", path, "--quiet",
               "--max-steps", "1e9"]
    status = subprocess.run(command).returncode
    if status not in (0, 3):
        raise subprocess.CalledProcessError(status, command)
    wall, after = time.monotonic() - start, resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    rows = [[float(x) for x in line.split(",")] for line in open(os.path.join(path, "energies.csv"))
            if not line.startswith("#")]
    return cpu, wall, rows[-1][4] + rows[-1][5] + rows[-1][8], [r[10] for r in rows], status == 3


def errors(energy, force, ref_energy, ref_force):
    """(relative error in transmitted energy, largest force difference over the reference's peak)."""
    peak = max(abs(x) for x in ref_force)
    return abs(energy / ref_energy - 1), max(abs(a - b) for a, b in zip(force, ref_force)) / peak


def time_to(target, points):
    """CPU time where the error first falls below target, points = [(cpu, error)] from coarse to fine."""
    if points[0][1] <= target:
        return "<%.2g" % points[0][0]
    for (c0, e0), (c1, e1) in zip(points, points[1:]):
        if e1 <= target < e0:
            s = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return "%.2g" % math.exp(math.log(c0) + s * (math.log(c1) - math.log(c0)))
    return "-"


def sweep(sedwave, out, c):
    tag = slug(c["name"])
    ref_theta = c["reference_theta"]
    _, _, ref_energy, ref_force, _ = run(sedwave, out, tag, c["scene"], "velocity_verlet", ref_theta)
    _, _, check_energy, check_force, _ = run(sedwave, out, tag, c["scene"], "velocity_verlet", 2 * ref_theta)
    mesh_theta = c["mesh_theta"] or ref_theta
    _, _, mesh_energy, mesh_force, mesh_flagged = run(sedwave, out, tag + "_h2", refined(c["scene"]),
                                                      "velocity_verlet", mesh_theta)
    _, _, h_energy, h_force, _ = (run(sedwave, out, tag, c["scene"], "velocity_verlet", mesh_theta)
                                  if c["mesh_theta"] else (0, 0, ref_energy, ref_force, False))
    own = errors(check_energy, check_force, ref_energy, ref_force)
    mesh = errors(h_energy, h_force, mesh_energy, mesh_force)
    print(f"\n{c['name']}: reference velocity_verlet at theta {ref_theta}, transmitted {ref_energy:.6g} J, "
          f"peak force {max(ref_force):.6g} N; reference's own error {own[0]:.2g} (energy), {own[1]:.2g} (force); "
          f"mesh h against h/2 (theta {mesh_theta}) {mesh[0]:.2g} (energy), {mesh[1]:.2g} (force)"
          + (" (h/2 flagged: its contact patch is wider than half an element)" if mesh_flagged else ""))
    print(f"{'scheme':16} {'theta':>7} {'cpu s':>7} {'wall s':>7} {'energy err':>11} {'force err':>10}")
    result = dict(name=c["name"], reference_theta=ref_theta, own_error=own, mesh_error=mesh,
                  mesh_flagged=mesh_flagged, schemes={})
    for scheme in SCHEMES:
        points = []
        for theta in c["thetas"][scheme]:
            cpu, wall, energy, force, _ = run(sedwave, out, tag, c["scene"], scheme, theta)
            e, f = errors(energy, force, ref_energy, ref_force)
            points.append(dict(theta=theta, cpu=cpu, wall=wall, energy=e, force=f))
            print(f"{scheme:16} {theta:>7} {cpu:>7.3f} {wall:>7.3f} {e:>11.3g} {f:>10.3g}")
        result["schemes"][scheme] = points
    print(f"{'cpu s to reach':16} {'energy 1e-2':>11} {'1e-4':>7} {'1e-6':>7} {'force 1e-2':>11} {'1e-4':>7} {'1e-6':>7}")
    for scheme, points in result["schemes"].items():
        cells = []
        for quantity, floor in (("energy", own[0]), ("force", own[1])):
            series = [(p["cpu"], p[quantity]) for p in points]
            cells += [time_to(t, series) + ("?" if t < floor else "") for t in TARGETS]
        print(f"{scheme:16} {cells[0]:>11} {cells[1]:>7} {cells[2]:>7} {cells[3]:>11} {cells[4]:>7} {cells[5]:>7}")
    return result


def plot(results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    columns = min(4, len(results))
    rows = (len(results) + columns - 1) // columns
    fig, axes = plt.subplots(rows, columns, figsize=(3.6 * columns, 3.2 * rows), squeeze=False)
    style = {"velocity_verlet": ("C0", "velocity Verlet"), "newmark_rk4": ("C3", "Newmark-RK4")}
    for ax, r in zip(axes.flat, results):
        for scheme, points in r["schemes"].items():
            colour, label = style[scheme]
            cpu = [p["cpu"] for p in points]
            ax.loglog(cpu, [max(p["energy"], 1e-12) for p in points], "o-", color=colour, label=label + ", energy")
            ax.loglog(cpu, [max(p["force"], 1e-12) for p in points], "s--", color=colour, mfc="none",
                      label=label + ", force")
        own_energy, own_force = r["own_error"]  # 0 where the two agree to every digit of energies.csv: no line
        for own, ls in ((own_energy, ":"), (own_force, "-.")):
            if own > 0:
                ax.axhline(own, color="grey", lw=0.8, ls=ls)
        flag = " (h/2 flagged)" if r.get("mesh_flagged") else ""
        ax.set_title(f"{r['name']}\nmesh h vs h/2: energy {r['mesh_error'][0]:.1g}, force {r['mesh_error'][1]:.1g}{flag}",
                     fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="major", lw=0.3)
    for ax in axes.flat[len(results):]:
        ax.axis("off")
    for ax in axes[:, 0]:
        ax.set_ylabel("error against the same-mesh reference", fontsize=7)
    for ax in axes[-1, :]:
        ax.set_xlabel("CPU seconds per run", fontsize=7)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    handles += [plt.Line2D([], [], color="grey", lw=0.8, ls=":"), plt.Line2D([], [], color="grey", lw=0.8, ls="-.")]
    labels += ["reference's own error, energy", "reference's own error, force"]
    fig.legend(handles, labels, loc="lower center", ncol=3 if columns > 2 else 2, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=90)
    os.replace(tmp, path)


def draw(data_path, figure):
    """Draw with matplotlib here, or with /usr/bin/python3 where this python lacks it."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        subprocess.run(["/usr/bin/python3", os.path.abspath(__file__), "--plot", data_path, figure], check=True)
        return
    with open(data_path) as f:
        plot(json.load(f), figure)


def main(argv):
    if argv and argv[0] == "--plot":
        with open(argv[1]) as f:
            plot(json.load(f), argv[2])
        return
    hard = "--hard" in argv
    only = [a.split("=", 1)[1] for a in argv if a.startswith("--only=")]
    figure = next((a.split("=", 1)[1] for a in argv if a.startswith("--figure=")), None)
    args = [a for a in argv if a != "--hard" and not a.startswith("--")]
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    sedwave = os.path.abspath(args[0] if args else os.path.join(root, "build/bin/sedwave"))
    out = args[1] if len(args) > 1 else os.path.join(os.environ.get("TMPDIR", "/tmp"), "sedwave-scheme-error")
    os.makedirs(out, exist_ok=True)
    started = time.monotonic()
    data_path = os.path.join(out, "scheme_error.json")
    results = []
    for c in CASES + (HARD if hard else []):
        if only and not any(o in c["name"] for o in only):
            continue
        results.append(sweep(sedwave, out, c))
        with open(data_path, "w") as f:  # after every case, so that a case that fails keeps the others
            json.dump(results, f, indent=1)
    print(f"\n{len(results)} cases in {time.monotonic() - started:.0f} s wall; points in {data_path}")
    if figure:
        draw(data_path, figure)
        print(f"figure {figure}")


if __name__ == "__main__":
    main(sys.argv[1:])
