"""The runs of tools/error_vs_runtime.py and the exact answers they are measured against: the standard objects of
docs/validation.md section 0, the closed forms of its sections 2, 4 and 5 and of docs/physics.md section 4, and a
Runner that makes one rondel run of a case and reads its figures back (log, summary, final.csv, diagnostics.csv)
with the rondel package."""
import math
import os
import shutil
import subprocess
import time

from rondel import CheckFailed, RondelError, open_run, read_csv

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
