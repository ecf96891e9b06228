#!/usr/bin/python3
"""Error against run time for Rondel's validation cases with exact answers (docs/validation.md section 7).

For each case, runs dt_k = dt0 / 2^k (k = 0 .. levels-1, dt0 = 0.2 dt_crit, dt_crit read from the run's
log.txt and checked against docs/physics.md section 4 computed here) and records the step size, steps, wall time
(of the subprocess, and the figure in summary.txt), the error against the exact answer and the observed order
p_k = log2(err_k / err_{k+1}), plus a least-squares slope of log(error) against log(dt) over all levels.

Cases (the exact answers are computed here from the formulas of docs/validation.md / docs/physics.md):
  a   two-disc normal impact (two D5, set J, 1 m/s), zeta = 0: |1 - e|, worst of --phases contact-onset
      phases                                                                    (VALIDATION 4; 7 says 3)
  a2  the same with dt0 the largest step below 0.2 dt_crit that divides the contact time t_c = pi/w0
  b   the same impact with zeta = 0.3: |e - e_exact|                            (VALIDATION 4; 7 says 1)
  c   D5 rolling on a flat wall (set S, v0 = 1 m/s), constant_torque mu_r = 0.05, f_lim = 0: first-stop
      (largest) x against the rigid-plastic s = a KE0/M; also against the model's own continuum answer
      with its undamped tangential spring ("alt. error")                        (VALIDATION 2; 7 says >= 2)
  d   the same with jiang_plastic (delta = 0.3): first stop against s1 = a (KE0/M + M/(2K)) (VALIDATION 2)
  e   rolling mode of a D5 resting on a wall (jiang_plastic, K = 0.75), started along the low mode:
      frequency from the zero crossings of omega against the quartic's w_low   (VALIDATION 5; 7 says 2)
  c2  (not in the default set) case c with tangential damping zeta_t = 0.5, against the continuum stop of
      that model (the rigid s plus the static shift of the tangential spring, D/Omega^2)
final.csv is the only trajectory output of rondel, so a first stop is found by runs that end at chosen
steps (a bracketed search for the step where vx changes sign), the maximum then from the cubic Hermite
interpolant of (x, vx) at the two steps around it; the frequency of case e comes from diagnostics.csv
(ke_rot every step).

Usage (from the repository root; only numpy and matplotlib are needed; about 2 minutes on 2 cores):
  /usr/bin/python3 tools/error_vs_runtime.py [--rondel build/rondel] [--out study-output]
      [--levels 6 | --quick] [--cases a,a2,b,c,d,e] [--ranks 1] [--phases 5] [--keep-runs]
Output in --out: <case>.csv per case, combined.csv, combined.md (also printed), error_vs_runtime.png
(--format pdf|svg, --dpi). The critical step comes from the run's summary.json when present, else log.txt.
Exit status: 0 done, 1 bad executable or option, 2 a rondel run failed (e.g. more ranks than the build accepts).
"""
import csv
import math
import os
import shutil
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rondel import CheckFailed, RondelError, open_run, read_csv  # noqa: E402
from rondel.cli import ArgumentParser, add_figure_options, check_figure_options, pyplot, run_tool, save_figure  # noqa: E402,E501

TOOL = "error_vs_runtime"

# ---------------------------------------------------------------------------------------------------------
# Standard objects (docs/validation.md section 0)
G = 9.81
RHO = 2650.0
THICK = 1.0
R5 = 0.005  # disc D5


def disc_mass(R, rho=RHO, t=THICK):
    return rho * math.pi * R * R * t


def disc_inertia(R, rho=RHO, t=THICK):
    m = disc_mass(R, rho, t)
    return 0.5 * m * R * R


SET_S = dict(k_n=1e6, k_s=0.75e6, mu=0.5)
SET_J = dict(k_n=2e8, k_s=1.5e8, mu=0.5)


# ---------------------------------------------------------------------------------------------------------
# Exact answers
def restitution_exact(zeta):
    """No-tension linear spring-dashpot restitution (docs/validation.md section 4)."""
    if zeta == 0.0:
        return 1.0
    if zeta < 1.0:
        return math.exp(-zeta * math.acos(2 * zeta * zeta - 1) / math.sqrt(1 - zeta * zeta))
    return math.exp(-zeta * math.acosh(2 * zeta * zeta - 1) / math.sqrt(zeta * zeta - 1))


def contact_time_exact(zeta, w0):
    if zeta == 0.0:
        return math.pi / w0
    return math.acos(2 * zeta * zeta - 1) / (w0 * math.sqrt(1 - zeta * zeta))


class RollingDisc:
    """D5 on the bottom wall at the static overlap, rolling without slip at v0 along t = +x."""

    def __init__(self, contact=SET_S, v0=1.0):
        self.R = R5
        self.m = disc_mass(self.R)
        self.I = disc_inertia(self.R)
        self.k_n, self.k_s, self.mu = contact["k_n"], contact["k_s"], contact["mu"]
        self.Fn = self.m * G
        self.un0 = self.Fn / self.k_n
        self.a = self.R - self.un0 / 2
        self.v0 = v0
        self.w0 = -v0 / self.a
        self.KE0 = 0.5 * (self.m * v0 ** 2 + self.I * self.w0 ** 2)
        # tangential mode with rotation at the wall (slip spring alone): Omega^2 = k_s (1/m + a^2/I)
        self.Omega = math.sqrt(self.k_s * (1 / self.m + self.a ** 2 / self.I))

    def decel(self, M):
        """Rolling without slip under a resisting couple M: dv/dt = -M a/(I + m a^2)."""
        return M * self.a / (self.I + self.m * self.a ** 2)

    def scene_row(self, vx=None, omega=None):
        vx = self.v0 if vx is None else vx
        omega = self.w0 if omega is None else omega
        return [0, 0.0, self.R - self.un0, self.R, vx, 0.0, omega]


