"""
Fitting a load curve
====================

:func:`dhfield.analysis.fit.fit_curve` estimates the work of adhesion Δγ and the maximum adhesive
stress σ0, with standard errors, from a measured curve of load against contact size.  Here
the "measurement" is synthetic: the load curve of the paper's model for a soft contact
(E = 1 MPa, two cylinders of radius 2 mm crossed at 70°, Δγ = 50 mJ/m², σ0 = 0.1 MPa),
with 1 % seeded noise on the loads, so the fit can be checked against the truth.

Δγ, which sets the whole adhesive part of the curve, comes back within its standard error.
σ0 is constrained only by the shape of the curve near pull-off and is less well determined:
in this draw it is about two standard errors from the truth.  The standard errors assume
independent, equal-variance noise (:func:`dhfield.analysis.fit.fit_curve`, Notes).
"""
import matplotlib.pyplot as plt
import numpy as np

from dhfield.analysis import dimensional as dim
from dhfield.analysis import fit

truth = dim.contact_parameters(youngs_modulus_1=1e6, poisson_ratio_1=0.5,
                               youngs_modulus_2=1e6, poisson_ratio_2=0.5,
                               cylinder_radius=2e-3, skew_angle=np.deg2rad(70),
                               work_of_adhesion=0.05, max_adhesive_stress=1e5)
curve = dim.load_curve_si(truth, n=40)                         # semi-axes [m], force [N]
keep = curve["semi_major"] > 0
a, load = curve["semi_major"][keep], curve["force"][keep]
rng = np.random.default_rng(7)
measured = load + 0.01 * np.ptp(load) * rng.standard_normal(load.size)

start = dim.contact_parameters(youngs_modulus_1=1e6, poisson_ratio_1=0.5,
                               youngs_modulus_2=1e6, poisson_ratio_2=0.5,
                               cylinder_radius=2e-3, skew_angle=np.deg2rad(70),
                               work_of_adhesion=0.03, max_adhesive_stress=2e5)   # a poor first guess
res = fit.fit_curve(measured, a, start)
print(f"dgamma = {1e3 * res.work_of_adhesion:.1f} +/- {1e3 * res.work_of_adhesion_stderr:.1f} mJ/m^2 "
      f"(truth 50), sigma0 = {1e-3 * res.max_adhesive_stress:.0f} +/- "
      f"{1e-3 * res.max_adhesive_stress_stderr:.0f} kPa (truth 100); success: {res.success}")

fig, (ax, ax_r) = plt.subplots(2, 1, figsize=(6, 5), sharex=True, height_ratios=(3, 1),
                               layout="constrained")
ax.plot(1e6 * a, 1e3 * measured, "o", ms=3, label="synthetic data")
ax.plot(1e6 * res.contact_size, 1e3 * res.load_fitted, "-", label="fitted model")
ax.set_ylabel("load W [mN]")
ax.legend()
ax_r.plot(1e6 * a, 1e6 * res.load_residuals, ".")
ax_r.axhline(0, color="k", lw=0.5)
ax_r.set_xlabel("contact semi-major axis a [µm]")
ax_r.set_ylabel("residual [µN]")
plt.show()
