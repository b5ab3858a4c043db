# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""The core's states, fault codes and identification errors, in order, from their one list each.

firmware/mc.h spells the states and faults once, as the X-macro tables MC_STATE_LIST and
MC_FAULT_LIST (X(name) and X(name, code)), firmware/mc_id.h the identification's errors
(MC_ID_ERROR_LIST, X(name, code)); the tools that print or plot a state, a fault or an
identification's outcome (tools/scope, tools/sim/plot.py) read them here.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass
from pathlib import Path

MC_H = Path(__file__).resolve().parents[2] / "firmware" / "mc.h"
MC_ID_H = MC_H.with_name("mc_id.h")


class McNamesError(Exception):
    """firmware/mc.h does not hold the tables as this reader expects them."""


@dataclass(frozen=True)
class McNames:
    states: tuple[str, ...]  # index = mc_state_t value
    faults: tuple[str, ...]  # index = fault code; code 0 reads "none"
    id_errors: tuple[str, ...] = ()  # index = MC_ID_ERROR_* code; 0 is NONE

    def state(self, code: int) -> str:
        return self.states[code] if 0 <= code < len(self.states) else f"unknown state {code}"

    def fault(self, code: int) -> str:
        return self.faults[code] if 0 <= code < len(self.faults) else str(code)

    def id_error(self, code: int) -> str:
        return self.id_errors[code] if 0 <= code < len(self.id_errors) else f"unknown error {code}"


def _table(text: str, name: str, entry: str, where: Path = MC_H) -> list[re.Match[str]]:
    """The X(...) entries of `#define name(X)`: its spliced lines, comments dropped."""
    start = text.find(f"#define {name}(X)")
    if start < 0:
        raise McNamesError(f"{where}: no #define {name}(X)")
    lines: list[str] = []
    for ln in text[start:].splitlines():
        lines.append(re.sub(r"/\*.*?\*/", " ", ln))
        if not ln.rstrip().endswith("\\"):
            break
    found = list(re.finditer(entry, " ".join(lines)))
    if not found:
        raise McNamesError(f"{where}: {name} has no entries")
    return found


def _coded(text: str, name: str, where: Path) -> tuple[str, ...]:
    """The names of an X(name, code) table, by code; the codes must be 0..n-1."""
    codes: dict[int, str] = {int(m.group(2)): m.group(1)
                             for m in _table(text, name, r"\bX\((\w+),\s*(\d+)\)", where)}
    if sorted(codes) != list(range(len(codes))):
        raise McNamesError(f"{where}: {name}'s codes are not 0..{len(codes) - 1}")
    return tuple(codes[k] for k in range(len(codes)))


def parse(text: str, id_text: str = "") -> McNames:
    """The names in the text of firmware/mc.h (and of firmware/mc_id.h, when given)."""
    states = tuple(m.group(1) for m in _table(text, "MC_STATE_LIST", r"\bX\((\w+)\)"))
    faults = _coded(text, "MC_FAULT_LIST", MC_H)
    ids = _coded(id_text, "MC_ID_ERROR_LIST", MC_ID_H) if id_text else ()
    return McNames(states, ("none",) + faults[1:], ids)


@functools.cache
def read(path: Path = MC_H) -> McNames:
    """The names in firmware/mc.h and mc_id.h beside it (read once)."""
    return parse(path.read_text(encoding="utf-8"), path.with_name("mc_id.h").read_text(encoding="utf-8"))