def constant_torque_compliant_stop(disc, M):
    """First maximum of x for a constant couple M with the undamped tangential spring in series (the
    model's own continuum solution; the spring starts unloaded, so it oscillates about its static shift):
      xi(t) = xi_eq (1 - cos W t),  x(t) = v0 t - D t^2/2 + D (1 - cos W t)/W^2,
      vx(t) = v0 - D t + (D/W) sin W t,  omega(t) = omega0 + [M t - a k_s xi_eq (t - sin(W t)/W)]/I,
    with W = disc.Omega, D = M a/(I + m a^2), xi_eq = a M/(I W^2). Valid while omega < 0 (the couple does
    not flip); returns (x_max, t_max, omega(t_max))."""
    W, D, a = disc.Omega, disc.decel(M), disc.a
    xi_eq = a * M / (disc.I * W * W)

    def vx(t):
        return disc.v0 - D * t + (D / W) * math.sin(W * t)

    lo, hi = disc.v0 / D - 2.0 / W, disc.v0 / D + 2.0 / W
    assert vx(lo) > 0 > vx(hi)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if vx(mid) > 0:
            lo = mid
        else:
            hi = mid
    t = 0.5 * (lo + hi)
    x = disc.v0 * t - 0.5 * D * t * t + D * (1 - math.cos(W * t)) / W ** 2
    om = disc.w0 + (M * t - a * disc.k_s * xi_eq * (t - math.sin(W * t) / W)) / disc.I
    return x, t, om


def rolling_mode_low(disc, K):
    """Lowest root of m I w^4 - [k_s (I + m a^2) + m K] w^2 + k_s K = 0 (docs/validation.md section 5), and its
    mode shape X/Theta (x and theta amplitudes) from the 2x2 system."""
    m, I, a, ks = disc.m, disc.I, disc.a, disc.k_s
    A, B, C = m * I, ks * (I + m * a * a) + m * K, ks * K
    disc_ = math.sqrt(B * B - 4 * A * C)
    w2 = 2 * C / (B + disc_)  # the small root, without cancellation
    ratio = -ks * a / (ks - m * w2)  # X/Theta from the first row (k_s - m w^2) X + k_s a Theta = 0
    return math.sqrt(w2), ratio


# ---------------------------------------------------------------------------------------------------------
# Critical time step, docs/physics.md section 4 (a check on the log's figure)
def mode_limit(w, zeta):
    return (2.0 / w) * (math.sqrt(1 + zeta * zeta) - zeta)


def critical_step_tool(R, k_n, k_s, zeta_n=0.0, zeta_t=0.0, rolling_K=None, walls=True):
    """Smallest limit over the disc-disc pair (R, R) and, with walls, the disc-wall pair. rolling_K(R_star)
    returns the rolling stiffness of a contact with that R* (or None)."""
    m, I = disc_mass(R), disc_inertia(R)
    best = math.inf
    pairs = [("disc", m / 2, 1 / (2 / m + 2 * R * R / I), I / 2, R / 2)]
    if walls:
        pairs.append(("wall", m, 1 / (1 / m + R * R / I), I, R))
    for _, m_eff, m_t, I_red, R_star in pairs:
        best = min(best, mode_limit(math.sqrt(k_n / m_eff), zeta_n))
        w2_t = k_s / m_t
        z_t = zeta_t * math.sqrt(m_eff / m_t)
        best = min(best, mode_limit(math.sqrt(w2_t), z_t))
        if rolling_K is not None:
            K = rolling_K(R_star)
            best = min(best, mode_limit(math.sqrt(w2_t + K / I_red), z_t))
    return best


# ---------------------------------------------------------------------------------------------------------
# Running rondel
class RunError(CheckFailed):
    """A rondel run that failed (exit status 2)."""


class Runner:
    def __init__(self, rondel, ranks, workdir, launcher):
        self.rondel = os.path.abspath(rondel)
        self.ranks = ranks
        self.workdir = workdir
        self.launcher = launcher
        self.count = 0
        if not os.access(self.rondel, os.X_OK):
            raise RunError(f"rondel executable not found at {rondel} (build it, or pass --rondel)")

    def command(self, ini, overrides):
        cmd = [self.rondel, ini] + [f"--{k}={v}" for k, v in overrides.items()]
        if self.launcher == "mpirun":
            mpirun = shutil.which("mpirun")
            if mpirun is None:
                raise RunError("mpirun not found on PATH")
            cmd = [mpirun, "-n", str(self.ranks), "--oversubscribe", "--allow-run-as-root"] + cmd
        return cmd

    def run(self, ini, outdir, overrides, want_diag=False):
        """Runs rondel; returns a dict with final state, wall times, log figures."""
        ov = {"run.output": outdir, "run.overwrite": "true", "run.progress": "false"}
        ov.update(overrides)
        cmd = self.command(ini, ov)
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
        wall = time.perf_counter() - t0
        self.count += 1
        if proc.returncode != 0:
            msg = (proc.stderr.strip() or proc.stdout.strip()).splitlines()
            raise RunError(f"rondel exited with code {proc.returncode}: {' '.join(cmd)}\n  " + "\n  ".join(msg[:8]))
        res = {"wall_subprocess": wall}
        res.update(parse_log(os.path.join(outdir, "log.txt")))
        res.update(parse_summary(os.path.join(outdir, "summary.txt")))
        res["final"] = parse_final(os.path.join(outdir, "final.csv"))
        if want_diag:
            res["diag"] = parse_diagnostics(os.path.join(outdir, "diagnostics.csv"))
        return res


