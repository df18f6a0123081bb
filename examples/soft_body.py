#!/usr/bin/python3
"""A soft ball springs off a soft block and falls back onto it, with pdd's contact energy.

Coupling (docs/definitions.md "Contact energy"; README "Contact energy"). Each time step of
implicit (backward) Euler minimises the incremental potential

    Phi(x) = 1/(2 dt^2) (x - x_pred)^T M (x - x_pred) + W_el(x) - f_g . x + k E(x),

x_pred = x_n + dt v_n, M the lumped mass, W_el linear FEM elasticity (small strain, Lame
parameters from Young's modulus and Poisson's ratio), f_g gravity and E = pdd.contact_energy
(sum over intersecting element pairs of (V_a V_b)^(1/3) pdd2_global, rest volumes). The
minimiser: L-BFGS whose initial inverse Hessian is the Newton matrix M/dt^2 + K + k H_E, H_E
pdd's Gauss-Newton Hessian (positive semi-definite, so the matrix is positive definite), the
gradient with k dE/dx, and a backtracking line search on Phi (Armijo), until the residual force
is below 1e-5 of the weight (Scene.step says why not plain Newton). The block's bottom
vertices are fixed (the floor). The start (ball sunk 0.06 into the block) is made
intersection-free by pdd.resolve; the rest shapes are the bodies before resolving, so the
resolve's deformation is stored as elastic energy (1.45 at the start, against the 0.125 kinetic
of the ball thrown down at 1 m/s): released, it pushes the ball off the block (airborne from
step 6, highest at step 18), and the ball falls back onto it (step 31), bounces and lands
again (step 52). With --rest resolved the resolved start is the rest shape (no stored strain):
the thrown ball presses into the block and comes to rest on it.

    PYTHONPATH=build/python /usr/bin/python3 examples/soft_body.py [--steps 60] [--out soft_body_out] [--rest original|resolved]

writes out/ball_block_NNNN.vtu (ParaView: open the series) and out/soft_body.png (contact energy,
largest pdd2_global and number of contact pairs per step).
"""
import argparse
import os

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import pdd

KUHN = [(0, 1, 3, 7), (0, 1, 5, 7), (0, 2, 3, 7), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 6, 7)]


def grid(n, lo, hi):
    """A box [lo, hi] as n[0] x n[1] x n[2] cubes, each split into 6 tetrahedra (Kuhn)."""
    axes = [np.linspace(lo[d], hi[d], n[d] + 1) for d in range(3)]
    V = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
    idx = np.arange(len(V)).reshape(n[0] + 1, n[1] + 1, n[2] + 1)
    T = []
    for i in range(n[0]):
        for j in range(n[1]):
            for k in range(n[2]):
                c = [idx[i + (b >> 2 & 1), j + (b >> 1 & 1), k + (b & 1)] for b in range(8)]
                T += [[c[a] for a in t] for t in KUHN]
    return V, np.array(T, dtype=np.int64)


def ball(n, radius, centre):
    """A cube grid mapped onto a ball (x -> x |x|_inf / |x|_2)."""
    V, T = grid((n, n, n), (-1, -1, -1), (1, 1, 1))
    r2 = np.linalg.norm(V, axis=1)
    scale = np.where(r2 > 0, np.abs(V).max(axis=1) / np.where(r2 > 0, r2, 1), 0)
    return V * scale[:, None] * radius + centre, T


def stiffness(V, T, young, poisson):
    """Linear elasticity: K (3n x 3n sparse) and the lumped mass per vertex (density 1)."""
    lam = young * poisson / ((1 + poisson) * (1 - 2 * poisson))
    mu = young / (2 * (1 + poisson))
    rows, cols, vals = [], [], []
    mass = np.zeros(len(V))
    for t in T:
        X = V[t]
        Dm = (X[1:] - X[0]).T
        vol = abs(np.linalg.det(Dm)) / 6
        Binv = np.linalg.inv(Dm)
        grads = np.vstack([-Binv.sum(axis=0), Binv])  # shape-function gradients (4 x 3)
        B = np.zeros((6, 12))
        for a in range(4):
            gx, gy, gz = grads[a]
            B[:, 3 * a:3 * a + 3] = [[gx, 0, 0], [0, gy, 0], [0, 0, gz], [gy, gx, 0], [0, gz, gy], [gz, 0, gx]]
        C = np.zeros((6, 6))
        C[:3, :3] = lam
        C[np.arange(3), np.arange(3)] += 2 * mu
        C[np.arange(3, 6), np.arange(3, 6)] = mu
        Ke = vol * B.T @ C @ B
        dofs = np.ravel([[3 * v, 3 * v + 1, 3 * v + 2] for v in t])
        rows.append(np.repeat(dofs, 12))
        cols.append(np.tile(dofs, 12))
        vals.append(Ke.ravel())
        mass[t] += vol / 4
    n = 3 * len(V)
    K = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
    return K, mass


