"""Ride comfort and health (ISO 2631-1, ISO 8041, Directive 2002/44/EC): frequency weightings as arrays and
filters, and the evaluation of acceleration records (:func:`stochvib.exposure`).

Examples
--------
>>> import numpy as np
>>> from stochvib import comfort
>>> round(float(abs(comfort.weighting("Wd", f=1.0))), 3)  # ISO 2631-1 Table 3: Wd at 1 Hz is 1.011
1.011
>>> b, a = comfort.weighting_filter("Wk")  # descending powers of s, for scipy.signal.freqs(b, a)
>>> len(a) > len(b)
True
"""

from __future__ import annotations

from typing import Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

from . import _stochvib

__all__ = ["weighting", "weighting_filter", "a8", "vdv_gaussian", "WEIGHTINGS"]

WEIGHTINGS = ("Wk", "Wd", "Wc", "We", "Wj", "Wb", "Wf")
"""The frequency weightings of ISO 2631-1 (Wk, Wd, Wc, We, Wj, Wf) and ISO 2631-4 (Wb)."""


def weighting(name: str, omega: Optional[npt.ArrayLike] = None, *, f: Optional[npt.ArrayLike] = None) -> npt.NDArray[np.complex128]:
    """The complex response W(iω) of a frequency weighting, band limiting included.

    Parameters
    ----------
    name : str
        "Wk", "Wd", "Wc", "We", "Wj", "Wb" or "Wf".
    omega : array_like, optional
        Angular frequencies in rad/s, any shape.
    f : array_like, keyword-only, optional
        Frequencies in Hz instead. Exactly one of ``omega`` and ``f``.

    Returns
    -------
    numpy.ndarray of complex128
        Shaped as the argument; ``abs()`` is the weighting factor of ISO 2631-1 Tables 3 and 4.

    Raises
    ------
    InvalidInputError
        An unknown weighting, both or neither of ``omega`` and ``f``.

    Examples
    --------
    >>> from stochvib import comfort
    >>> round(float(abs(comfort.weighting("Wk", f=8.0))), 3)  # ISO 2631-1:1997 Table 3: Wk at 8 Hz is 1.036
    1.036
    """
    return _stochvib.weighting_response(name, omega, f=f)


def weighting_filter(name: str, *, order: str = "descending") -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """The weighting as a rational filter (b, a) in powers of s.

    Parameters
    ----------
    name : str
        "Wk", "Wd", "Wc", "We", "Wj", "Wb" or "Wf".
    order : {"descending", "ascending"}, keyword-only
        Coefficient order; descending (highest power first) is scipy.signal's.

    Returns
    -------
    (b, a) : tuple of numpy.ndarray
        ``scipy.signal.freqs(b, a, worN=omega)[1]`` equals :func:`weighting` at ``omega``;
        ``stochvib.System.transfer_function(b, a)`` is the weighting as a system.

    Examples
    --------
    >>> from stochvib import comfort
    >>> b, a = comfort.weighting_filter("Wd")
    >>> (len(b) - 1, len(a) - 1)  # degrees of numerator and denominator
    (3, 6)
    """
    return _stochvib.weighting_filter(name, order=order)


def a8(a_w: Union[float, str], duration: Union[float, str]) -> float:
    """The daily exposure A(8) = a_w √(T/8 h) of Directive 2002/44/EC, m/s².

    Parameters
    ----------
    a_w : float or str
        Weighted r.m.s. acceleration, m/s² (or a unit string, "0.5 m/s^2"), already multiplied by the axis
        factor k (1.4 for x, y seated).
    duration : float or str
        The daily exposure T in s, or with a unit ("4 h").

    Returns
    -------
    float
        A(8) in m/s².

    Raises
    ------
    UnitError
        A string of another dimension, naming the argument.

    Examples
    --------
    >>> from stochvib import comfort
    >>> round(comfort.a8(1.0, "2 h"), 12)  # √(2/8)
    0.5
    """
    return _stochvib.daily_exposure_a8(a_w, duration)


def vdv_gaussian(a_w: Union[float, str], duration: Union[float, str]) -> float:
    """The vibration dose value of a stationary Gaussian weighted acceleration, VDV = (3T)^¼ a_w, m/s^1.75
    (the fourth moment of a Gaussian is 3σ⁴; compare the standard's estimate 1.4 a_w T^¼).

    Parameters
    ----------
    a_w : float or str
        The weighted r.m.s. acceleration, m/s² ("0.5 m/s^2").
    duration : float or str
        T in s ("8 h").

    Returns
    -------
    float
        VDV in m/s^1.75.

    Raises
    ------
    UnitError
        A string of another dimension, naming the argument.
    InvalidInputError
        A negative or non-finite value.

    Examples
    --------
    >>> from stochvib import comfort
    >>> round(comfort.vdv_gaussian(0.5, "8 h") / (3 * 28800) ** 0.25, 12)
    0.5
    """
    return _stochvib.vdv_gaussian(a_w, duration)