def parse_log(path):
    """dt, critical dt and mode of a run: summary.json when the build writes it, else the log's 'time step' line."""
    try:
        ts = open_run(os.path.dirname(path)).time_step()
    except RondelError as e:
        raise RunError(str(e)) from None
    return {"dt_log": float(ts["dt"]), "dt_crit_log": float(ts["dt_critical"]), "crit_mode": ts["critical_mode"]}


def parse_summary(path):
    """Steps, discs, wall time, rate and completion of a run (summary.json or summary.txt)."""
    try:
        s = open_run(os.path.dirname(path)).summary()
    except RondelError as e:
        raise RunError(str(e)) from None
    complete = s.get("complete", s.get("status") == "complete")
    return {"steps": int(s["steps"]), "discs": int(s["discs"]), "wall_summary": float(s["wall_seconds"]),
            "disc_steps_per_s": float(s["disc_steps_per_s"]), "complete": bool(complete)}


def parse_final(path):
    """final.csv as {gid: {column: value}} (exact floats, hexadecimal or decimal)."""
    t = read_csv(path)
    return {int(g): t.row(k) for k, g in enumerate(t["gid"])}


def parse_diagnostics(path):
    """diagnostics.csv as named columns (rondel.Table)."""
    return read_csv(path)


def write_scene(path, rows):
    with open(path, "w") as f:
        f.write("id,x,y,radius,vx,vy,omega\n")
        for r in rows:
            f.write(",".join([str(r[0])] + [repr(float(v)) for v in r[1:]]) + "\n")


def write_ini(path, sections):
    with open(path, "w") as f:
        for sec, kv in sections.items():
            f.write(f"[{sec}]\n")
            for k, v in kv.items():
                f.write(f"{k} = {v}\n")
            f.write("\n")


# ---------------------------------------------------------------------------------------------------------
# Cases
class Case:
    key = ""
    title = ""
    expected_order = ""
    error_name = ""
    alt_name = ""

    def __init__(self, runner, root, phases):
        self.runner = runner
        self.dir = os.path.join(root, "runs", self.key)
        os.makedirs(self.dir, exist_ok=True)
        self.ini = os.path.join(self.dir, "case.ini")
        self.phases = phases
        self.notes = []

    def base_step(self, dt_crit):
        return 0.2 * dt_crit

    def probe(self):
        """A 0-step run for the code's dt_crit; checks it against the tool's own formula."""
        res = self.runner.run(self.ini, os.path.join(self.dir, "probe"), {"run.steps": 0})
        self.dt_crit = res["dt_crit_log"]
        self.crit_mode = res["crit_mode"]
        rel = abs(self.dt_crit - self.dt_crit_tool) / self.dt_crit_tool
        if rel > 1e-5:
            self.notes.append(f"dt_crit: log {self.dt_crit:.6g} s differs from docs/physics.md section 4 "
                              f"{self.dt_crit_tool:.6g} s by {rel:.2e} relative")
        return self.dt_crit


class ImpactCase(Case):
    """Two D5 discs, set J, head-on at 1 m/s relative; worst case over contact-onset phases."""

    zeta = 0.0
    v_rel = 1.0

    def __init__(self, runner, root, phases):
        super().__init__(runner, root, phases)
        self.R = R5
        self.m = disc_mass(self.R)
        self.m_eff = self.m / 2
        self.w0 = math.sqrt(SET_J["k_n"] / self.m_eff)
        self.tc = contact_time_exact(self.zeta, self.w0)
        self.exact = restitution_exact(self.zeta)
        write_ini(self.ini, {
            "run": {"steps": 1},
            "diagnostics": {"every": 10 ** 9},
            "domain": {"xlo": -0.02, "xhi": 0.02, "ylo": -0.01, "yhi": 0.01},
            "material": {"density": RHO, "thickness": THICK},
            "linear": {"k_n": SET_J["k_n"], "zeta": self.zeta},
            "coulomb": {"k_s": SET_J["k_s"], "mu": SET_J["mu"]},
            "scene": {"type": "csv", "file": "probe.csv"},
        })
        write_scene(os.path.join(self.dir, "probe.csv"), self.scene(1e-6, 0.5, 0))
        self.dt_crit_tool = critical_step_tool(self.R, SET_J["k_n"], SET_J["k_s"], zeta_n=self.zeta, walls=False)

    def scene(self, dt, phase, n_pre=1):
        gap = self.v_rel * (n_pre + phase) * dt  # contact starts at (n_pre + phase) dt
        x = self.R + 0.5 * gap
        return [[0, -x, 0.0, self.R, 0.5 * self.v_rel, 0.0, 0.0], [1, x, 0.0, self.R, -0.5 * self.v_rel, 0.0, 0.0]]

    def level(self, k, dt):
        errs, walls, wsum, steps, measured, replica = [], [], [], [], [], []
        for j in range(self.phases):
            phase = (j + 0.5) / self.phases
            scene = os.path.join(self.dir, f"k{k}_p{j}.csv")
            write_scene(scene, self.scene(dt, phase))
            n = math.ceil((1 + phase + 1.25 * self.tc / dt)) + 3
            for _ in range(4):
                res = self.runner.run(self.ini, os.path.join(self.dir, f"k{k}_p{j}"),
                                      {"run.steps": n, "run.dt": repr(dt), "scene.file": os.path.abspath(scene)})
                f = res["final"]
                if f[1]["x"] - f[0]["x"] > 2 * self.R:  # separated: the velocities are final
                    break
                n *= 2
            else:
                raise RunError(f"case {self.key}: discs still in contact after {n} steps")
            e = (f[1]["vx"] - f[0]["vx"]) / self.v_rel
            measured.append(e)
            errs.append(abs(e - self.exact))
            replica.append(abs(e - impact_verlet_replica(self.w0, self.zeta, dt, (1 + phase) * dt, self.v_rel)))
            walls.append(res["wall_subprocess"])
            wsum.append(res["wall_summary"])
            steps.append(res["steps"])
        i = int(np.argmax(errs))
        ratio = self.tc / dt
        return {"steps": int(round(np.mean(steps))), "runs": self.phases, "wall_subprocess": float(np.mean(walls)),
                "wall_summary": float(np.mean(wsum)), "measured": measured[i], "exact": self.exact,
                "error": errs[i],
                "extra": f"worst of {self.phases} onset phases at phase {(i + 0.5) / self.phases:.2f}, mean error "
                         f"{np.mean(errs):.3e}; t_c/dt = {ratio:.3f}; (w0 dt)^2/8 = {(self.w0 * dt) ** 2 / 8:.3e}; "
                         f"rondel vs 1-D Verlet replica: {max(replica):.1e}"}


