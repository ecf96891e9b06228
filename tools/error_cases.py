"""The cases of tools/error_vs_runtime.py (docs/validation.md section 7): each builds its scene, runs it at a step
size through a Runner (error_runs.py) and measures its error against the exact answer. CASES maps the keys of
--cases to them."""
import math
import os

import numpy as np

from error_runs import (G, R5, RHO, SET_J, THICK, RollingDisc, RunError, constant_torque_compliant_stop,
                        contact_time_exact, critical_step_tool, disc_mass, restitution_exact, rolling_mode_low,
                        write_ini, write_scene)


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
