"""The exceptions of stochvib.

Every error of the library is raised as one of these classes, with the message the command-line tool prints
after ``error:`` (the hint included: what to do about it); the fields of the error are attributes
(``reason``, ``hint``, ``name``, ``value``, ``quantity``, ``key``, ``path``, ..., ``None`` when the error
has no such field).

    StochvibError(Exception)
    ├── InvalidInputError(StochvibError, ValueError)     a parameter or argument outside its valid range
    │   │                                                 (``name``, ``value``, ``reason``), an array of the
    │   │                                                 wrong dtype or shape
    │   └── UnitError(InvalidInputError)                 a quantity string whose unit is unknown or of the
    │                                                     wrong dimension (``name`` the parameter, ``value``
    │                                                     the text)
    ├── NotApplicableError(StochvibError, ValueError)    a method that does not apply (e.g. modes of a
    │                                                     system without mass matrix)
    ├── DivergentError(StochvibError, ArithmeticError)   an infinite variance or spectral moment, or no
    │                                                     stationary response at all (an unstable system);
    │                                                     ``reason`` is the diagnosis, ``hint`` what finite
    │                                                     question to ask or what to check
    ├── NumericalError(StochvibError, ArithmeticError)   a numerical procedure that failed (singular matrix)
    │   └── NotConvergedError(NumericalError)            an adaptive quadrature that did not reach its
    │                                                     tolerance (``estimate``, ``abs_error``,
    │                                                     ``evaluations``)
    └── FileError(StochvibError, OSError)                a file that cannot be read or written, or a file
                                                          whose key ``key`` has a bad value

Examples
--------
>>> import stochvib
>>> try:
...     stochvib.System.model("quarter-car", sprung_mass="300 kgg")
... except stochvib.UnitError as e:
...     print(e.name, isinstance(e, ValueError))
sprung_mass True
"""

from __future__ import annotations

from typing import Any

__all__ = [
    "StochvibError",
    "InvalidInputError",
    "UnitError",
    "NotApplicableError",
    "DivergentError",
    "NumericalError",
    "NotConvergedError",
    "FileError",
    "StochvibWarning",
]

_FIELDS = ("reason", "hint", "name", "value", "quantity", "method", "what", "key", "path")


class StochvibError(Exception):
    """Base class of every stochvib error. ``str(e)`` is the command-line tool's message (with its hint)."""

    reason: str | None
    hint: str | None
    name: str | None
    value: str | None
    quantity: str | None
    method: str | None
    what: str | None
    key: str | None
    path: str | None

    def __init__(self, message: str, **details: Any) -> None:
        super().__init__(message)
        self.message = message
        for field in _FIELDS:
            setattr(self, field, details.pop(field, None))
        for k, v in details.items():
            setattr(self, k, v)

    def __str__(self) -> str:
        return self.message


class InvalidInputError(StochvibError, ValueError):
    """A parameter outside its valid range (``name``, ``value``, ``reason``), or an argument of the wrong
    dtype, shape or kind."""


class UnitError(InvalidInputError):
    """A quantity string (``value``, e.g. ``"10.8 km/hh"``) given for the parameter ``name`` whose unit is
    unknown or has the wrong dimension (``reason`` names both dimensions)."""


class NotApplicableError(StochvibError, ValueError):
    """A method that does not apply to this problem (``method``, ``reason``); another one may."""


class DivergentError(StochvibError, ArithmeticError):
    """An infinite variance or spectral moment (``quantity``), or an unstable system (no stationary
    response); ``reason`` is the diagnosis, ``hint`` (when separate) what to ask or check instead."""


class NumericalError(StochvibError, ArithmeticError):
    """A numerical procedure that failed (``what``, ``reason``)."""


class NotConvergedError(NumericalError):
    """An adaptive quadrature that did not converge (``what``, ``estimate``, ``abs_error``,
    ``evaluations``, ``reason``); the message says which option raises the effort."""


class FileError(StochvibError, OSError):
    """A file that cannot be read, parsed or written (``path``, ``reason``), or a bad value at ``key``."""

    def __init__(self, message: str, **details: Any) -> None:
        StochvibError.__init__(self, message, **details)
        # OSError.__init__ with a single argument keeps errno/strerror None; str() is the message.


class StochvibWarning(UserWarning):
    """Something worth knowing that does not stop the computation (e.g. an invalid catalogue file)."""