def impact_verlet_replica(w0, zeta, dt, gap, v):
    """Velocity Verlet on the relative normal coordinate, as docs/physics.md sections 1-2 prescribe (force from the
    drifted positions, dashpot on the half-step velocity, no tension); returns the restitution coefficient."""
    u, ud, acc, touched = -gap, v, 0.0, False
    for _ in range(10 ** 7):
        ud += 0.5 * dt * acc
        u += dt * ud
        acc = -max(0.0, w0 * w0 * u + 2 * zeta * w0 * ud) if u > 0 else 0.0
        ud += 0.5 * dt * acc
        touched = touched or u > 0
        if touched and u <= 0:
            return -ud / v
    raise RuntimeError("replica: no separation")


class ImpactUndamped(ImpactCase):
    key = "a"
    title = "(a) impact, zeta = 0: |1 - e|"
    expected_order = "3"
    error_name = "|1 - e|"
    zeta = 0.0


class ImpactUndampedCommensurate(ImpactCase):
    key = "a2"
    title = "(a2) impact, zeta = 0, t_c/dt integer: |1 - e|"
    expected_order = "3"
    error_name = "|1 - e|"
    zeta = 0.0

    def base_step(self, dt_crit):
        """The largest step below 0.2 dt_crit that divides the contact time: t_c/dt_k = N 2^k."""
        return self.tc / math.ceil(self.tc / (0.2 * dt_crit))


class ImpactDamped(ImpactCase):
    key = "b"
    title = "(b) impact, zeta = 0.3: |e - e_exact|"
    expected_order = "1"
    error_name = "|e - e_exact|"
    zeta = 0.3


class RollingStopCase(Case):
    """D5 rolling on the bottom wall with set S; the error is that of the first-stop (largest) x.
    The first stop is found by runs that end at chosen steps (final.csv is the only trajectory output):
    a bracketed search for the step where vx changes sign, then the cubic Hermite interpolant through
    (x, vx) at the two steps around it gives the maximum."""

    zeta_t = 0.0

    def __init__(self, runner, root, phases):
        super().__init__(runner, root, phases)
        self.disc = RollingDisc()
        d = self.disc
        sections = {
            "run": {"steps": 1},
            "diagnostics": {"every": 10 ** 9},
            "domain": {"xlo": -0.05, "xhi": 1.0, "ylo": 0.0, "yhi": 0.05},
            "gravity": {"y": -G},
            "material": {"density": RHO, "thickness": THICK},
            "linear": {"k_n": d.k_n, "zeta": 0.0},
            "coulomb": {"k_s": d.k_s, "mu": d.mu, "zeta_t": self.zeta_t},
            "contact": {"rolling": self.law},
            "walls": {"box": "bottom"},
            "scene": {"type": "csv", "file": "scene.csv"},
        }
        sections.update(self.law_sections())
        self.trace = []
        write_ini(self.ini, sections)
        write_scene(os.path.join(self.dir, "scene.csv"), [d.scene_row()])
        self.exact, self.t_guess = self.exact_stop()

    def level(self, k, dt):
        self._dt = dt
        cache = {}

        def at(n):
            if n not in cache:
                res = self.runner.run(self.ini, os.path.join(self.dir, f"k{k}"), {"run.steps": n, "run.dt": repr(dt)})
                cache[n] = res
            return cache[n]

        def vx(n):
            return at(n)["final"][0]["vx"]

        # Newton steps with the mean deceleration until the sign change is bracketed, then regula falsi on
        # the step index (bisection whenever an iteration shrinks the bracket by less than half). The wiggle
        # of the undamped tangential spring moves the crossing by up to 1/Omega in time: each Newton step
        # adds that much so that it brackets quickly.
        D, W = self.mean_decel, self.disc.Omega
        n_guess = max(2, int(round(self.t_guess / dt)))
        lo, hi, n = None, None, n_guess
        for _ in range(50):
            v = vx(n)
            if v > 0:
                lo = n
                if hi is not None:
                    break
                n += max(1, int(round((v / D + 1 / W) / dt)))
                if n > 3 * n_guess:
                    raise RunError(f"case {self.key}: vx still > 0 after {n} steps (no stop?)")
            else:
                hi = n
                if lo is not None:
                    break
                if n == 1:
                    raise RunError(f"case {self.key}: vx <= 0 already after 1 step")
                n = max(1, n - max(1, int(round((-v / D + 1 / W) / dt))))
        else:
            raise RunError(f"case {self.key}: could not bracket the first stop")
        use_bisect = False
        while hi - lo > 1:
            vlo, vhi = vx(lo), vx(hi)
            if use_bisect:
                n = (lo + hi) // 2
            else:
                n = int(round(lo + (hi - lo) * vlo / (vlo - vhi)))
                n = min(max(n, lo + 1), hi - 1)
            old = hi - lo
            if vx(n) > 0:
                lo = n
            else:
                hi = n
            use_bisect = (hi - lo) > old / 2
        self.trace.append(f"k={k}: runs at steps {sorted(cache)}")
        a, b = at(lo)["final"][0], at(hi)["final"][0]
        x_max = hermite_max(a["x"], a["vx"], b["x"], b["vx"], dt)
        timed = at(hi)  # the run to the first step past the stop: the cost of this answer
        return {"steps": hi, "runs": len(cache), "wall_subprocess": timed["wall_subprocess"],
                "wall_summary": timed["wall_summary"], "measured": x_max, "exact": self.exact,
                "error": abs(x_max - self.exact), "error_alt": self.alt_error(x_max, dt),
                "extra": "; ".join(x for x in (self.extra_note(x_max), self.trace[-1]) if x)}

    def extra_note(self, x_max):
        return ""

    def alt_error(self, x_max, dt):
        return None


