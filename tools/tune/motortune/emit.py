# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""Writes a motor profile header (the format of firmware/motors/motor_hurst.h).

Every text that goes into the header passes through comment_text (comments) or
c_string (the MOTOR_NAME literal), whatever checked it before: a newline, a
comment's end or a quote from a description or a file name must never become
C code (a description with a newline used to put a live #define in the header).
"""

from __future__ import annotations

import textwrap

from .derive import Tuning, Value, fmt_num
from .describe import Description
from .probe import pwm_guard_message


def comment_text(text: str) -> str:
    """text safe inside a /* */ comment: printable ASCII (anything else becomes '?'),
    no comment end or start (which would end it, or trip -Wcomment), no trigraph (??/
    is a backslash, and a backslash before the line's end splices the next line in)."""
    s = "".join(c if " " <= c <= "~" or c == "\n" else "?" for c in text)
    while "*/" in s or "/*" in s or "??" in s:
        s = s.replace("*/", "* /").replace("/*", "/ *").replace("??", "? ?")
    return s


def c_string(text: str) -> str:
    """text as a C string literal: quotes, backslashes and question marks (trigraphs)
    escaped, anything but printable ASCII as an octal escape."""
    out: list[str] = []
    for c in text:
        if c in ('"', "\\", "?"):
            out.append("\\" + c)
        elif " " <= c <= "~":
            out.append(c)
        else:
            out.extend(f"\\{b:03o}" for b in c.encode("utf-8"))
    return '"' + "".join(out) + '"'

# Macros every profile defines, in the order motor_hurst.h has them, by section.
# The profile is a file of the project (or of the user's, from its description): the same
# licence line as every source.
SPDX_LINE = "SPDX-License-Identifier: Apache-2.0"
COPYRIGHT_LINE = "Copyright 2026 The open AN1078 authors"

SECTIONS = [
    ("electrical data", ["MOTOR_POLE_PAIRS", "MOTOR_RS_OHM", "MOTOR_LS_H", "MOTOR_KE_VPK_LL_PER_KRPM"]),
    ("speeds", ["MOTOR_SPEED_NOMINAL_RPM", "MOTOR_SPEED_FW_MAX_RPM", "MOTOR_SPEED_MIN_RPM",
                "MOTOR_SPEED_FULLSCALE_RPM"]),
    ("currents", ["MOTOR_CURRENT_MAX_A", "MOTOR_OVERCURRENT_A"]),
    ("start-up (AN1078 \"Motor start-up\")", ["MOTOR_LOCK_TIME_S", "MOTOR_LOCK_CURRENT_A", "MOTOR_RAMP_TIME_S",
                                              "MOTOR_RAMP_END_RPM", "MOTOR_RAMP_CURRENT_A", "MOTOR_OL_DAMP_S"]),
    ("sliding-mode observer", ["MOTOR_SMC_GAIN_V", "MOTOR_SMC_LINEAR_BAND_A", "MC_SPEED_FILTER_HZ"]),
    ("dead-time compensation", ["MC_DEADTIME_BAND_A"]),  # only when UserParms.h's default does not fit
    ("current PI (d and q)", ["MOTOR_CURRENT_LOOP_BW_RAD_S", "MOTOR_CURRENT_KP_V_PER_A",
                              "MOTOR_CURRENT_KI_V_PER_AS"]),
    ("speed PI", ["MOTOR_SPEED_KP_FULL_RPM", "MOTOR_SPEED_KP_A_PER_RPM", "MOTOR_SPEED_KI_A_PER_RPM_S"]),
    ("data for tools (not used by the core)", ["MOTOR_RATED_CURRENT_A", "MOTOR_INERTIA_KGM2",
                                                "MOTOR_START_LOAD_NM"]),
]


def _comment_block(text: str, indent: str = " * ", width: int = 96) -> list[str]:
    out: list[str] = []
    for para in comment_text(text).split("\n"):
        if not para.strip():
            out.append(indent.rstrip())
            continue
        out.extend(textwrap.wrap(para, width=width - len(indent), initial_indent=indent,
                                 subsequent_indent=indent, break_on_hyphens=False))
    return out


def _define(name: str, value_text: str, reason: str) -> list[str]:
    lines: list[str] = []
    if reason:
        body = textwrap.wrap(comment_text(reason).replace("\n", " "), width=92, break_on_hyphens=False)
        lines += ["/* " + body[0]] + [" * " + b for b in body[1:]]
        lines[-1] += " */"
    return lines + [f"#ifndef {name}", f"#define {name} {value_text}", "#endif"]


def render(d: Description, t: Tuning, tool_cmd: str) -> str:
    """The header text for a description and its Tuning."""
    board_id, board_name = t.board.id, t.board.name
    guard = f"MOTOR_{d.name.upper()}_H"
    vals = dict(t.by)

    # the electrical data (inputs, converted)
    def add(macro: str, number: float, unit: str, reason: str, fmt: str = "{:.4g}") -> None:
        vals[macro] = Value(macro, number, unit, reason, fmt)

    rk = "half the line-to-line reading" if d.raw[("motor", "resistance_kind")] == 0.5 else "as given"
    lk = "half the line-to-line reading" if d.raw[("motor", "inductance_kind")] == 0.5 else "as given"
    add("MOTOR_POLE_PAIRS", d.pole_pairs, "", "", "{:d}")
    add("MOTOR_RS_OHM", d.r_ph, "ohm", f"per phase ({rk})")
    add("MOTOR_LS_H", d.l_ph, "H", f"per phase ({lk})")
    add("MOTOR_KE_VPK_LL_PER_KRPM", d.ke_ll, "V/krpm",
        f"back-EMF, peak line-to-line volts per 1000 rpm (psi = {t.psi * 1e3:.3f} mWb, Kt = {t.kt * 1e3:.2f} mN m/A)")
    add("MOTOR_RATED_CURRENT_A", d.i_rated, "A", "rated phase current, A peak (from the description)")
    if d.j is not None:
        add("MOTOR_INERTIA_KGM2", d.j, "kg m^2", "rotor plus load inertia (from the description)", "{:.4g}")

    tuned_name = d.tuning.get("MOTOR_NAME") if "MOTOR_NAME" in t.tuned else None
    motor_name = tuned_name.text if tuned_name is not None else d.desc
    first_desc = comment_text(motor_name).replace("\n", "?")  # the first line stays one line
    lines = [
        f"/* {SPDX_LINE} */",
        f"/* {COPYRIGHT_LINE} */",
        f"/* motor_{d.name}.h - {first_desc}: generated by tools/tune, do not edit (edit the "
        f"description). */",
        f"#ifndef {guard}",
        f"#define {guard}",
        "",
        "/*",
    ]
    intro = (
        f"Generated by `{tool_cmd}` for the {board_name} board (BOARD={board_id}) at "
        f"{t.fpwm} Hz PWM. Build with: make BOARD={board_id} MOTOR={d.name}. Review with: tools/tune/tune "
        f"--check firmware/motors/motor_{d.name}.h.\n"
        "Every value below is derived from the description; the comment above each says how. Units are in "
        "every name; R and L are per phase, currents and voltages are peak phase amplitudes.\n\n"
        + "\n".join(t.notes)
    )
    if t.tuned:
        intro += ("\n\nHAND-TUNED: the description's [tuning] table sets " + ", ".join(t.tuned) + " by hand, "
                  "each with its reason and what the tool alone gives; the notes above and below are the "
                  "tool's own derivation, which these values do not enter (tools/tune --no-tuning writes "
                  "the profile without them).")
    if t.warnings:
        intro += "\n\nDERATED: " + "; ".join(t.warnings) + "."
    if t.limited:
        intro += "\n\nHELD TO THE CORE'S RANGES: " + "; ".join(t.limited) + "."
    lines += _comment_block(intro)
    lines += [" */", ""]
    if tuned_name is not None:
        lines += _define("MOTOR_NAME", "", t.tuned["MOTOR_NAME"])[:-3]
    lines += [f"#define MOTOR_NAME {c_string(motor_name)}", "#ifndef MOTOR_TUNE_BOARD",
              f"#define MOTOR_TUNE_BOARD {c_string(board_id)} /* the board these values were derived for */",
              "#endif"]
    if d.pwm_hz is not None:
        lines += ["", "/* PWM frequency of the description: the board's (boards/board.h) must match. */",
                  f"#if defined(PWM_FREQUENCY_HZ) && PWM_FREQUENCY_HZ != {t.fpwm}L",
                  f'#error "{pwm_guard_message(t.fpwm)}"',
                  "#endif"]
    for title, macros in SECTIONS:
        present = [m for m in macros if m in vals]
        if not present:
            continue
        lines += ["", f"/* ---- {title} " + "-" * max(4, 88 - len(title)) + " */"]
        for m in present:
            v = vals[m]
            text = v.text if v.text is not None else fmt_num(v.number, v.fmt) if v.fmt != "{:d}" else str(v.number)
            lines += _define(m, text, v.reason)
    # field-weakening table
    lines += ["", "/* ---- field weakening " + "-" * 74 + " */"]
    fw_tuned = t.tuned.get("MOTOR_FW_ID_TABLE_A")
    if fw_tuned is not None:
        fw_text = ("Id (A) at 16 speeds evenly spaced from MOTOR_SPEED_NOMINAL_RPM (entry 0) to "
                   f"MOTOR_SPEED_FW_MAX_RPM (entry 15). {fw_tuned}")
    elif t.fw_speeds[-1] > t.fw_speeds[0]:
        fw_text = (
            f"Id (A) at 16 speeds evenly spaced from MOTOR_SPEED_NOMINAL_RPM (entry 0) to "
            f"MOTOR_SPEED_FW_MAX_RPM (entry 15): at each speed the smallest |Id| that keeps the steady-state "
            f"voltage sqrt((R Id - w L Iq)^2 + (R Iq + w (psi + L Id))^2) within the {t.v_ss:.2f} V budget, "
            f"with Iq = {t.i_load:.3g} A (the load the table is computed for: a quarter of the Iq limit unless "
            f"application.fw_load_current says otherwise). A quadratic in Id, solved exactly. The current limit "
            f"|(Id, Iq)| <= {t.i_peak:.3g} A allows Id down to {t.id_limit:.2f} A. Speeds (rpm): "
            + ", ".join(f"{n:.0f}" for n in t.fw_speeds) + "."
        )
    else:
        fw_text = ("No field weakening: nominal speed = FW max speed, so the core never reads the table "
                   "(all zeros, as AN1078 says to disable it).")
    lines += ["/*"] + _comment_block(fw_text) + [" */"]
    lines += ["#ifndef MOTOR_FW_ID_TABLE_A", "/* X-macro: exactly 16 entries (layout kept: clang-format does not",
              " * settle on a fixed point for this macro). */", "/* clang-format off */",
              "#define MOTOR_FW_ID_TABLE_A(X) \\"]
    fw_override = d.tuning.get("MOTOR_FW_ID_TABLE_A") if fw_tuned is not None else None
    entries = fw_override.text.split(" ") if fw_override is not None else [f"X({a:.3f})" for a in t.fw_table]
    for k in range(0, 16, 4):
        sep = " \\" if k < 12 else ""
        lines.append("    " + " ".join(entries[k:k + 4]) + sep)
    lines += ["/* clang-format on */", "#endif", "", f"#endif /* {guard} */", ""]
    return "\n".join(lines)
