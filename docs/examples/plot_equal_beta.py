"""
The equal-β test
================

The paper's model gives both ellipses one ellipticity β (Eqs. 17–19) and imposes the work of
adhesion on the major axis only (Eq. 31).  Then the maximum adhesive stress σ0 is the same
on every ray θp, but the work of adhesion along a ray, Δγ(θp), is not.
:func:`dhfield.models.dh_elliptic_closure.equal_beta_spread` measures how far the paper's fields are from one
cohesive law at the pull-off: with Δγ(0) = 1, ``work_ratio`` is Δγ(π/2) itself.

A contact whose adhesion is a property of the two materials would have ``work_ratio`` = 1
everywhere; the map shows where the paper's closure departs from it.  At β0 = 1 (the
circle) the two axes coincide and the ratio is exactly 1.
"""
import matplotlib.pyplot as plt
import numpy as np

from dhfield.models import dh_elliptic_closure as closure

mu = np.geomspace(0.3, 10, 14)
beta0 = np.linspace(0.5, 1.0, 11)
spread = closure.equal_beta_spread(beta0=beta0[:, None], mu=mu[None, :], n_theta=15)

print("Delta gamma(pi/2)/Delta gamma(0) at mu = 1:",
      np.round(np.interp(1.0, mu, spread.work_ratio[0]), 3), "(beta0 = 0.5),",
      np.round(np.interp(1.0, mu, spread.work_ratio[-1]), 3), "(beta0 = 1)")

fig, (ax, ax2) = plt.subplots(1, 2, figsize=(9, 3.8), layout="constrained")
m = ax.pcolormesh(mu, beta0, spread.work_ratio, shading="nearest", cmap="viridis")
ax.set_xscale("log")
ax.set_xlabel("Tabor parameter μ")
ax.set_ylabel("initial ellipticity β0")
ax.set_title("Δγ(π/2) / Δγ(0) at pull-off")
fig.colorbar(m, ax=ax)
for k in (0, 4, 8):
    ax2.semilogx(mu, spread.work_ratio[k], label=f"β0 = {beta0[k]:.2f}")
ax2.axhline(1.0, color="k", lw=0.5)
ax2.set_xlabel("Tabor parameter μ")
ax2.set_ylabel("Δγ(π/2) / Δγ(0)")
ax2.legend()
plt.show()