def hermite_max(x0, v0, x1, v1, h):
    """Maximum of the cubic Hermite interpolant on [0, h] with x(0) = x0, x'(0) = v0 > 0, x(h) = x1,
    x'(h) = v1 <= 0."""
    # x(s) = h00 x0 + h10 h v0 + h01 x1 + h11 h v1, s in [0, 1]; x'(s) = A s^2 + B s + C
    A = 6 * x0 + 3 * h * v0 - 6 * x1 + 3 * h * v1
    B = -6 * x0 - 4 * h * v0 + 6 * x1 - 2 * h * v1
    C = h * v0
    roots = [s.real for s in np.roots([A, B, C]) if abs(s.imag) < 1e-12 and -1e-12 <= s.real <= 1 + 1e-12] \
        if abs(A) > 0 else ([-C / B] if B != 0 else [])

    def x(s):
        return ((2 * s ** 3 - 3 * s ** 2 + 1) * x0 + (s ** 3 - 2 * s ** 2 + s) * h * v0
                + (-2 * s ** 3 + 3 * s ** 2) * x1 + (s ** 3 - s ** 2) * h * v1)

    return max([x0, x1] + [x(min(max(s, 0.0), 1.0)) for s in roots])


class ConstantTorqueStop(RollingStopCase):
    key = "c"
    title = "(c) rolling, constant_torque: first stop vs s = a KE0/M"
    expected_order = ">= 2"
    error_name = "|s_num - s|"
    law = "constant_torque"
    mu_r = 0.05

    def law_sections(self):
        return {"constant_torque": {"mu_r": self.mu_r, "f_lim": 0}}

    def couple(self):
        return self.mu_r * 2 * self.disc.R * self.disc.Fn  # R_eq = 2R at a wall

    def rigid_stop(self):
        """The couple M, and the rigid-plastic stop s = a KE0/M (kept as self.rigid)."""
        d = self.disc
        M = self.couple()
        self.dt_crit_tool = critical_step_tool(d.R, d.k_n, d.k_s, zeta_t=self.zeta_t)
        self.rigid = d.a * d.KE0 / M
        self.mean_decel = d.decel(M)
        return M, self.rigid

    def exact_stop(self):
        d = self.disc
        M, s = self.rigid_stop()
        x_c, t_c, om = constant_torque_compliant_stop(d, M)
        self.compliant = x_c
        if om >= 0:
            self.notes.append("compliant solution: omega reaches 0 before vx; its x_max is not valid")
        self.notes.append(f"rigid-plastic s = {s:.12g} m; the model's own continuum answer (undamped tangential "
                          f"spring oscillating about its static shift, Omega = {d.Omega:.6g} rad/s) is "
                          f"x_max = {x_c:.12g} m (s + {x_c - s:.3e} m); the rigid-s error cannot fall below "
                          f"about D/Omega^2 = {d.decel(M) / d.Omega ** 2:.2e} m")
        return s, t_c

    alt_name = "vs the compliant continuum x_max"

    def alt_error(self, x_max, dt):
        return abs(x_max - self.compliant)

    def extra_note(self, x_max):
        return f"error vs compliant continuum x_max: {abs(x_max - self.compliant):.3e}"


class ConstantTorqueStopDamped(ConstantTorqueStop):
    key = "c2"
    title = "(c2) rolling, constant_torque, zeta_t = 0.5: first stop vs s + D/Omega^2"
    error_name = "|s_num - (s + D/W^2)|"
    zeta_t = 0.5

    def exact_stop(self):
        d = self.disc
        M, s = self.rigid_stop()
        shift = d.decel(M) / d.Omega ** 2
        self.compliant = s + shift
        self.notes.append(f"with a damped tangential spring the start-up transient dies out and the motion is the "
                          f"rigid one shifted by D/Omega^2 = {shift:.4e} m: exact stop {s + shift:.12g} m")
        return s + shift, d.v0 / d.decel(M)

    def alt_error(self, x_max, dt):
        return None

    def extra_note(self, x_max):
        return f"error vs rigid s: {abs(x_max - self.rigid):.3e}"


