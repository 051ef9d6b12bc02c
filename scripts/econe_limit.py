#!/usr/bin/python3
"""Reference computation of the h -> 0 limit of the n = 2 excess cone (e-cone).

For h -> 0 the sheet is the cone x(r, s) = r u(s), where u is a closed curve of length
L = 2*pi + phi_e on the unit sphere that minimises the bending functional  B = \\oint kappa_g^2 ds
(a spherical elastica; Mueller, Ben Amar, Guven, PRL 101, 156104 (2008)). This script computes
the n = 2 branch in two independent ways:

  1. Discrete: u is a geodesic polygon with N vertices and N equal great-circle edges of
     length L/N. The unknowns are the turning angles theta_i (angle between incoming and
     outgoing edge in the tangent plane at vertex i), so equal edge lengths hold exactly;
     B_h = sum_i theta_i^2 / (L/N). The D2d ("baseball seam") symmetry of the n = 2 e-cone is
     imposed: one eighth of the curve (tip of an "up" lobe -> inflection point) is computed,
     with the tip on the mirror plane y = 0 at height angle alpha and the inflection point
     on the C2 axis (1, 1, 0)/sqrt(2). Those two closure conditions are equality constraints;
     the KKT system is solved by Newton's method with exact first and second derivatives
     (a turning angle rigidly rotates the rest of the curve about the vertex's position
     vector, which makes the derivatives closed-form). Continuation in phi_e from a small
     n = 2 perturbation of the great circle, warm-starting every step.
  2. Continuum: shooting on the Euler-Lagrange equation of the spherical elastica,
     kappa'' = -kappa^3/2 - mu kappa (mu = 1 - sigma/2, sigma the length multiplier), with the
     Darboux frame x' = t, t' = -x + kappa (x cross t), same symmetry conditions, solved to
     ODE tolerance 1e-12. The self-contact point phi_e^kiss is solved for directly.

For every phi_e it reports the smallest chord between vertices whose arclength separation is
at least L/8 (the rim gap at r = R = 1 in units of R), the angle between the generators of the
closest pair, and B/L (proportional to the paper's E_b-hat = int U_b dOmega / A, because for a
cone int U_b dOmega = ln(R/R_c) B and A = L R^2 / 2). It locates phi_e^kiss (gap = 0) for each
N, Richardson-extrapolates in N, reports the closing rate -d(gap)/d(phi_e) and the location of
the maximum of B/L, and checks (optionally) that the symmetric solution is a local minimum of
the full, symmetry-free discrete problem.

usage: econe_limit.py [--Ns 200,400,800,1600,3200] [--dphi 0.1] [--phi-max 7.3]
                      [--stability-N 400] [--no-ode] [--quick]
Runs in well under a minute with the defaults on one core.
"""
import argparse
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import null_space
from scipy.optimize import brentq, fsolve, minimize_scalar

TWO_PI = 2.0 * math.pi
# Closure conditions for the eighth-arc: the end vertex lies on the C2 axis (1,1,0)/sqrt(2).
W_CLOSE = np.array([[0.0, 0.0, 1.0], [1.0 / math.sqrt(2.0), -1.0 / math.sqrt(2.0), 0.0]])


# ----------------------------------------------------------------------------------------
# Derivatives of a vector carried rigidly by a chain of rotations.
# Parameter p rotates everything downstream of it by c_p * dp about the world axis a_p.
# For y downstream of all parameters and a fixed w:
#   d(w.y)/dp        = c_p a_p . (y x w)
#   d2(w.y)/dp dq    = c_p c_q [ (a_p.y)(a_q.w) - (w.y)(a_p.a_q) ]   for p upstream of / equal to q
# ----------------------------------------------------------------------------------------
def chain_gradient(axes, coef, y, w):
    return coef * (axes @ np.cross(y, w))


def chain_hessian(axes, coef, y, w):
    u = axes @ y
    v = axes @ w
    m = np.outer(coef, coef) * (np.outer(u, v) - float(w @ y) * (axes @ axes.T))
    return np.triu(m) + np.triu(m, 1).T


