"""The exceptions of stochvib.

Every error of the library is raised as one of these classes, with the message the command-line tool prints
after ``error:``; the fields of the error are attributes (``reason``, ``quantity``, ``key``, ``path``, ...,
``None`` when the error has no such field).

    StochvibError(Exception)
    ├── InvalidInputError(StochvibError, ValueError)     a parameter or argument outside its valid range,
    │                                                     an array of the wrong dtype or shape, a bad unit
    ├── NotApplicableError(StochvibError, ValueError)    a method that does not apply (e.g. modes of a
    │                                                     system without mass matrix)
    ├── DivergentError(StochvibError, ArithmeticError)   an infinite variance or spectral moment; ``reason``
    │                                                     is the diagnosis (the asymptotic slopes) and says
    │                                                     what finite question to ask instead (a band)
    ├── NumericalError(StochvibError, ArithmeticError)   quadrature that did not converge, a singular matrix
    └── FileError(StochvibError, OSError)                a file that cannot be read or written, or a file
                                                          whose key ``key`` has a bad value
"""

from __future__ import annotations

from typing import Any

__all__ = [
    "StochvibError",
    "InvalidInputError",
    "NotApplicableError",
    "DivergentError",
    "NumericalError",
    "FileError",
    "StochvibWarning",
]


class StochvibError(Exception):
    """Base class of every stochvib error. ``str(e)`` is the command-line tool's message."""

    reason: str | None
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
        for field in ("reason", "name", "value", "quantity", "method", "what", "key", "path"):
            setattr(self, field, details.pop(field, None))
        for k, v in details.items():
            setattr(self, k, v)

    def __str__(self) -> str:
        return self.message


class InvalidInputError(StochvibError, ValueError):
    """A parameter outside its valid range (``name``, ``value``, ``reason``), a bad unit, or an argument of the
    wrong dtype, shape or kind."""


class NotApplicableError(StochvibError, ValueError):
    """A method that does not apply to this problem (``method``, ``reason``); another one may."""


class DivergentError(StochvibError, ArithmeticError):
    """An infinite variance or spectral moment (``quantity``); ``reason`` is the diagnosis and the finite
    question that can be asked instead."""


class NumericalError(StochvibError, ArithmeticError):
    """A numerical procedure that failed (``what``, ``reason``); for quadrature also ``estimate``,
    ``abs_error`` and ``evaluations``."""


class FileError(StochvibError, OSError):
    """A file that cannot be read, parsed or written (``path``, ``reason``), or a bad value at ``key``."""

    def __init__(self, message: str, **details: Any) -> None:
        StochvibError.__init__(self, message, **details)
        # OSError.__init__ with a single argument keeps errno/strerror None; str() is the message.


class StochvibWarning(UserWarning):
    """Something worth knowing that does not stop the computation (e.g. an invalid catalogue file)."""