class JiangPlasticStop(RollingStopCase):
    key = "d"
    title = "(d) rolling, jiang_plastic: first stop vs s1"
    expected_order = "~1"
    error_name = "|s1_num - s1|"
    law = "jiang_plastic"
    delta = 0.3

    def law_sections(self):
        return {"jiang": {"delta": self.delta}}

    def exact_stop(self):
        d = self.disc
        B = self.delta * 2 * d.R  # r -> 2R at a wall
        K = d.k_n * B * B / 12
        M = d.Fn * B / 6
        self.dt_crit_tool = critical_step_tool(
            d.R, d.k_n, d.k_s, rolling_K=lambda Rs: d.k_n * (self.delta * 2 * Rs) ** 2 / 12)
        s1 = d.a * (d.KE0 / M + M / (2 * K))
        t_guess = d.v0 / d.decel(M) + (M / K) / abs(d.w0)
        self.mean_decel = d.decel(M)
        self.t_yield = (M / K) / abs(d.w0)
        self.notes.append(f"the unloaded rolling spring reaches the cap after t_y = (M0/K)/|omega0| = "
                          f"{self.t_yield:.3e} s; for dt > t_y the first step's trapezoid couple M0 dt/2 replaces "
                          f"M0 (dt - t_y/2), which predicts an overshoot v0 (dt - t_y)/2 (first order, then "
                          f"second order once dt < t_y)")
        self.notes.append(f"K_m = {K:.6g} N m/rad, M0 = {M:.6g} N m, s1 = {s1:.12g} m, s_rest = "
                          f"{s1 - d.a * M / K:.12g} m; tangential compliance shifts the stop by about "
                          f"{d.decel(M) / d.Omega ** 2:.1e} m (not modelled here)")
        return s1, t_guess

    def extra_note(self, x_max):
        dt = self._dt
        if dt <= self.t_yield:
            return "dt < t_y"
        return f"overshoot model v0 (dt - t_y)/2 = {self.disc.v0 * (dt - self.t_yield) / 2:.3e}"


class RollingFrequency(Case):
    key = "e"
    title = "(e) rolling mode on a wall, K = 0.75: |w - w_low|/w_low"
    expected_order = "2"
    error_name = "|w_num/w_low - 1|"
    delta = 0.3
    theta_amp = 1e-4  # rad, far below the Jiang yield rotation M0/K = 1.36e-3
    periods = 6

    def __init__(self, runner, root, phases):
        super().__init__(runner, root, phases)
        d = self.disc = RollingDisc()
        B = self.delta * 2 * d.R
        self.K = d.k_n * B * B / 12
        self.w_low, ratio = rolling_mode_low(d, self.K)
        self.exact = self.w_low
        omega0 = self.theta_amp * self.w_low
        # start at equilibrium with the velocity of the low mode only (no high mode)
        write_ini(self.ini, {
            "run": {"steps": 1},
            "diagnostics": {"every": 1},
            "domain": {"xlo": -0.05, "xhi": 0.05, "ylo": 0.0, "yhi": 0.05},
            "gravity": {"y": -G},
            "material": {"density": RHO, "thickness": THICK},
            "linear": {"k_n": d.k_n, "zeta": 0.0},
            "coulomb": {"k_s": d.k_s, "mu": d.mu},
            "contact": {"rolling": "jiang_plastic"},
            "jiang": {"delta": self.delta},
            "walls": {"box": "bottom"},
            "scene": {"type": "csv", "file": "scene.csv"},
        })
        write_scene(os.path.join(self.dir, "scene.csv"), [d.scene_row(vx=ratio * omega0, omega=omega0)])
        self.dt_crit_tool = critical_step_tool(
            d.R, d.k_n, d.k_s, rolling_K=lambda Rs: d.k_n * (self.delta * 2 * Rs) ** 2 / 12)
        self.notes.append(f"w_low = {self.w_low:.9g} rad/s from the quartic (K = {self.K:.6g}); start along the "
                          f"low mode (vx/omega = {ratio:.6g} m), theta amplitude {self.theta_amp:g} rad")

    def level(self, k, dt):
        T = self.periods * 2 * math.pi / self.w_low
        n = int(math.ceil(T / dt))
        res = self.runner.run(self.ini, os.path.join(self.dir, f"k{k}"),
                              {"run.steps": n, "run.dt": repr(dt)}, want_diag=True)
        diag = res["diag"]
        t = np.asarray(diag["step"], dtype=float) * dt  # (the time column has 10 significant digits only)
        ke = np.asarray(diag["ke_rot"], dtype=float)
        crossings = omega_zero_crossings(t, np.sqrt(2 * ke / self.disc.I))
        if len(crossings) < 4:
            raise RunError(f"case e: only {len(crossings)} zero crossings of omega at dt = {dt}")
        j = np.arange(len(crossings))
        half_period = np.polyfit(j, crossings, 1)[0]
        w = math.pi / half_period
        w_discrete = (2 / dt) * math.asin(self.w_low * dt / 2)
        return {"steps": res["steps"], "runs": 1, "wall_subprocess": res["wall_subprocess"],
                "wall_summary": res["wall_summary"], "measured": w, "exact": self.w_low,
                "error": abs(w / self.w_low - 1),
                "extra": f"{len(crossings)} crossings; Verlet's (2/dt) asin(w dt/2) = {w_discrete:.10g}, "
                         f"measured - that = {w - w_discrete:.3e} rad/s"}


def omega_zero_crossings(t, amp):
    """Zero crossings of omega from |omega| sampled every step: at each local minimum of |omega| the sign
    flips on the side of the smaller neighbour; the crossing is the root of the cubic through the four
    signed samples around it."""
    n = len(amp)
    sign = np.ones(n)
    flips = []
    for i in range(1, n - 1):
        if amp[i] <= amp[i - 1] and amp[i] < amp[i + 1]:
            flips.append(i if amp[i - 1] < amp[i + 1] else i + 1)  # the sign changes before sample flips[-1]
    s = 1.0
    last = 0
    for f in flips:
        sign[last:f] = s
        s = -s
        last = f
    sign[last:] = s
    w = sign * amp
    out = []
    for f in flips:
        lo = f - 2
        if lo < 0 or f + 2 > n:
            continue
        tt, ww = t[lo:lo + 4], w[lo:lo + 4]
        t0 = tt[1]
        c = np.polyfit(tt - t0, ww, 3)
        r = [x.real for x in np.roots(c) if abs(x.imag) < 1e-9 * (tt[2] - tt[1]) and 0 <= x.real <= tt[2] - t0]
        if not r:
            r = [(tt[2] - t0) * ww[1] / (ww[1] - ww[2])]
        out.append(t0 + r[0])
    return np.array(out)


