"""Closed-form creep of a Prony solid, the reference of the viscoelastic examples (docs/algorithms.md §11).

For a relaxation modulus G(t) = G∞ + Σ_i G_i exp(−t/τ_i) (shear or Young's), the creep compliance is the inverse of
G in the Laplace domain: J(t) = 1/G∞ + Σ_k exp(ρ_k t)/(ρ_k g′(ρ_k)), with ρ_k the roots of g(s) = G∞ + Σ G_i s/(s + λ_i),
λ_i = 1/τ_i. g has one root between each pair of consecutive poles −λ and one in (−λ_min, 0); bisection finds them.
tests/support/prony_creep.hpp is the same derivation in C++, checked there against a direct convolution.

Use from a script next to an example::

    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "tools"))
    import prony
    J = prony.creep_compliance(relaxed, moduli, times)   # J(t), 1/Pa
"""
import numpy as np


def creep_compliance(relaxed, moduli, times):
    """J(t) of the Prony series G∞ = relaxed, G_i = moduli, τ_i = times (SI), as a function of t."""
    G = np.asarray(moduli, dtype=float)
    lam = 1 / np.asarray(times, dtype=float)
    g = lambda s: relaxed + np.sum(G * s / (s + lam))
    dg = lambda s: np.sum(G * lam / (s + lam) ** 2)
    order = np.argsort(lam)
    roots = []
    for k, idx in enumerate(order):
        lo, hi = -lam[idx], (0.0 if k == 0 else -lam[order[k - 1]])
        for _ in range(400):
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            if g(mid) < 0:
                lo = mid
            else:
                hi = mid
        roots.append(0.5 * (lo + hi))
    amplitude = [1 / (r * dg(r)) for r in roots]
    return lambda t: 1 / relaxed + sum(a * np.exp(r * t) for a, r in zip(amplitude, roots))