class Scene:
    def __init__(self, n_ball=4, n_block=(6, 6, 3), young=2e3, poisson=0.3, k=1e7, dt=0.01, g=9.81,
                 rest="original"):
        self.VB, self.TB = grid(n_block, (-1, -1, 0), (1, 1, 0.6))
        VA, self.TA = ball(n_ball, 0.4, np.array([0.05, 0.03, 0.6 + 0.4 - 0.06]))  # sunk 0.06 into the block
        fixed_b = self.VB[:, 2] == 0
        # Start: ball and block made intersection-free by pdd.resolve (the floor vertices kept).
        VA1, VB1, report = pdd.resolve(VA, self.TA, self.VB, self.TB, fixed_b=fixed_b)
        assert report["resolved"], "pdd.resolve did not separate the start"
        # rest shapes: the bodies before resolving ("original": the resolve's deformation is then
        # elastic energy at the start), or the resolved start itself ("resolved": no stored strain)
        if rest not in ("original", "resolved"):
            raise ValueError(f"rest must be 'original' or 'resolved'; got {rest!r}")
        self.rest = np.vstack([VA, self.VB]) if rest == "original" else np.vstack([VA1, VB1])
        self.nA = len(VA)
        self.x = np.vstack([VA1, VB1])
        self.v = np.zeros_like(self.x)
        self.v[:self.nA, 2] = -1.0  # the ball is thrown down
        T = np.vstack([self.TA, self.TB + self.nA])
        self.K, m = stiffness(self.rest, T, young, poisson)
        self.M = np.repeat(m, 3)
        self.f = np.zeros_like(self.x)
        self.f[:, 2] = -g * m
        self.k, self.dt = k, dt
        fixed = np.zeros(len(self.x), bool)
        fixed[self.nA:][fixed_b] = True
        self.free = np.flatnonzero(~np.repeat(fixed, 3))

    def contact(self, x, hessian=False):
        return pdd.contact_energy(x[:self.nA], self.TA, x[self.nA:], self.TB, hessian=hessian,
                                  rest_A=self.rest[:self.nA], rest_B=self.rest[self.nA:])

    def phi(self, x, x_pred, e=None):
        d = (x - x_pred).ravel()
        u = (x - self.rest).ravel()
        e = e if e is not None else self.contact(x)
        return (0.5 / self.dt**2 * d @ (self.M * d) + 0.5 * u @ (self.K @ u) - self.f.ravel() @ x.ravel()
                + self.k * e["energy"]), e

    def phi_rounding(self, x, x_pred, e):
        """A bound on |phi(x') - phi(x)|'s rounding error for x' near x. Each term of phi is a
        dot product over N = x.size coordinates, K u's entries sums of at most 81 products (a
        vertex and its neighbours), so each is within (N + 81) u of its terms' magnitudes
        (u = 2^-53, first order); doubled for the two evaluations. (The contact energy's own
        error, ~u in practice, is left out: where it is larger the test below is stricter and
        the step ends not converged, never accepted wrongly.)"""
        d = (x - x_pred).ravel()
        u = (x - self.rest).ravel()
        mag = (0.5 / self.dt**2 * d @ (self.M * d) + 0.5 * np.abs(u) @ (abs(self.K) @ np.abs(u))
               + np.abs(self.f.ravel()) @ np.abs(x.ravel()) + self.k * e["energy"])
        return 2 * (x.size + 100) * 2.0**-53 * mag

    def gradient(self, x, x_pred, e):
        """dPhi/dx on the free coordinates."""
        d = (x - x_pred).ravel()
        u = (x - self.rest).ravel()
        g = self.M * d / self.dt**2 + self.K @ u - self.f.ravel() + self.k * e["gradient"].ravel()
        return g[self.free]

    def step(self, max_iterations=400, tol=1e-5, memory=8):
        """One implicit Euler step: minimises Phi, returns (the Phi values of the iterates,
        each below the one before or within phi_rounding of it, kept in self.allowances; the
        contact energy's dict at the result; whether it converged).

        Converged: the residual force |dPhi/dx| on the free vertices is at most tol times the
        total weight |f_g|. A residual r moves the minimiser by about H^-1 r, at most
        dt^2 |r| / m_min (H >= M / dt^2): with tol = 1e-5 that is ~1e-5 g dt^2 (M_total / m_min),
        orders of magnitude below the contact's penetration (a depth ~1e-5, pdd2_global ~1e-10).

        Direction: L-BFGS (the last `memory` pairs of steps and gradient changes) on top of the
        Newton matrix H = M/dt^2 + K + k H_E as its initial inverse (a sparse solve per
        iteration). Why not plain Newton: H_E is the Hessian of the fixed-plane majorizer, which
        leaves out the (concave) turning of each pair's separating plane, so along the Newton
        step Phi curves 2 to 10 times less than H says; Newton steps are then far too short
        and converge only linearly (measured: after 12 iterations the residual force was still
        ~10x the weight and Phi falling by a constant amount per iteration). The secant pairs
        supply the missing curvature. Each step is then accepted by Armijo backtracking on Phi,
        so the Phi values decrease; a direction that is not a descent direction (a stale
        secant pair) is replaced by the Newton direction and the memory cleared. Near the
        minimiser the decrease Armijo asks for falls below Phi's rounding (phi_rounding: a
        ball resting on the block, residual ~1e-5 of the weight, a decrease ~1e-15 of Phi), while
        the gradient is still accurate: a step whose Phi is within that rounding of the start
        is accepted when its slope meets Armijo's condition in derivative form,
        dPhi(alpha) . d <= (2 c - 1) dPhi(0) . d (what Armijo's is for a quadratic; Hager and
        Zhang's approximate Wolfe condition, SIAM J. Optim. 16 (2005))."""
        x_pred = self.x + self.dt * self.v
        x = x_pred.copy()
        F = self.free
        weight = np.linalg.norm(self.f.ravel()[F])
        e = self.contact(x, hessian=True)
        p, _ = self.phi(x, x_pred, e)
        g = self.gradient(x, x_pred, e)
        phis, S, Y = [p], [], []
        self.allowances = []
        converged = False
        for _ in range(max_iterations):
            if np.linalg.norm(g) <= tol * weight:
                converged = True
                break
            H = (sp.diags(self.M / self.dt**2) + self.K + self.k * e["hessian"]).tocsr()[F][:, F]
            lu = spla.splu(H.tocsc())
            q, a = g.copy(), []
            for s_, y_ in reversed(list(zip(S, Y))):  # L-BFGS two-loop recursion
                a.append((s_ @ q) / (y_ @ s_))
                q -= a[-1] * y_
            r = lu.solve(q)
            for (s_, y_), ai in zip(zip(S, Y), reversed(a)):
                r += s_ * (ai - (y_ @ r) / (y_ @ s_))
            dF = -r
            if g @ dF >= 0:
                dF, S, Y = -lu.solve(g), [], []
            slope = g @ dF
            dx = np.zeros(x.size)
            dx[F] = dF
            alpha = 1.0
            noise = self.phi_rounding(x, x_pred, e)
            while True:  # backtracking: Armijo on Phi, or on its slope below Phi's rounding
                xn = x + alpha * dx.reshape(-1, 3)
                en = self.contact(xn, hessian=True)
                pn, _ = self.phi(xn, x_pred, en)
                gn = self.gradient(xn, x_pred, en)
                if pn <= p + 1e-4 * alpha * slope:
                    break
                if pn <= p + noise and gn @ dF <= (2 * 1e-4 - 1) * slope:
                    break
                alpha /= 2
                if alpha < 1e-12:
                    break
            if alpha < 1e-12:  # no decrease along a descent direction, in value or slope
                break
            s_, y_ = alpha * dF, gn - g
            if s_ @ y_ > 1e-12 * np.linalg.norm(s_) * np.linalg.norm(y_):  # curvature condition
                S.append(s_)
                Y.append(y_)
                if len(S) > memory:
                    S.pop(0)
                    Y.pop(0)
            x, p, g, e = xn, pn, gn, en
            phis.append(p)
            self.allowances.append(noise)
        self.v = (x - self.x) / self.dt
        self.x = x
        return phis, e, converged


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=60)
    ap.add_argument("--out", default="soft_body_out")
    ap.add_argument("--rest", choices=("original", "resolved"), default="original",
                    help="rest shapes: the bodies before pdd.resolve (its deformation stored as "
                         "strain at the start) or the resolved start (none stored)")
    args = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import meshio

    os.makedirs(args.out, exist_ok=True)
    s = Scene(rest=args.rest)
    T = np.vstack([s.TA, s.TB + s.nA])
    body = np.r_[np.zeros(len(s.TA), int), np.ones(len(s.TB), int)]
    hist = []
    for n in range(args.steps):
        phis, e, converged = s.step()
        hist.append((e["energy"], e["max_pdd2_global"], e["pairs"]))
        meshio.write(os.path.join(args.out, f"ball_block_{n:04d}.vtu"),
                     meshio.Mesh(s.x, [("tetra", T)], cell_data={"body": [body]},
                                 point_data={"velocity": s.v}))
        print(f"step {n:3d}: {'iterations' if converged else 'NOT CONVERGED after'} {len(phis) - 1:3d}, Phi {phis[0]:.6g} -> {phis[-1]:.6g}, "
              f"E {e['energy']:.3e}, max pdd2_global {e['max_pdd2_global']:.3e}, pairs {e['pairs']}")
    h = np.array(hist)
    fig, ax = plt.subplots(3, 1, sharex=True, figsize=(6, 6))
    for a, col, label in zip(ax, h.T, ["contact energy E", "largest pdd2_global", "contact pairs"]):
        a.plot(col)
        a.set_ylabel(label)
    ax[-1].set_xlabel("time step")
    fig.suptitle("soft ball on a soft block (pdd contact energy, implicit Euler)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "soft_body.png"), dpi=100)


if __name__ == "__main__":
    main()