CASES = {"a": ImpactUndamped, "a2": ImpactUndampedCommensurate, "b": ImpactDamped, "c": ConstantTorqueStop, "c2": ConstantTorqueStopDamped,
         "d": JiangPlasticStop, "e": RollingFrequency}


# ---------------------------------------------------------------------------------------------------------
def orders(errors):
    p = [None]
    for e0, e1 in zip(errors[:-1], errors[1:]):
        p.append(math.log2(e0 / e1) if e0 > 0 and e1 > 0 else None)
    return p


def fitted_order(dts, errors):
    pts = [(math.log(d), math.log(e)) for d, e in zip(dts, errors) if e > 0]
    if len(pts) < 2:
        return None
    x, y = np.array(pts).T
    return float(np.polyfit(x, y, 1)[0])


def fmt(v, spec):
    return "" if v is None else format(v, spec)


def main(argv=None):
    ap = ArgumentParser(TOOL, description=__doc__.split("\n")[0], epilog=__doc__)
    ap.add_argument("--rondel", default="build/rondel", help="the rondel executable (default build/rondel)")
    ap.add_argument("--out", default="study-output", help="output directory (default study-output/)")
    ap.add_argument("--levels", type=int, default=6, help="number of step sizes, k = 0..levels-1 (default 6)")
    ap.add_argument("--quick", action="store_true", help="smoke check: 3 levels and 2 onset phases")
    ap.add_argument("--cases", default="a,a2,b,c,d,e", help="comma-separated cases among " + ",".join(CASES))
    ap.add_argument("--ranks", type=int, default=1, help="MPI ranks (mpirun -n N --oversubscribe "
                    "--allow-run-as-root); the errors are the same bits on any rank count")
    ap.add_argument("--launcher", choices=["auto", "mpirun", "direct"], default="auto",
                    help="auto: mpirun when --ranks > 1, else the executable directly")
    ap.add_argument("--phases", type=int, default=None, help="contact-onset phases per impact level (default 5)")
    ap.add_argument("--keep-runs", action="store_true", help="keep the run directories under OUT/runs")
    add_figure_options(ap, dpi=150)
    args = ap.parse_args(argv)
    check_figure_options(ap, args)

    levels = 3 if args.quick else args.levels
    phases = args.phases or (2 if args.quick else 5)
    if levels < 1 or phases < 1 or args.ranks < 1:
        ap.error("--levels, --phases and --ranks must be >= 1")
    keys = [c.strip() for c in args.cases.split(",") if c.strip()]
    for c in keys:
        if c not in CASES:
            ap.error(f"unknown case '{c}' (choose among {', '.join(CASES)})")
    launcher = args.launcher if args.launcher != "auto" else ("mpirun" if args.ranks > 1 else "direct")
    os.makedirs(args.out, exist_ok=True)
    if not os.access(os.path.abspath(args.rondel), os.X_OK):
        ap.error(f"the rondel executable '{args.rondel}' does not exist or is not executable "
                 "(build it: make -C build rondel, or pass --rondel)")
    return run_tool(TOOL, study, args, keys, levels, phases, launcher)


