"""The warnings of tack: :class:`TackWarning` and one subclass per kind, and how a result's
``summary["warnings"]`` become Python warnings when a run returns.

Every sentence of ``summary["warnings"]`` (why a result may not be trusted) is issued once with
:func:`warnings.warn` by :func:`tack.run` and :func:`tack.pull_off`, in the class of its kind,
prefixed with the function's name; the list stays in the summary. The keyword functions'
sentences name their Python arguments (``dx``, ``law.sigma0``, ``body.thickness``), as their
errors do; a scene's name its fields.
"""

from __future__ import annotations

import warnings
from typing import Iterable, Type

__all__ = [
    "ConvergenceWarning",
    "EdgeContactWarning",
    "FullContactWarning",
    "LoadingHistoryWarning",
    "ReferenceWarning",
    "RichardsonWarning",
    "TackWarning",
    "UnderResolvedWarning",
]


class TackWarning(UserWarning):
    """Base of tack's warnings: a result that may not mean what it seems. Silence them all with
    ``warnings.simplefilter("ignore", tack.TackWarning)``."""


class UnderResolvedWarning(TackWarning):
    """The mesh or the path does not resolve what the result depends on: a cohesive zone, a
    pull-off radius, a film or a pattern spanning too few elements, a pull-off carried by a
    handful of elements, or a retraction that stepped over the tensile part."""


class ReferenceWarning(TackWarning):
    """A closed-form reference (F_JKR, F_Maugis, ...) does not describe the body: e.g. a film on
    a rigid base, whose references stay the half-space's."""


class LoadingHistoryWarning(TackWarning):
    """A randomly rough body loaded in several steps under the zero-range law: its pull-off
    depends on the loading history (README, "Loading history")."""


class FullContactWarning(TackWarning):
    """Periodic full contact: every gap is closed and the approach no longer sets the load
    (:func:`tack.contact` returns the state in which contact has just become full; runs leave
    such steps out of the pull-off force)."""


class EdgeContactWarning(TackWarning, RuntimeWarning):
    """Contact reached the edge of a free array: the domain cuts it off."""


class ConvergenceWarning(TackWarning, RuntimeWarning):
    """Steps did not converge within the solver's caps, or the path stopped early."""


class RichardsonWarning(TackWarning):
    """A Richardson extrapolation that does not hold: the coarse (2 dx) grid samples another
    body (a height array with content above its Nyquist wave), or solves another law (the
    smoothed Dugdale law, whose ramp is bound to the grid)."""


#: (start of the sentence, class), first match wins.
_KINDS = (
    ("richardson:", RichardsonWarning),
    ("under-resolved", UnderResolvedWarning),
    ("pull-off not resolved", UnderResolvedWarning),
    ("the pull-off is carried by", UnderResolvedWarning),
    ("dissipated_energy:", UnderResolvedWarning),
    ("the closed-form references", ReferenceWarning),
    # "no F_JKR reference", "no F_MDR reference", "no F_JG reference": periodic strips and arrays.
    ("no F_", ReferenceWarning),
    # A one-step load that puts elements of a free grid's outermost ring below the approach.
    ("the one-step load to", EdgeContactWarning),
    ("loading history", LoadingHistoryWarning),
    ("full contact", FullContactWarning),
    ("contact reached the edge", EdgeContactWarning),
    ("incomplete", ConvergenceWarning),
)


def kind(sentence: str) -> Type[TackWarning]:
    """The class of one sentence of ``summary["warnings"]``."""
    for start, cls in _KINDS:
        if sentence.startswith(start):
            return cls
    if "did not converge" in sentence:
        return ConvergenceWarning
    return TackWarning


def issue(sentences: Iterable[str], function: str, stacklevel: int = 3) -> None:
    """Issues every sentence as a warning of its kind, prefixed ``tack.<function>: ``."""
    for sentence in sentences:
        warnings.warn(f"tack.{function}: {sentence}", kind(sentence), stacklevel=stacklevel)
