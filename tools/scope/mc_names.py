"""The core's states and fault codes, in order, from their one list in firmware/mc.h.

firmware/mc.h spells them once, as the X-macro tables MC_STATE_LIST and
MC_FAULT_LIST (X(name) and X(name, code)); the tools that print or plot a
state or a fault (tools/scope, tools/sim/plot.py) read them here.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass
from pathlib import Path

MC_H = Path(__file__).resolve().parents[2] / "firmware" / "mc.h"


class McNamesError(Exception):
    """firmware/mc.h does not hold the tables as this reader expects them."""


@dataclass(frozen=True)
class McNames:
    states: tuple[str, ...]  # index = mc_state_t value
    faults: tuple[str, ...]  # index = fault code; code 0 reads "none"

    def state(self, code: int) -> str:
        return self.states[code] if 0 <= code < len(self.states) else f"unknown state {code}"

    def fault(self, code: int) -> str:
        return self.faults[code] if 0 <= code < len(self.faults) else str(code)


def _table(text: str, name: str, entry: str) -> list[re.Match[str]]:
    """The X(...) entries of `#define name(X)`: its spliced lines, comments dropped."""
    start = text.find(f"#define {name}(X)")
    if start < 0:
        raise McNamesError(f"{MC_H}: no #define {name}(X)")
    lines: list[str] = []
    for ln in text[start:].splitlines():
        lines.append(re.sub(r"/\*.*?\*/", " ", ln))
        if not ln.rstrip().endswith("\\"):
            break
    found = list(re.finditer(entry, " ".join(lines)))
    if not found:
        raise McNamesError(f"{MC_H}: {name} has no entries")
    return found


def parse(text: str) -> McNames:
    """The names in the text of firmware/mc.h."""
    states = tuple(m.group(1) for m in _table(text, "MC_STATE_LIST", r"\bX\((\w+)\)"))
    faults: dict[int, str] = {int(m.group(2)): m.group(1)
                              for m in _table(text, "MC_FAULT_LIST", r"\bX\((\w+),\s*(\d+)\)")}
    if sorted(faults) != list(range(len(faults))):
        raise McNamesError(f"{MC_H}: MC_FAULT_LIST's codes are not 0..{len(faults) - 1}")
    return McNames(states, ("none",) + tuple(faults[k] for k in range(1, len(faults))))


@functools.cache
def read(path: Path = MC_H) -> McNames:
    """The names in firmware/mc.h (read once)."""
    return parse(path.read_text(encoding="utf-8"))
