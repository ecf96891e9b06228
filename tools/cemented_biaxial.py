#!/usr/bin/python3
"""The cemented biaxial test: the J05 specimen with parallel bonds of a given strength (docs/cemented_biaxial.md).

  python3 tools/cemented_biaxial.py OUT_DIR [--strengths 0,5e4,2e5,8e5] [--rolling none,jiang_plastic]
                                    [--strain 0.05] [--kb-n 2.7e10] [--jobs 2] [--quick] [--rondel PATH]

The specimen of inputs/biaxial_prepare.ini (1008 discs compressed to 200 kPa by servo walls, OUT_DIR/prep), then
for each bond strength S (0: no bonds) and rolling law, the shear stage of inputs/biaxial_jiang.ini (top wall at a
true strain rate of 0.1 /s, the side walls held at 200 kPa) with every pair within bonds.gap (1 % of the smaller
radius: every contact of the dense specimen) bonded at its start: kb_n (default 2.7e10 Pa/m: a bond's normal spring
kb_n A equal to the contacts' k_n = 2e8 N/m for the mean radius), kb_s = kb_n / 2, sigma_c = tau_c = S. Rolling:
none, or jiang_plastic with delta 0.4 (the J05 law of the specimen's preparation). Each run to the axial strain
--strain (the steps from its own time step, a one-step probe). From measures.csv (tools/biaxial.py): the peak
deviator q = s1 - s3 (the walls' stresses) and friction angle, the axial strain at the peak, and the bonds broken by
the end. Writes OUT_DIR/table.csv, OUT_DIR/peak.png (q_peak against S per rolling law) and OUT_DIR/curves.png (q
against the axial strain). --quick: the CI preset (1 % strain, strengths 0 and 8e5 Pa, no rolling law). Runs that
finished are not run again (rondel.study).
"""
import csv
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import biaxial  # noqa: E402
from rondel import CheckFailed, read_csv, study  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "cemented_biaxial"
RATE = 0.1  # the shear stage's true axial strain rate [1/s] (inputs/biaxial_jiang.ini)


def name_of(strength, rolling):
    return f"{rolling}_s{strength:g}"


def shear_command(a, strength, rolling):
    cmd = [a.rondel, os.path.join(ROOT, "inputs", "biaxial_jiang.ini"), f"--scene.file={os.path.join(a.out, 'prep')}"]
    cmd += ["--contact.rolling=none", "--run.reset_history=true"] if rolling == "none" else ["--jiang.delta=0.4"]
    if strength > 0:
        cmd += [f"--bonds.kb_n={a.kb_n!r}", f"--bonds.kb_s={a.kb_n / 2.0!r}", f"--bonds.sigma_c={strength!r}",
                f"--bonds.tau_c={strength!r}"]
    return cmd


def run_all(a):
    prep = study.Job("prep", [a.rondel, os.path.join(ROOT, "inputs", "biaxial_prepare.ini")]
                     + ([f"--run.steps={a.prep_steps}"] if a.prep_steps else []), os.path.join(a.out, "prep"))
    failed = study.run_chains([[prep]])
    chains = []
    for rolling in a.rolling:
        for s in a.strengths:
            cmd, out = shear_command(a, s, rolling), os.path.join(a.out, name_of(s, rolling))
            if not study.complete(out):
                dt = study.probe_dt(cmd, out)
                cmd = cmd + [f"--run.steps={int(math.ceil(math.log(1.0 / (1.0 - a.strain)) / (RATE * dt)))}"]
            chains.append([study.Job(name_of(s, rolling), cmd, out)])
    failed.update(study.run_chains(chains, workers=a.jobs))
    if failed:
        raise CheckFailed("runs failed: " + ", ".join(f"{k} ({v})" for k, v in failed.items()))


def result(a, strength, rolling):
    run = os.path.join(a.out, name_of(strength, rolling))
    m = biaxial.read_measures(run)
    s1, s3 = m["wall_syy"], m["wall_sxx"]
    f = biaxial.friction_angles(m["eps_axial"], s1, s3)
    d = read_csv(os.path.join(run, "diagnostics.csv"))
    bonds = int(d["bonds"][0])
    broken = int(d["bond_breaks_tension"][-1]) + int(d["bond_breaks_shear"][-1])
    return dict(rolling=rolling, sigma_c=strength, q_peak=f["q_peak"], phi_peak=f["phi_peak"], eps_peak=f["eps_peak"],
                bonds=bonds, broken=broken, tension=int(d["bond_breaks_tension"][-1]),
                curve=(m["eps_axial"], s1 - s3))


