"""Escaping a degenerate optimum: a mass that the fit shrank to nothing.

A mode that the measured quantity barely shows (the HBFD's handle mode at the actuator: pole and
zero 0.03 % apart) gives the least-squares problem a flat valley of chains that fit about
equally well.  Levenberg-Marquardt in log-parameters often slides to the valley's degenerate
end: the handle mass shrinks toward zero with its element keeping the mode's frequency
(``k_i / m_i`` fixed), the neighbour takes the whole mass, and the gradient in ``log m_i``
vanishes (``m_i dRSS/dm_i -> 0``), so the solver stops on a plateau that is not the optimum
(on 1 % noise, several ``s^2`` above the valley floor).

:func:`reinflate` restarts from chains that give such a mass back its share: for a free mass
``m_i`` (``i < n - 1``) below :data:`DEGENERATE` times its neighbour ``m_{i+1}``, the pair's total
``M = m_i + m_{i+1}`` is split ``f M`` and ``(1 - f) M`` for ``f`` in :data:`SHARES`, the
element ``i`` is scaled with ``m_i`` (its mode frequency ``sqrt(k_i / m_i)`` stays where the data
put it) and its damping is raised to at least a 2 % damping ratio.  Each restart gets a short
run, the best a full run; it replaces the optimum only when it fits better.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

from analysis.identify.params import parse_key
from analysis.identify.problem import FitProblem, solve

__all__ = ["DEGENERATE", "SHARES", "degenerate_masses", "reinflate", "restart"]

#: A handle-side mass below this fraction of its neighbour is treated as shrunk to nothing.
DEGENERATE = 1e-3
#: Shares of the pair's mass given back to the shrunk mass by the restarts.
SHARES = (0.02, 0.08, 0.25)
_SHORT = 15
_MIN_RATIO = 0.02


def degenerate_masses(problem: FitProblem, theta: np.ndarray) -> list[int]:
    """Indices ``i`` of free masses ``m_i`` (``i < n - 1``) below :data:`DEGENERATE` ``m_{i+1}``."""
    chain = problem.chains(theta)
    keys = problem.keys
    out = []
    for i in range(chain.n - 1):
        if f"masses[{i}]" in keys and f"masses[{i + 1}]" in keys and f"stiffnesses[{i}]" in keys:
            if chain.masses[0, i] < DEGENERATE * chain.masses[0, i + 1]:
                out.append(i)
    return out


def restart(problem: FitProblem, theta: np.ndarray, i: int, share: float) -> np.ndarray:
    """``theta`` with the shrunk mass ``i`` given ``share`` of the pair's mass (module doc)."""
    chain = problem.chains(theta)
    m = chain.masses[0]
    total = m[i] + m[i + 1]
    new_mi = share * total
    r = new_mi / m[i]
    k = chain.stiffnesses[0, i] * r
    b = max(chain.dampings[0, i] * r, _MIN_RATIO * 2.0 * math.sqrt(k * new_mi))
    values = {f"masses[{i}]": new_mi, f"masses[{i + 1}]": total - new_mi, f"stiffnesses[{i}]": k,
              f"dampings[{i}]": b}
    out = np.array(theta, float)
    for j, key in enumerate(problem.keys):
        if key in values:
            out[j] = math.log(values[key])
        else:
            parse_key(key, chain.n)
    return out


def reinflate(problem: FitProblem, sol: optimize.OptimizeResult, max_nfev: int) -> optimize.OptimizeResult:
    """``sol``, or a better optimum from the restarts of the module doc when a mass shrank."""
    idx = degenerate_masses(problem, sol.x)
    if not idx:
        return sol
    starts = [restart(problem, sol.x, i, f) for i in idx for f in SHARES]
    short = min((solve(problem, th, _SHORT) for th in starts), key=lambda r: r.cost)
    full = solve(problem, short.x, max_nfev)
    return full if full.cost < sol.cost else sol
