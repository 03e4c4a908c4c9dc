"""
A boundary-element solve: contact and cohesive zone
===================================================

:func:`dhfield.bem.adhesive_pull_off` solves the adhesive contact self-consistently on an
N × N grid (Dugdale law, load control) and unloads it to the pull-off.  Here β0 = 0.8,
μ = 1 on a small grid (N = 128, a few seconds); the ground truth of :doc:`/theory/bem`
uses N up to 1024 and extrapolates over grids.

The map shows the state nearest to the pull-off: the cells in contact, and the cohesive
zone round them, with the contact ellipse of the paper's model (β = β0) for comparison.
The BEM's contact and adhesive ellipses have their own ellipticities, β_ab and β_cd.
"""
import matplotlib.pyplot as plt
import numpy as np

import dhfield
from dhfield import bem

mu, beta0 = 1.0, 0.8
res = bem.adhesive_pull_off(mu=mu, beta0=beta0, n=128)
print(f"BEM: W*max = {res.W_star:.4f}, a* = {res.a_star:.3f}, b/a = {res.ellipticity:.3f}, "
      f"d/c = {res.adhesive_ellipticity:.3f}, converged = {res.converged}, {res.n_steps} states")
paper = dhfield.pull_off(mu=mu, beta0=beta0)
print(f"paper's model: W*max = {float(paper.W_star):.4f}, a* = {float(paper.a_star):.3f}")

state = res.path.pull_off_state
zone = np.where(state.contact, 2.0, np.clip(state.cohesive, 0.0, 1.0))   # 2: contact, (0, 1]: zone
x, y = state.grid.x, state.grid.y                                       # cell centres [c_r]
fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 4.2), layout="constrained")
ax.pcolormesh(x, y, zone.T, cmap="Blues", vmin=0, vmax=2, shading="nearest")
ax.set_aspect("equal")
t = np.linspace(0, 2 * np.pi, 200)
a = float(paper.a_star)
ax.plot(a * np.cos(t), beta0 * a * np.sin(t), "r--", lw=1, label="paper's contact ellipse")
ax.set_xlabel("x / c_r")
ax.set_ylabel("y / c_r")
ax.set_title("contact (dark) and cohesive zone (light)")
ax.legend(loc="upper right", fontsize=8)
lim = 1.3 * max(res.c_star, a)
ax.set_xlim(-lim, lim)
ax.set_ylim(-lim, lim)

p = state.pressure
ax2.plot(x, p[:, np.argmin(np.abs(y))], label="major axis (y ≈ 0)")
ax2.plot(y, p[np.argmin(np.abs(x)), :], label="minor axis (x ≈ 0)")
ax2.axhline(-mu, color="k", ls=":", lw=1, label="−σ0 = −μ (Dugdale)")
ax2.set_xlim(-lim, lim)
ax2.set_xlabel("position / c_r")
ax2.set_ylabel("pressure [E* c_r / R]")
ax2.set_title("pressure at pull-off")
ax2.legend(fontsize=8)
plt.show()