def write(a, rows):
    cols = ["rolling", "sigma_c", "q_peak", "phi_peak", "eps_peak", "bonds", "broken", "tension"]
    table = os.path.join(a.out, "table.csv")
    with open(table, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in rows:
            w.writerow([repr(r[c]) if isinstance(r[c], float) else r[c] for c in cols])
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.0, 4.0), layout="constrained")
    for rolling in a.rolling:
        mine = [r for r in rows if r["rolling"] == rolling]
        ax.plot([r["sigma_c"] / 1e3 for r in mine], [r["q_peak"] / 1e3 for r in mine], "o-",
                label="no rolling resistance" if rolling == "none" else f"{rolling}, delta 0.4")
    ax.set_xlabel("bond strength sigma_c = tau_c [kPa]")
    ax.set_ylabel("peak deviator q = s1 - s3 [kPa]")
    ax.set_title("Cemented biaxial test at 200 kPa (the J05 specimen, bonded)", fontsize=10)
    ax.legend(fontsize=8)
    written = [table, save_figure(fig, os.path.join(a.out, "peak"), a)]
    fig, ax = plt.subplots(figsize=(6.4, 4.2), layout="constrained")
    for r in rows:
        eps, q = r["curve"]
        ax.plot(eps * 100, q / 1e3, label=f"{r['rolling']}, sigma_c {r['sigma_c'] / 1e3:g} kPa")
    ax.set_xlabel("axial strain [%]")
    ax.set_ylabel("deviator q [kPa]")
    ax.legend(fontsize=7)
    written.append(save_figure(fig, os.path.join(a.out, "curves"), a))
    return written


def body(a):
    run_all(a)
    rows = [result(a, s, rolling) for rolling in a.rolling for s in a.strengths]
    for r in rows:
        print(f"{TOOL}: {r['rolling']}, sigma_c {r['sigma_c']:g} Pa: q_peak {r['q_peak'] / 1e3:.1f} kPa, phi_peak "
              f"{r['phi_peak']:.1f} deg at {100 * r['eps_peak']:.2f} % axial strain; {r['broken']} of {r['bonds']} "
              f"bonds broken ({r['tension']} in tension)")
    print(f"{TOOL}: wrote " + ", ".join(write(a, rows)))
    return 0


def main(argv=None):
    ap = ArgumentParser(TOOL, description="The cemented biaxial test (the J05 specimen with parallel bonds).",
                        epilog="See the module docstring (head of tools/cemented_biaxial.py).")
    ap.add_argument("out", help="the study's directory")
    ap.add_argument("--strengths", default="0,5e4,2e5,8e5", help="bond strengths sigma_c = tau_c [Pa]; 0 = no bonds")
    ap.add_argument("--rolling", default="none,jiang_plastic", help="rolling laws: none, jiang_plastic (delta 0.4)")
    ap.add_argument("--strain", type=float, default=0.05, help="axial strain to reach")
    ap.add_argument("--kb-n", type=float, default=2.7e10, help="bond normal stiffness per area [Pa/m]")
    ap.add_argument("--jobs", type=int, default=2, help="runs in parallel")
    ap.add_argument("--prep-steps", type=int, default=0, help="steps of the preparation (0: the file's)")
    ap.add_argument("--quick", action="store_true", help="the CI preset")
    ap.add_argument("--rondel", default=os.path.join(ROOT, "build", "rondel"))
    add_figure_options(ap, dpi=120, no_plot=False)
    a = ap.parse_args(argv)
    check_figure_options(ap, a)
    try:
        a.strengths = [float(s) for s in a.strengths.split(",")]
    except ValueError:
        ap.error("--strengths: numbers separated by commas")
    a.rolling = [r.strip() for r in a.rolling.split(",")]
    if any(not (math.isfinite(s) and s >= 0) for s in a.strengths):
        ap.error("--strengths: each a finite number >= 0")
    if any(r not in ("none", "jiang_plastic") for r in a.rolling):
        ap.error("--rolling: none or jiang_plastic")
    if not (0 < a.strain < 0.5) or not (math.isfinite(a.kb_n) and a.kb_n > 0) or a.jobs < 1:
        ap.error("--strain in (0, 0.5), --kb-n > 0 and --jobs >= 1")
    if a.quick:
        a.strengths, a.rolling, a.strain = [0.0, 8e5], ["none"], 0.01
    return run_tool(TOOL, body, a)


if __name__ == "__main__":
    sys.exit(main())
