"""Traction-separation laws of the adhesive BEM solver (:mod:`dhfield.bem.solver`).

A law gives the tensile adhesive stress sigma(h) >= 0 that acts between the
surfaces at gap h >= 0.  In the solver's sign convention (pressure positive in
compression, :mod:`dhfield.bem.operator`) it enters as the pressure ``-sigma(h)``.
The work of adhesion is the integral of the law over the gap,

.. math:: \\Delta\\gamma = \\int_0^\\infty \\sigma(h)\\,dh .

Two laws are provided, both parametrised by their maximum stress sigma0 and a
range chosen so that the work of adhesion is ``sigma0 * range``:

* :class:`DugdaleLaw` (Maugis 1992): sigma = sigma0 for h < h0, zero beyond;
  h0 = Delta gamma / sigma0.  The law of the Maugis-Dugdale (MD) sphere and of
  the paper's double-Hertz (DH) models, which also use a uniform sigma0.
* :class:`ExponentialLaw`: sigma = sigma0 exp(-h/rho); rho = Delta gamma/sigma0.

Units: any consistent system (SI, or the paper's nondimensional units of
Eqs. 32-35, in which Delta gamma = 1 and sigma0 = mu, so h0 = rho = 1/mu).

References
----------
.. [1] D. Maugis, J. Colloid Interface Sci. 150 (1992) 243-269,
   doi:10.1016/0021-9797(92)90288-C
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.validation import check_positive
from .backend import namespace_of

__all__ = ["DugdaleLaw", "ExponentialLaw", "TractionLaw", "cell_fraction_below"]


def _positive_scalar(name, value, what):
    arr = check_positive(name, value, what)
    if arr.ndim != 0:
        raise ValueError(f"{name} must be a scalar ({what}); got array of shape {arr.shape}")
    return float(arr)


def cell_fraction_below(excess, spread_x, spread_y):
    """Fraction of a rectangular cell where a linear field lies below a threshold.

    Parameters
    ----------
    excess : array_like
        ``threshold - f_c``: threshold minus the field at the cell centre [field unit].
    spread_x, spread_y : array_like
        Variation of the field across the cell, ``|df/dx| dx`` and ``|df/dy| dy``
        (>= 0) [field unit].

    Returns
    -------
    ndarray
        Area fraction in [0, 1] of the cell where ``f < threshold``.

    Notes
    -----
    For ``f = f_c + g_x x + g_y y`` over the cell, the fraction is the
    distribution function of the sum of two independent uniform variables of
    widths A = spread_x and B = spread_y evaluated at ``s = excess``.  With
    ``A >= B`` and ``H = (A + B)/2``:

    .. math::

        F(s) = \\begin{cases}
          0, & s \\le -H \\\\
          (s + H)^2/(2AB), & -H < s < -(A-B)/2 \\\\
          1/2 + s/A, & |s| \\le (A-B)/2 \\\\
          1 - (H - s)^2/(2AB), & (A-B)/2 < s < H \\\\
          1, & s \\ge H
        \\end{cases}

    It is exact for a linear field and reduces to a step at ``s = 0`` when both
    spreads vanish.
    """
    xp = namespace_of(excess)            # numpy, or CuPy on the GPU backend (dhfield.bem.backend)
    s = xp.asarray(excess, dtype=float)
    a0 = np.abs(xp.asarray(spread_x, dtype=float))
    b0 = np.abs(xp.asarray(spread_y, dtype=float))
    a = np.maximum(a0, b0)
    b = np.minimum(a0, b0)
    h = 0.5 * (a + b)
    tiny = np.finfo(float).tiny
    ab2 = np.maximum(2.0 * a * b, tiny)
    inner = 0.5 * (a - b)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        lin = 0.5 + s / np.maximum(a, tiny)
        low = (s + h) ** 2 / ab2
        high = 1.0 - (h - s) ** 2 / ab2
    out = np.where(s <= -inner, np.where(b > 0, low, 0.0), lin)
    out = np.where(s >= inner, np.where(b > 0, high, 1.0), out)
    out = np.where(np.abs(s) <= inner, lin, out)
    out = np.where(s <= -h, 0.0, out)
    out = np.where(s >= h, 1.0, out)
    # both spreads zero: a step at s = 0 (cell centre exactly on the threshold counts half)
    flat = a <= 0.0
    out = np.where(flat, np.where(s > 0, 1.0, np.where(s < 0, 0.0, 0.5)), out)
    return np.clip(out, 0.0, 1.0)


@dataclass(frozen=True)
class _TwoParameterLaw:
    """What both laws share: a peak stress sigma0 [Pa] and a length scale [m] whose
    product is the work of adhesion, checked once; the public evaluations and the
    mapping.  Subclasses name the two in ``_labels`` and give ``_stress`` and ``_energy``."""

    max_stress: float
    range: float

    _labels = ("sigma0, Pa", "length, m")

    def __post_init__(self):
        stress_label, range_label = self._labels
        object.__setattr__(self, "max_stress", _positive_scalar("max_stress", self.max_stress, stress_label))
        object.__setattr__(self, "range", _positive_scalar("range", self.range, range_label))

    @classmethod
    def from_work_of_adhesion(cls, max_stress, work_of_adhesion):
        """The law with sigma0 = ``max_stress`` [Pa] and range = Delta gamma/sigma0 [m]."""
        s = _positive_scalar("max_stress", max_stress, cls._labels[0])
        w = _positive_scalar("work_of_adhesion", work_of_adhesion, "Delta gamma, J/m^2")
        return cls(s, w / s)

    @property
    def work_of_adhesion(self) -> float:
        """Delta gamma = sigma0 x range [J/m^2]."""
        return self.max_stress * self.range

    @property
    def zone_gap(self) -> float:
        """Gap bounding the reported cohesive zone: the range (h0, or rho) [m]."""
        return self.range

    def stress(self, gap):
        """Evaluate the tensile adhesive stress sigma(h) >= 0 [Pa].

        Parameters
        ----------
        gap : array_like
            Gap h >= 0 [m].

        Returns
        -------
        ndarray
            The stress [Pa] (the law's formula: its class Notes).
        """
        return self._stress(namespace_of(gap).asarray(gap, dtype=float))

    def energy(self, gap):
        """Evaluate the adhesive energy per unit area still to be paid to separate to infinity.

        ``int_h^inf sigma dh`` [J/m^2]: sigma0 max(h0 - h, 0) for the Dugdale law,
        sigma0 rho exp(-h/rho) for the exponential law.

        Parameters
        ----------
        gap : array_like
            Gap h >= 0 [m].

        Returns
        -------
        ndarray
            The energy per unit area [J/m^2].
        """
        return self._energy(namespace_of(gap).asarray(gap, dtype=float))

    def as_dict(self) -> dict:
        """Return the law as a mapping.

        Returns
        -------
        dict
            ``law`` (the name), ``max_stress`` [Pa] and ``range`` [m].
        """
        return {"law": self.name, "max_stress": self.max_stress, "range": self.range}


@dataclass(frozen=True)
class DugdaleLaw(_TwoParameterLaw):
    """Dugdale (Maugis) law: uniform tensile stress sigma0 up to the gap h0.

    Parameters
    ----------
    max_stress : float
        Dugdale stress sigma0 > 0 [stress, e.g. Pa].
    range : float
        Cut-off gap h0 > 0 beyond which the stress vanishes [length, e.g. m].

    Notes
    -----
    .. math::

        \\sigma(h) = \\sigma_0\\,[h < h_0], \\qquad \\Delta\\gamma = \\sigma_0 h_0

    (Maugis 1992).  In the paper's units (Delta gamma = 1) sigma0 = mu and
    h0 = 1/mu.  The cohesive zone is ``0 < h < h0``; the solver resolves its
    edge below the cell size with :func:`cell_fraction_below`.
    """

    name = "dugdale"
    smooth = False
    _labels = ("Dugdale stress sigma0, Pa", "cut-off gap h0, m")

    def _stress(self, g):
        return np.where(g < self.range, self.max_stress, 0.0)  # sigma0 [h < h0]

    def _energy(self, g):
        return self.max_stress * np.maximum(self.range - g, 0.0)  # sigma0 max(h0 - h, 0)


@dataclass(frozen=True)
class ExponentialLaw(_TwoParameterLaw):
    """Exponential law: tensile stress sigma0 exp(-h/rho).

    Parameters
    ----------
    max_stress : float
        Peak stress sigma0 > 0, at contact (h = 0) [stress, e.g. Pa].
    range : float
        Decay length rho > 0 [length, e.g. m].

    Notes
    -----
    .. math::

        \\sigma(h) = \\sigma_0 e^{-h/\\rho}, \\qquad \\Delta\\gamma = \\sigma_0\\rho

    Hard contact (h >= 0) is kept.  Its cohesive zone, for the semi-axes
    c and d, is defined as the region h < rho (= h0 of the Dugdale law with
    the same sigma0 and Delta gamma); the law itself has unbounded support.
    """

    name = "exponential"
    smooth = True
    _labels = ("peak stress sigma0, Pa", "decay length rho, m")

    def _stress(self, g):
        return self.max_stress * np.exp(-np.maximum(g, 0.0) / self.range)  # sigma0 exp(-h/rho)

    def _energy(self, g):
        return self.work_of_adhesion * np.exp(-np.maximum(g, 0.0) / self.range)  # sigma0 rho exp(-h/rho)

    def stress_slope(self, gap):
        """Evaluate the slope d sigma/dh <= 0 [Pa/m].

        Parameters
        ----------
        gap : array_like
            Gap h >= 0 [m].

        Returns
        -------
        ndarray
            The slope [Pa/m].
        """
        return -self.stress(gap) / self.range



#: The traction laws the solver accepts.
TractionLaw = DugdaleLaw | ExponentialLaw

LAWS = {"dugdale": DugdaleLaw, "exponential": ExponentialLaw}


def _law_names():
    return tuple(LAWS)


def law_from_name(name: str, max_stress, work_of_adhesion=1.0):
    """Build a law by name ('dugdale' or 'exponential') from sigma0 and Delta gamma.

    Parameters
    ----------
    name : {"dugdale", "exponential"}
        The law.
    max_stress : float
        Peak stress sigma0 > 0 [Pa].
    work_of_adhesion : float, default 1.0
        Delta gamma > 0 [J/m^2].

    Returns
    -------
    DugdaleLaw or ExponentialLaw
        The law.
    """
    if name not in LAWS:
        raise ValueError(f"law must be one of {_law_names()}; got {name!r}")
    return LAWS[name].from_work_of_adhesion(max_stress, work_of_adhesion)


__all__ += ["LAWS", "law_from_name"]


def check_law(law):
    """Check that ``law`` is a Dugdale or exponential law or None (no adhesion).

    Parameters
    ----------
    law : DugdaleLaw, ExponentialLaw or None
        The law to check.

    Returns
    -------
    DugdaleLaw, ExponentialLaw or None
        ``law``, unchanged.

    Raises
    ------
    ValueError
        For anything else.
    """
    if law is None or isinstance(law, (DugdaleLaw, ExponentialLaw)):
        return law
    raise ValueError(f"law must be a DugdaleLaw, an ExponentialLaw or None (no adhesion); got {law!r}")


__all__ += ["check_law"]
