"""The result of a task run through a request (the library's core/request_fields.h contract).

Every such task (``roadbrdf.luminaire``, ``roadbrdf.lighting``, ``roadbrdf.marking``, ...) returns a
:class:`Result`: its value as the command line's ``--json`` prints it (the same JSON writer), its notes
and warnings as structured items (a ``kind`` for programs, a ``message`` for people), and the summary
text the command line prints. Warnings are also issued as :class:`RoadbrdfWarning` at the caller's line.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from typing import Any, Dict, List


class RoadbrdfWarning(UserWarning):
    """A result that may be wrong or misleading (the command line's ``roadbrdf: warning:`` lines)."""


@dataclass(frozen=True)
class Diagnostic:
    """A note or a warning: ``kind`` is a short stable identifier, ``message`` one sentence."""

    kind: str
    message: str


@dataclass
class Result:
    """A task's value (a dict, as ``--json`` prints it), notes, warnings and summary text."""

    value: Dict[str, Any]
    notes: List[Diagnostic] = field(default_factory=list)
    warnings: List[Diagnostic] = field(default_factory=list)
    summary: str = ""

    def __post_init__(self) -> None:
        self.notes = [n if isinstance(n, Diagnostic) else Diagnostic(**n) for n in self.notes]
        self.warnings = [w if isinstance(w, Diagnostic) else Diagnostic(**w) for w in self.warnings]

    def __getitem__(self, key: str) -> Any:
        return self.value[key]

    def __contains__(self, key: object) -> bool:
        return key in self.value

    def to_json(self) -> str:
        """The document the command line's ``--json`` prints."""
        return json.dumps(self.value, indent=2)

    def __str__(self) -> str:
        return self.summary
