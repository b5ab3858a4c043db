# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
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
from .derive import MIN_GAIN_COUNTS, GainBlame, Infeasible, Tuning, Value, fmt_num
from .describe import TUNABLE, Description
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


def apply_tuning(d: Description, t: Tuning) -> None:
    """The description's [tuning] entries replace the values derived for their macros, each
    with its reason and what the tool alone gives (nothing is derived again from them)."""
    for macro, o in d.tuning.items():
        if macro == "MOTOR_NAME":
            t.tuned[macro] = f"HAND-TUNED (the description's [tuning]): {o.reason}"
            continue
        if macro == "MOTOR_FW_ID_TABLE_A":
            t.fw_table = list(o.numbers)
            t.tuned[macro] = f"HAND-TUNED (the description's [tuning]): {o.reason}"
            continue
        old = t.by.get(macro)
        alone = (f"tools/tune alone: {fmt_num(old.number, old.fmt)}" if old is not None
                 else "tools/tune alone: UserParms.h's default")
        reason = f"HAND-TUNED (the description's [tuning]): {o.reason} ({alone})"
        v = Value(macro, o.numbers[0], TUNABLE[macro], reason, text=o.text)
        if old is not None:
            t.values[t.values.index(old)] = v
        else:
            t.values.append(v)
        t.by[macro] = v
        t.tuned[macro] = reason
        if macro in t.gains:
            t.gains[macro] = GainBlame(f"tuning.{macro}", f"the value is in {TUNABLE[macro]}: check it")


def judge(t: Tuning, prof: probe.Profile) -> None:
    """The core's verdict on the generated values, as the description's terms."""
    if prof.refused:
        r = prof.refused[0]
        if r.param in t.tuned:
            raise Infeasible(f"tuning.{r.param}", f"the core rejects it: {r.why} ({r.where})")
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


def build(d: Description, tool_cmd: str, shown: str, tuning: bool = True) -> Generated:
    """The header for d, judged by the core (InputError, Infeasible otherwise); `shown`
    names it in messages. tuning=False leaves the description's [tuning] out: the profile
    the tool derives on its own."""
    t = derive.derive(d)
    if tuning:
        apply_tuning(d, t)
    text = clang_format(emit.render(d, t, tool_cmd))
    prof = probe.profile(text, t.board.id, shown, t.fpwm)
    judge(t, prof)
    return Generated(t, text, prof)
