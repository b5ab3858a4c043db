"""A description to a checked header text: derive, write, judge with the core's own checks.

`build` runs derive.derive, renders the header (emit.render, then the repo's
clang-format style) and compiles it with the probe: a value the core refuses
is reported against the description's field that gave it (Tuning.gains) or
by the core's parameter; a PI gain with fewer than MIN_GAIN_COUNTS counts in
the core's integers is a unit slip, reported against its field. Nothing is
written here (cli.py writes the text).
"""

from __future__ import annotations

import shutil
import subprocess
from dataclasses import dataclass

from . import derive, emit, probe
from .derive import MIN_GAIN_COUNTS, Infeasible, Tuning
from .describe import Description
from .units import InputError

# Each PI gain and the integer the core stores for it (probe_facts.h)
GAIN_COUNTS = {"MOTOR_CURRENT_KP_V_PER_A": "MC_CUR_KP", "MOTOR_CURRENT_KI_V_PER_AS": "MC_CUR_KI",
               "MOTOR_SPEED_KP_A_PER_RPM": "MC_SPD_KP", "MOTOR_SPEED_KI_A_PER_RPM_S": "MC_SPD_KI"}


@dataclass
class Generated:
    tuning: Tuning
    text: str
    profile: probe.Profile


def clang_format(text: str) -> str:
    """The repo's clang-format style (make lint checks firmware/motors/*.h), when installed."""
    exe = shutil.which("clang-format")
    if exe is None:
        return text
    for _ in range(4):  # clang-format is not always idempotent on macro bodies: run to a fixed point
        p = subprocess.run([exe, f"--assume-filename={probe.FIRMWARE}/motors/motor_x.h"], input=text,
                           capture_output=True, text=True)
        if p.returncode != 0 or not p.stdout or p.stdout == text:
            break
        text = p.stdout
    return text


def judge(t: Tuning, prof: probe.Profile) -> None:
    """The core's verdict on the generated values, as the description's terms."""
    if prof.refused:
        r = prof.refused[0]
        blame = t.gains.get(r.param)
        if blame is not None:
            raise Infeasible(blame.field, f"gives {r.param} = {t[r.param]:g}, outside the core's range: "
                                          f"{r.why} ({r.where})")
        raise Infeasible(r.param, f"the core would reject the generated value: {r.why} ({r.where})")
    for macro, blame in t.gains.items():
        n = int(prof.out.fact(GAIN_COUNTS[macro]))
        if n < MIN_GAIN_COUNTS:
            raise InputError(blame.field, f"gives {macro} = {t[macro]:g}, {n} counts in the core's Q15 form "
                                          f"(at least {MIN_GAIN_COUNTS}): {blame.hint}")


def build(d: Description, tool_cmd: str, shown: str) -> Generated:
    """The header for d, judged by the core (InputError, Infeasible otherwise); `shown`
    names it in messages."""
    t = derive.derive(d)
    text = clang_format(emit.render(d, t, tool_cmd))
    prof = probe.profile(text, t.board.id, shown, t.fpwm)
    judge(t, prof)
    return Generated(t, text, prof)