def study(args, keys, levels, phases, launcher):
    runner = Runner(args.rondel, args.ranks, args.out, launcher)

    rank_label = f"{args.ranks} rank" + ("s" if args.ranks > 1 else "")
    results = {}
    t_start = time.perf_counter()
    for key in keys:
        try:
            case = CASES[key](runner, args.out, phases)
            dt_crit = case.probe()
            dt0 = case.base_step(dt_crit)
            rows = []
            for k in range(levels):
                dt = dt0 / 2 ** k
                r = case.level(k, dt)
                r.update({"case": key, "k": k, "dt": dt, "dt_over_crit": dt / dt_crit, "ranks": args.ranks})
                rows.append(r)
                print(f"  [{key}] k={k} dt={dt:.4e} steps={r['steps']} runs={r['runs']} "
                      f"wall={r['wall_subprocess']:.3f}s ({r['wall_summary']:.4f}s in-code) "
                      f"error={r['error']:.3e}", file=sys.stderr, flush=True)
            for r, p in zip(rows, orders([r["error"] for r in rows])):
                r["order"] = p
            fit = fitted_order([r["dt"] for r in rows], [r["error"] for r in rows])
            fit_alt = None
            if all(r.get("error_alt") is not None for r in rows):
                for r, p in zip(rows, orders([r["error_alt"] for r in rows])):
                    r["order_alt"] = p
                fit_alt = fitted_order([r["dt"] for r in rows], [r["error_alt"] for r in rows])
            results[key] = {"case": case, "rows": rows, "fit": fit, "fit_alt": fit_alt, "dt_crit": dt_crit}
        except RunError as e:
            raise RunError(f"case {key}: {e}") from None
    elapsed = time.perf_counter() - t_start

    # tables
    fields = ["case", "ranks", "k", "dt", "dt_over_crit", "steps", "runs", "wall_subprocess", "wall_summary",
              "disc_steps_per_s", "measured", "exact", "error", "order", "error_alt", "order_alt", "extra"]
    all_rows = []
    for key, R in results.items():
        all_rows += R["rows"]

    def csv_rows(rows):
        return [{k: ("" if r.get(k) is None else r.get(k)) for k in fields} for r in rows]

    for key, R in results.items():
        with open(os.path.join(args.out, f"{key}.csv"), "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            w.writerows(csv_rows(R["rows"]))
    with open(os.path.join(args.out, "combined.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(csv_rows(all_rows))

    md = [f"Error against run time: {rank_label}, {levels} levels dt_k = dt0/2^k (dt0 = 0.2 dt_crit; a2: the "
          f"largest step below it that divides t_c), {runner.count} rondel runs in {elapsed:.0f} s", ""]
    md.append("| case | ranks | k | dt [s] | dt/dt_crit | steps | runs | wall, subprocess [s] | wall, summary [s] "
              "| error | p | alt. error | alt. p |")
    md.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in all_rows:
        md.append(f"| {r['case']} | {r['ranks']} | {r['k']} | {r['dt']:.4e} | {r['dt_over_crit']:.5f} | {r['steps']} | "
                  f"{r['runs']} | {r['wall_subprocess']:.3f} | {r['wall_summary']:.4g} | {r['error']:.3e} | "
                  f"{fmt(r['order'], '.2f')} | {fmt(r.get('error_alt'), '.3e')} | {fmt(r.get('order_alt'), '.2f')} |")
    md += ["", "| case | error measure | exact | dt_crit [s] (log / docs/physics.md 4) | limiting mode | expected p "
           "| fitted p (all levels) | p of the last pair | alt. error: fitted p |",
           "|---|---|---|---|---|---|---|---|---|"]
    for key, R in results.items():
        c = R["case"]
        last = R["rows"][-1]["order"]
        alt = f"{c.alt_name}: {fmt(R['fit_alt'], '.2f')}" if R["fit_alt"] is not None else ""
        md.append(f"| {mdc(c.title)} | {mdc(c.error_name)} | {c.exact:.12g} | {R['dt_crit']:.6g} / "
                  f"{c.dt_crit_tool:.6g} | {c.crit_mode} | {mdc(c.expected_order)} | {fmt(R['fit'], '.2f')} | "
                  f"{fmt(last, '.2f')} | {mdc(alt)} |")
    notes = [f"- {key}: {n}" for key, R in results.items() for n in R["case"].notes]
    notes += [f"- {r['case']} k={r['k']}: {r['extra']}" for r in all_rows if r.get("extra")]
    if notes:
        md += ["", "Notes:", ""] + notes
    text = "\n".join(md) + "\n"
    with open(os.path.join(args.out, "combined.md"), "w") as f:
        f.write(text)
    print(text)

    figure = None if args.no_plot else plot(results, os.path.join(args.out, "error_vs_runtime"), rank_label, args)
    if not args.keep_runs:
        shutil.rmtree(os.path.join(args.out, "runs"), ignore_errors=True)
    print(f"error_vs_runtime: wrote {args.out}/combined.md, combined.csv, <case>.csv"
          + (f", {figure}" if figure else ""), file=sys.stderr)
    return 0


def mdc(text):
    """A markdown table cell: pipes escaped."""
    return str(text).replace("|", "\\|")


def plot(results, stem, rank_label, args):
    plt = pyplot()
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(15, 6.5))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, (key, R) in enumerate(results.items()):
        c = colors[i % len(colors)]
        case = R["case"]
        rows = [r for r in R["rows"] if r["error"] > 0]
        if rows:
            err = [r["error"] for r in rows]
            label = f"{case.title} [{rank_label}]: fitted p = {fmt(R['fit'], '.2f')} (expected {case.expected_order})"
            ax1.loglog([r["wall_summary"] for r in rows], err, "o-", color=c, label=label)
            ax1.loglog([r["wall_subprocess"] for r in rows], err, "s:", color=c, alpha=0.4, markersize=3)
            ax2.loglog([r["dt"] for r in rows], err, "o-", color=c, label=label)
        alt = [r for r in R["rows"] if r.get("error_alt")]
        if alt and R["fit_alt"] is not None:
            label = f"({key}) {case.alt_name} [{rank_label}]: fitted p = {fmt(R['fit_alt'], '.2f')}"
            ax1.loglog([r["wall_summary"] for r in alt], [r["error_alt"] for r in alt], "^--", color=c,
                       markerfacecolor="none", label=label)
            ax2.loglog([r["dt"] for r in alt], [r["error_alt"] for r in alt], "^--", color=c,
                       markerfacecolor="none", label=label)
    ax1.set_xlabel("wall time of one run [s]: solid = summary.txt (time loop); dotted = subprocess "
                   "(includes ~1 s of MPI start-up)", fontsize=8)
    ax1.set_ylabel("error (each case's own measure, see the legend)")
    ax1.set_title(f"Error against wall time ({rank_label})")
    ax2.set_xlabel("dt [s]")
    ax2.set_title(f"Error against step size ({rank_label})")
    # a fan of reference slopes 1, 2, 3 over one decade of dt, in the lower left corner
    (xlo, xhi), (ylo, yhi) = ax2.get_xlim(), ax2.get_ylim()
    x0, x1 = xlo * 1.3, xlo * 13
    y0 = ylo * 1.5
    for p in (1, 2, 3):
        ax2.loglog([x0, x1], [y0, y0 * (x1 / x0) ** p], color="grey", lw=0.9, ls="--")
        ax2.annotate(f"slope {p}", (x1, y0 * (x1 / x0) ** p), fontsize=7, color="grey",
                     xytext=(2, -3), textcoords="offset points")
    ax2.set_xlim(xlo, xhi)
    ax2.set_ylim(ylo, yhi)
    for ax in (ax1, ax2):
        ax.grid(True, which="both", alpha=0.25)
    handles, labels = ax2.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=7.5, frameon=False)
    fig.suptitle("Rondel validation cases with exact answers: error against run time and step size "
                 f"({rank_label})", fontsize=11)
    fig.tight_layout(rect=(0, 0.16, 1, 1))
    return save_figure(fig, stem, args)


if __name__ == "__main__":
    sys.exit(main())