def min_chord(points, exclude_index_sep):
    """Smallest chord between vertices at cyclic index separation >= exclude_index_sep.

    Returns (distance, i, j)."""
    n = len(points)
    best = (np.inf, -1, -1)
    idx = np.arange(n)
    block = 512
    for start in range(0, n, block):
        rows = points[start:start + block]
        d2 = np.maximum(2.0 - 2.0 * rows @ points.T, 0.0)
        sep = np.abs(idx[start:start + block, None] - idx[None, :])
        sep = np.minimum(sep, n - sep)
        d2[sep < exclude_index_sep] = np.inf
        k = int(np.argmin(d2))
        i, j = divmod(k, n)
        if d2[i, j] < best[0] ** 2:
            best = (math.sqrt(d2[i, j]), start + i, j)
    return best


# ----------------------------------------------------------------------------------------
# Discrete symmetric e-cone
# ----------------------------------------------------------------------------------------
class DiscreteEcone:
    """Geodesic N-gon with D2d symmetry; unknowns p = [alpha, theta_0, ..., theta_{m-1}], m = N/8.

    theta_0 is the turning angle at the lobe tip (on the mirror plane; half of it belongs to the
    computed eighth), theta_k (1 <= k < m) the others; theta_m = 0 at the inflection point."""

    def __init__(self, n):
        if n % 8 != 0 or n < 16:
            raise ValueError("N must be a multiple of 8 and >= 16, got %d" % n)
        self.n = n
        self.m = n // 8
        self.w_energy = np.r_[0.0, 4.0, 8.0 * np.ones(self.m - 1)]  # copies of each angle in B

    def walk(self, p, delta):
        """End vertex of the eighth-arc and the rotation axes/rates of all parameters."""
        m = self.m
        alpha = p[0]
        x = np.array([math.cos(alpha), 0.0, math.sin(alpha)])
        t = np.array([0.0, 1.0, 0.0])
        nrm = np.cross(x, t)
        axes = np.empty((m + 1, 3))
        coef = np.ones(m + 1)
        axes[0] = (0.0, -1.0, 0.0)  # alpha rotates the whole curve about -y
        axes[1] = x
        coef[1] = 0.5
        h = 0.5 * p[1]
        t, nrm = t * math.cos(h) + nrm * math.sin(h), -t * math.sin(h) + nrm * math.cos(h)
        cd, sd = math.cos(delta), math.sin(delta)
        for k in range(1, m + 1):
            x, t = x * cd + t * sd, -x * sd + t * cd
            if k < m:
                axes[k + 1] = x
                c, s = math.cos(p[k + 1]), math.sin(p[k + 1])
                t, nrm = t * c + nrm * s, -t * s + nrm * c
        return x, axes, coef

    def full_turning(self, p):
        """Turning angles of all N vertices, starting at the tip of an up lobe."""
        th = p[1:]
        quarter = np.r_[th, 0.0, -th[:0:-1]]  # tip, ..., inflection (0), ..., before next tip
        return np.r_[quarter, -quarter, quarter, -quarter]

    def full_curve(self, p, delta):
        """All N vertex positions (in order) and the closure error of the full walk."""
        theta = self.full_turning(p)
        alpha = p[0]
        x = np.array([math.cos(alpha), 0.0, math.sin(alpha)])
        t = np.array([0.0, 1.0, 0.0])
        nrm = np.cross(x, t)
        h = -0.5 * theta[0]  # incoming tangent at the tip
        t, nrm = t * math.cos(h) + nrm * math.sin(h), -t * math.sin(h) + nrm * math.cos(h)
        frame0 = np.array([x, t, nrm])
        pts = np.empty((self.n, 3))
        axes = np.empty((self.n, 3))
        cd, sd = math.cos(delta), math.sin(delta)
        for k in range(self.n):
            pts[k] = x
            axes[k] = x
            c, s = math.cos(theta[k]), math.sin(theta[k])
            t, nrm = t * c + nrm * s, -t * s + nrm * c
            x, t = x * cd + t * sd, -x * sd + t * cd
        frame_end = np.array([x, t, nrm])
        closure = float(np.max(np.abs(frame_end - frame0)))
        return pts, axes, theta, frame0, frame_end, closure

    def energy(self, p, delta):
        return float(self.w_energy @ (p * p)) / delta

    def initial_guess(self, phi):
        """Small-amplitude n = 2 mode: z = eps cos(2 varphi), kappa_g = -3 eps cos(4 pi s / L)."""
        L = TWO_PI + phi
        delta = L / self.n
        eps = math.sqrt(2.0 * phi / (3.0 * math.pi))
        s = np.arange(self.m) * delta
        theta = -3.0 * eps * np.cos(4.0 * math.pi * s / L) * delta
        return np.r_[math.asin(eps), theta]

    def solve(self, phi, p, lam=None, tol=1e-11, maxit=60):
        """Newton on the KKT system of min B_h s.t. end vertex on the C2 axis.

        Returns (p, lam, info) with info = dict(iters, reduced_min_eig)."""
        L = TWO_PI + phi
        delta = L / self.n
        we = 2.0 * self.w_energy / delta  # Hessian of B_h (diagonal)
        p = p.copy()
        lam = np.zeros(2) if lam is None else lam.copy()
        nv = len(p)
        for it in range(maxit):
            x, axes, coef = self.walk(p, delta)
            g = W_CLOSE @ x
            jac = np.array([chain_gradient(axes, coef, x, w) for w in W_CLOSE])
            r1 = we * p + jac.T @ lam
            scale = max(1.0, float(np.max(np.abs(we * p))))
            hl = np.diag(we)
            for i, w in enumerate(W_CLOSE):
                hl += lam[i] * chain_hessian(axes, coef, x, w)
            if np.max(np.abs(r1)) < tol * scale and np.max(np.abs(g)) < tol:
                z = null_space(jac)
                red = np.linalg.eigvalsh(z.T @ hl @ z)
                return p, lam, {"iters": it, "reduced_min_eig": float(red[0]) * delta}
            kkt = np.zeros((nv + 2, nv + 2))
            kkt[:nv, :nv] = hl
            kkt[:nv, nv:] = jac.T
            kkt[nv:, :nv] = jac
            step = np.linalg.solve(kkt, -np.r_[r1, g])
            dp, dl = step[:nv], step[nv:]
            big = float(np.max(np.abs(dp)))
            f = 1.0 if big < 0.2 else 0.2 / big  # keep far-from-converged steps local
            p += f * dp
            lam += f * dl
        raise RuntimeError("Newton did not converge at phi_e = %.6f, N = %d" % (phi, self.n))

    def observables(self, phi, p, with_chord=True):
        L = TWO_PI + phi
        delta = L / self.n
        alpha = p[0]
        out = {
            "phi": phi,
            "alpha": alpha,
            "B": self.energy(p, delta),
            "tip_gap": 2.0 * math.cos(alpha),  # signed: tips of the two up lobes
        }
        out["B_over_L"] = out["B"] / L
        if with_chord:
            pts, _, _, _, _, closure = self.full_curve(p, delta)
            d, i, j = min_chord(pts, self.n // 8)
            out.update(
                chord=d,
                chord_pair=(i, j),
                gen_angle=math.degrees(math.acos(max(-1.0, min(1.0, pts[i] @ pts[j])))),
                closure=closure,
            )
        return out


def full_problem_stability(model, phi, p):
    """Check the symmetric solution against the symmetry-free discrete problem.

    Unknowns: all N turning angles; constraint: the walk closes (end frame = start frame,
    three conditions vee(skew(R_total)) = 0). Returns (stationarity residual relative to
    |grad B|, the three lowest eigenvalues of the reduced Hessian times delta)."""
    L = TWO_PI + phi
    delta = L / model.n
    pts, axes, theta, frame0, frame_end, _ = model.full_curve(p, delta)
    coef = np.ones(model.n)
    # rows of frame arrays are the frame vectors; R_total = F_end^T-columns * F_0
    rot = frame_end.T @ frame0
    grad_b = 2.0 * theta / delta
    pairs = [((2, 1), (1, 2)), ((0, 2), (2, 0)), ((1, 0), (0, 1))]
    eye = np.eye(3)
    jac = np.zeros((3, model.n))
    hess = []
    for r, ((a, b), (c, d)) in enumerate(pairs):
        yb, yd = rot @ eye[b], rot @ eye[d]
        jac[r] = 0.5 * (chain_gradient(axes, coef, yb, eye[a]) - chain_gradient(axes, coef, yd, eye[c]))
        hess.append(0.5 * (chain_hessian(axes, coef, yb, eye[a]) - chain_hessian(axes, coef, yd, eye[c])))
    lam = -np.linalg.lstsq(jac.T, grad_b, rcond=None)[0]
    resid = float(np.linalg.norm(grad_b + jac.T @ lam) / np.linalg.norm(grad_b))
    hl = np.diag(np.full(model.n, 2.0 / delta))
    for r in range(3):
        hl += lam[r] * hess[r]
    z = null_space(jac)
    eig = np.linalg.eigvalsh(z.T @ hl @ z) * delta
    return resid, eig[:3]


# ----------------------------------------------------------------------------------------
# Continuum shooting
# ----------------------------------------------------------------------------------------
def _rhs(_s, y, mu):
    x, t, k, kp = y[0:3], y[3:6], y[6], y[7]
    n = np.cross(x, t)
    return np.r_[t, -x + k * n, kp, -0.5 * k ** 3 - mu * k, k * k]


def shoot(alpha, k0, mu, s_end, dense=False):
    y0 = [math.cos(alpha), 0.0, math.sin(alpha), 0.0, 1.0, 0.0, k0, 0.0, 0.0]
    return solve_ivp(_rhs, (0.0, s_end), y0, method="DOP853", rtol=1e-12, atol=1e-13,
                     args=(mu,), dense_output=dense)


def shoot_residual(alpha, k0, mu, L):
    y = shoot(alpha, k0, mu, L / 8.0).y[:, -1]
    return np.array([y[6], y[2], (y[0] - y[1]) / math.sqrt(2.0)]), 8.0 * y[8]


class ContinuumEcone:
    def __init__(self):
        self.state = None  # (alpha, k0, mu) of the last solved point

    def solve_fixed_phi(self, phi, guess=None):
        L = TWO_PI + phi
        g = np.array(guess if guess is not None else self.state)
        sol, info, ier, msg = fsolve(lambda v: shoot_residual(v[0], v[1], v[2], L)[0], g,
                                     xtol=1e-13, full_output=True)
        res, b = shoot_residual(sol[0], sol[1], sol[2], L)
        if ier != 1 and np.max(np.abs(res)) > 1e-9:
            raise RuntimeError("shooting failed at phi_e = %g: %s" % (phi, msg))
        self.state = sol
        return sol, b

    def solve_fixed_alpha(self, alpha, guess):
        """Unknowns (phi_e, k0, mu) for a prescribed tip height angle alpha."""
        sol, info, ier, msg = fsolve(
            lambda v: shoot_residual(alpha, v[1], v[2], TWO_PI + v[0])[0], np.array(guess),
            xtol=1e-13, full_output=True)
        res, b = shoot_residual(alpha, sol[1], sol[2], TWO_PI + sol[0])
        if ier != 1 and np.max(np.abs(res)) > 1e-9:
            raise RuntimeError("shooting failed at alpha = %g: %s" % (alpha, msg))
        return sol, b

    def curve(self, phi, state, npts=4000):
        L = TWO_PI + phi
        sol = shoot(state[0], state[1], state[2], L, dense=True)
        s = np.linspace(0.0, L, npts, endpoint=False)
        y = sol.sol(s)
        end = sol.y[:, -1]
        closure = float(np.max(np.abs(end[0:6] - sol.y[0:6, 0])))
        return y[0:3].T, closure


def guess_from_discrete(model, phi, p):
    """(alpha, kappa_tip, mu) for the shooting from a discrete solution."""
    delta = (TWO_PI + phi) / model.n
    kc = model.full_turning(p) / delta
    kpp = (np.roll(kc, -1) - 2.0 * kc + np.roll(kc, 1)) / delta ** 2
    mu = -float(kc @ (kpp + 0.5 * kc ** 3) / (kc @ kc))
    return np.array([p[0], p[1] / delta, mu])


# ----------------------------------------------------------------------------------------
def richardson(ns, vals):
    """Observed order from the three finest levels and the extrapolated value (ratio 2)."""
    if len(vals) < 3:
        return float("nan"), float("nan"), float("nan")
    a, b, c = vals[-3:]
    if (b - c) == 0 or (a - b) / (b - c) <= 0:
        return float("nan"), c, abs(b - c)
    order = math.log((a - b) / (b - c)) / math.log(ns[-2] / ns[-3])
    ratio = ns[-1] / ns[-2]
    ext = c + (c - b) / (ratio ** order - 1.0)
    ext2 = c + (c - b) / (ratio ** 2 - 1.0)
    return order, ext, max(abs(ext - c), abs(ext - ext2))


def run_discrete(n, phis):
    model = DiscreteEcone(n)
    p = model.initial_guess(phis[0])
    lam = None
    sols = []
    prev = []
    for phi in phis:
        if len(prev) >= 2:  # secant predictor
            (f1, p1), (f2, p2) = prev[-2], prev[-1]
            p = p2 + (p2 - p1) * (phi - f2) / (f2 - f1)
        p, lam, info = model.solve(phi, p, lam)
        prev = (prev + [(phi, p.copy())])[-2:]
        sols.append((phi, p.copy(), lam.copy(), info))
    # phi_e^kiss: signed tip gap 2 cos(alpha) = 0
    kiss = None
    for (f1, p1, l1, _), (f2, p2, l2, _) in zip(sols[:-1], sols[1:]):
        if math.cos(p1[0]) > 0.0 >= math.cos(p2[0]):
            cache = {"p": p1, "lam": l1}

            def gap(phi):
                q, lm, _ = model.solve(phi, cache["p"], cache["lam"])
                cache["p"], cache["lam"] = q, lm
                return 2.0 * math.cos(q[0])

            kiss = brentq(gap, f1, f2, xtol=1e-11, rtol=1e-14)
            pk, lk, infok = model.solve(kiss, cache["p"], cache["lam"])
            break
    result = {"model": model, "sols": sols, "kiss": kiss}
    if kiss is not None:
        dphi = 1e-3
        gp = 2.0 * math.cos(model.solve(kiss + dphi, pk, lk)[0][0])
        gm = 2.0 * math.cos(model.solve(kiss - dphi, pk, lk)[0][0])
        result["rate"] = -(gp - gm) / (2.0 * dphi)
        result["kiss_p"] = pk
        result["kiss_info"] = infok
        # average closing rate from phi_e = 7 to contact, and the chord check just before contact
        p7 = None
        for f, q, lm, _ in sols:
            if abs(f - 7.0) < 1e-9:
                p7 = q
        if p7 is None:
            p7 = model.solve(7.0, pk, lk)[0]
        result["gap7"] = 2.0 * math.cos(p7[0])
        result["pre"] = model.observables(kiss - 0.02, model.solve(kiss - 0.02, pk, lk)[0])
    # maximum of B/L
    bl = [model.energy(q, (TWO_PI + f) / n) / (TWO_PI + f) for f, q, _, _ in sols]
    i = int(np.argmax(bl))
    if 0 < i < len(sols) - 1:
        cache = {"p": sols[i][1], "lam": sols[i][2]}

        def neg_bl(phi):
            q, lm, _ = model.solve(phi, cache["p"], cache["lam"])
            return -model.energy(q, (TWO_PI + phi) / n) / (TWO_PI + phi)

        r = minimize_scalar(neg_bl, bracket=(sols[i - 1][0], sols[i][0], sols[i + 1][0]),
                            tol=1e-10)
        result["bl_max"] = (r.x, -r.fun)
    return result


def check_derivatives():
    """Central differences (step 1e-6) against the closed-form chain derivatives."""
    model = DiscreteEcone(64)
    phi = 3.0
    delta = (TWO_PI + phi) / model.n
    p = model.initial_guess(phi) + 0.05 * np.random.default_rng(1).standard_normal(model.m + 1)

    def jac(q):
        x, axes, coef = model.walk(q, delta)
        return np.array([chain_gradient(axes, coef, x, w) for w in W_CLOSE])

    x, axes, coef = model.walk(p, delta)
    hs = [chain_hessian(axes, coef, x, w) for w in W_CLOSE]
    h = 1e-6
    eye = np.eye(len(p))
    jfd = np.array([(W_CLOSE @ (model.walk(p + h * e, delta)[0] - model.walk(p - h * e, delta)[0]))
                    / (2 * h) for e in eye]).T
    hfd = [np.array([(jac(p + h * e)[i] - jac(p - h * e)[i]) / (2 * h) for e in eye]) for i in range(2)]
    print("max |J - J_fd| = %.2e (|J|max %.2f); max |H - H_fd| = %.2e (|H|max %.2f)" % (
        np.abs(jac(p) - jfd).max(), np.abs(jac(p)).max(),
        max(np.abs(hs[i] - hfd[i]).max() for i in range(2)), max(np.abs(hh).max() for hh in hs)))


def main():
    ap = argparse.ArgumentParser(
        description=__doc__.split("\n\n")[0],
        epilog="Method and output are described in the module docstring (head of the file).")
    ap.add_argument("--Ns", default="200,400,800,1600,3200",
                    help="comma-separated vertex counts, multiples of 8, doubling (default %(default)s)")
    ap.add_argument("--dphi", type=float, default=0.1, help="continuation step in phi_e (default %(default)s)")
    ap.add_argument("--phi-max", type=float, default=7.3, help="last phi_e of the continuation (default %(default)s)")
    ap.add_argument("--stability-N", type=int, default=400,
                    help="N for the symmetry-free stability check, 0 to skip (default %(default)s)")
    ap.add_argument("--no-ode", action="store_true", help="skip the continuum shooting check")
    ap.add_argument("--quick", action="store_true", help="Ns = 200,400,800 only")
    ap.add_argument("--check-derivatives", action="store_true",
                    help="finite-difference check of the closure-constraint Jacobian/Hessian, then exit")
    args = ap.parse_args()
    if args.check_derivatives:
        check_derivatives()
        return

    t0 = time.time()
    ns = [int(v) for v in ("200,400,800" if args.quick else args.Ns).split(",")]
    nsteps = int(round((args.phi_max - args.dphi) / args.dphi))
    phis = [args.dphi * (k + 1) for k in range(nsteps)]

    results = {}
    for n in ns:
        results[n] = run_discrete(n, phis)
        print("N = %5d done (%.1f s)" % (n, time.time() - t0), file=sys.stderr)

    # ---- table for the finest N
    nf = ns[-1]
    model = results[nf]["model"]
    print("n = 2 e-cone, h -> 0 (spherical elastica), discrete N = %d" % nf)
    print("%6s %9s %10s %9s %9s %10s %9s %11s %9s" % (
        "phi_e", "alpha", "B=oint k^2", "B/L", "tip gap", "min chord", "gen.ang", "pair(i,j)",
        "redHmin"))
    show = {round(v, 6) for v in [0.5, 1, 2, 2.5, 3, 4, 5, 6, 6.5, 7, 7.1, 7.2]}
    for phi, p, lam, info in results[nf]["sols"]:
        if round(phi, 6) in show:
            o = model.observables(phi, p)
            i, j = o["chord_pair"]
            at_cut = min(abs(i - j), nf - abs(i - j)) == nf // 8
            print("%6.2f %9.5f %10.5f %9.6f %9.5f %9.5f%s %9.3f %5d,%5d %9.2e" % (
                phi, o["alpha"], o["B"], o["B_over_L"], o["tip_gap"], o["chord"],
                "*" if at_cut else " ", o["gen_angle"], i, j, info["reduced_min_eig"]))
    print("(alpha: tip height angle of an up lobe; tip gap = 2 cos(alpha) is the signed rim gap "
          "between the two up-lobe tips,\n vertices 0 and N/2; min chord over pairs >= L/8 apart (* = attained at that cut-off, "
          "i.e. no\n distant parts of the curve approach yet); "
          "gen.ang = angle between the closest generators in degrees;\n redHmin = lowest "
          "eigenvalue of the reduced Hessian in the symmetric class, times L/N.)")

    # ---- convergence study
    print("\nConvergence in N (discrete, symmetric eighth solved to KKT residual 1e-11)")
    print("%6s %14s %12s %12s %14s %12s %10s" % (
        "N", "phi_e^kiss", "-dgap/dphi", "gap(7.0)", "argmax B/L", "max B/L", "closure"))
    kv, rv, gv, bv, mv = [], [], [], [], []
    for n in ns:
        r = results[n]
        pre = r.get("pre", {})
        bl = r.get("bl_max", (float("nan"), float("nan")))
        print("%6d %14.9f %12.7f %12.7f %14.9f %12.8f %10.1e" % (
            n, r["kiss"], r["rate"], r["gap7"], bl[0], bl[1], pre.get("closure", float("nan"))))
        kv.append(r["kiss"]); rv.append(r["rate"]); gv.append(r["gap7"])
        bv.append(bl[0]); mv.append(bl[1])
    for name, vals in [("phi_e^kiss", kv), ("-dgap/dphi at kiss", rv), ("gap(phi_e=7)", gv),
                       ("argmax B/L", bv), ("max B/L", mv)]:
        order, ext, err = richardson(ns, vals)
        print("  Richardson %-20s observed order %5.2f  extrapolated %.9f  +- %.1e" % (
            name, order, ext, err))
    pre = results[nf]["pre"]
    print("\nJust before contact (phi_e = kiss - 0.02, N = %d): min chord %.6f between vertices "
          "%s, tip gap %.6f, generator angle %.3f deg" % (
              nf, pre["chord"], pre["chord_pair"], pre["tip_gap"], pre["gen_angle"]))
    print("Average closing rate from phi_e = 7 to contact, N = %d: gap(7)/(kiss-7) = %.5f R" % (
        nf, results[nf]["gap7"] / (results[nf]["kiss"] - 7.0)))

    # ---- stability in the symmetry-free discrete problem
    if args.stability_N:
        ns_ = args.stability_N
        rs = results.get(ns_)
        if rs is None:
            rs = run_discrete(ns_, phis)
        mdl = rs["model"]
        print("\nSymmetry-free check, N = %d (all N turning angles, 3 closure constraints):" % ns_)
        print("%8s %12s %34s" % ("phi_e", "stat.resid", "lowest reduced-Hessian eigenvalues"))
        checks = [(f, q) for f, q, _, _ in rs["sols"] if round(f, 6) in {0.5, 2.0, 4.0, 6.0, 7.0}]
        checks.append((rs["kiss"], rs["kiss_p"]))
        for f, q in checks:
            resid, eig = full_problem_stability(mdl, f, q)
            print("%8.4f %12.1e %11.3e %11.3e %11.3e" % (f, resid, eig[0], eig[1], eig[2]))
        print("(one eigenvalue ~0 is expected: sliding the vertices along the curve, a "
              "continuous symmetry of the continuum problem)")

    # ---- continuum shooting
    if not args.no_ode:
        print("\nContinuum check: shooting on kappa'' = -kappa^3/2 - mu kappa (DOP853, rtol 1e-12)")
        cont = ContinuumEcone()
        # start from the finest discrete solution at the kiss
        rk = results[nf]
        g = guess_from_discrete(model, rk["kiss"], rk["kiss_p"])
        sol, b = cont.solve_fixed_alpha(math.pi / 2.0, [rk["kiss"], g[1], g[2]])
        kiss_c = sol[0]
        da = 1e-4
        sp, _ = cont.solve_fixed_alpha(math.pi / 2.0 + da, sol)
        sm, _ = cont.solve_fixed_alpha(math.pi / 2.0 - da, sol)
        dphi_dalpha = (sp[0] - sm[0]) / (2.0 * da)
        rate_c = 2.0 / dphi_dalpha
        print("  phi_e^kiss = %.9f  (kappa_tip = %.6f, mu = %.6f, B = %.6f)" % (kiss_c, sol[1], sol[2], b))
        print("  closing rate -d(2 cos alpha)/d(phi_e) at contact = %.6f R per unit phi_e" % rate_c)
        # chord check just below contact on the continuum curve
        st, _ = cont.solve_fixed_phi(kiss_c - 0.02, [math.pi / 2 - 0.01, sol[1], sol[2]])
        pts, clos = cont.curve(kiss_c - 0.02, st, 4000)
        d, i, j = min_chord(pts, 500)
        print("  at phi_e = kiss - 0.02: min chord %.6f at samples (%d, %d) of 4000, tip gap %.6f, "
              "closure of full-length integration %.1e" % (d, i, j, 2 * math.cos(st[0]), clos))
        s7, _ = cont.solve_fixed_phi(7.0, st)
        print("  gap(phi_e = 7) = %.7f, average rate gap(7)/(kiss - 7) = %.5f" % (
            2 * math.cos(s7[0]), 2 * math.cos(s7[0]) / (kiss_c - 7.0)))
        # maximum of B/L
        bl0 = results[nf]["bl_max"][0]
        pb = [f for f in results[nf]["sols"] if abs(f[0] - round(bl0, 1)) < 1e-9][0]
        cont.state = guess_from_discrete(model, pb[0], pb[1])

        def neg_bl(phi):
            _, bb = cont.solve_fixed_phi(phi)
            return -bb / (TWO_PI + phi)

        r = minimize_scalar(neg_bl, bracket=(bl0 - 0.2, bl0, bl0 + 0.2), tol=1e-9)
        print("  B/L is maximal at phi_e = %.7f (B/L = %.8f, B = %.6f)" % (r.x, -r.fun, -r.fun * (TWO_PI + r.x)))
        for phi in (2.57,):
            _, bb = cont.solve_fixed_phi(phi)
            print("  at phi_e = %.2f: B/L = %.8f" % (phi, bb / (TWO_PI + phi)))
    print("\ntotal run time %.1f s" % (time.time() - t0))


if __name__ == "__main__":
    main()
