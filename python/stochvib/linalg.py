"""Closed-form spectral integrals, vectorised for parameter sweeps.

``h2_integral(numerator, denominator)``: ∫_{−∞}^{∞} |N(iω)/D(iω)|² dω for polynomials in s with coefficients in
descending powers of s, as scipy.signal (``order="ascending"`` for lowest first); 2-D arguments give one
integral per row (see its docstring).
"""

from ._stochvib import h2_integral

__all__ = ["h2_integral"]
