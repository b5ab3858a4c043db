# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""an1078-x2cmap on the built simulator: the map holds exactly the whitelist's rows
(firmware/x2cscope/x2c_vars.h: motor.<path> read-only, x2c.tune.<field> tunable, x2c.id.<field>
the identification's result, read-only) in the target's 16-bit window, with the XC16 type of
each width; it loads as pyx2cscope loads it
(PyYAML's FullLoader and a !VariableInfo constructor; pyx2cscope itself is not imported); and
the tool refuses, in one line, an ELF without the table, a table whose rows are not 80 bytes,
and an existing output without --force.

A board's map (--like): a 16-bit ELF with DWARF, built here with avr-gcc (int 16 bits, as on
the dsPIC) from the firmware's own headers, holding `motor` (static, as in firmware/motor.c)
and `x2c` (as in firmware/main.c): every variable's address and width must equal what the
compiler itself computes (the symbols' addresses, offsetof and sizeof through a probe object),
with the simulator's names, units and ranges; the simulator's ELF given as the board's, a
board ELF without --like, and one without the variables, are refused in one line.

usage: test_x2cmap.py <sim executable> [<-DNAME=VALUE of the build's profile>...]
       (CTest: test_x2cmap, label unit)
"""

from __future__ import annotations

import contextlib
import importlib.util
import io
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

if __name__ == "__main__":
    missing = [m for m in ("yaml", "elftools") if importlib.util.find_spec(m) is None]
    if missing:
        print(f"SKIPPED: {', '.join(missing)} not installed (run tools/bootstrap)")
        sys.exit(77)

from scope import varmap
from test_scope import VariableInfo, load_as_pyx2cscope

SIM = ""
DEFS: list[str] = []  # the build's profile defines (MC_BOARD_..., MC_MOTOR_..., MC_MOTOR_HEADER=...)
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# the type names pyx2cscope's get_variable_raw knows (its type_factory keys), as read from it
PYX2CSCOPE_TYPES = {"bool", "char", "double", "float", "int", "long", "long double", "long int", "long long",
                    "long long unsigned int", "long unsigned int", "pointer", "short", "short int",
                    "short unsigned int", "signed char", "signed int", "signed long", "signed long long",
                    "unsigned char", "unsigned int", "unsigned long", "unsigned long long", "enum"}


def whitelist() -> tuple[list[str], list[str], list[str]]:
    """The motor paths, tunable fields and result fields of x2c_vars.h's three X-macro tables."""
    with open(os.path.join(ROOT, "firmware", "x2cscope", "x2c_vars.h"), encoding="utf-8") as f:
        text = f.read()

    def table(name: str) -> list[str]:
        body = text[text.index(f"#define {name}(X)"):]
        lines = []
        for ln in body.splitlines()[1:]:
            lines.append(ln)
            if not ln.rstrip().endswith("\\"):
                break
        rows: list[str] = []
        for tok in re.findall(r"\bX\(\s*([\w.\[\]]+)\s*,|\b(X2C_\w+_VARS)\(X\)", " ".join(lines)):
            # a nested table (X2C_ESTIMATOR_VARS) expands to its first definition: the drive's,
            # which the simulator is built as
            rows += [tok[0]] if tok[0] else table(tok[1])
        return rows

    return table("X2C_MOTOR_VARS"), table("X2C_TUNABLES"), table("X2C_ID_VARS")


def run(*argv: str) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            rc = varmap.main(list(argv))
        except SystemExit as e:
            rc = int(e.code or 0)
    return rc, out.getvalue(), err.getvalue()


class X2cMap(unittest.TestCase):
    def setUp(self) -> None:
        self.tmp = tempfile.TemporaryDirectory()
        self.out = os.path.join(self.tmp.name, "x2cmap.yml")

    def tearDown(self) -> None:
        self.tmp.cleanup()

    def assertOneLine(self, rc: int, err: str, *want: str) -> None:
        self.assertEqual(rc, 1, err)
        self.assertEqual(len(err.splitlines()), 1, err)
        self.assertNotIn("Traceback", err)
        for w in want:
            self.assertIn(w, err)

    def test_the_map_should_hold_the_whitelist_in_the_window(self) -> None:
        rc, _, err = run(SIM, "-o", self.out)
        self.assertEqual(rc, 0, err)
        vm = varmap.load_map(self.out)
        motor, tune, ident = whitelist()
        self.assertEqual(list(vm.vars), [f"motor.{p}" for p in motor] + [f"x2c.tune.{f}" for f in tune]
                         + [f"x2c.id.{f}" for f in ident])
        for v in vm.vars.values():
            if v.name.startswith("motor."):
                self.assertTrue(0x1000 <= v.address < 0x10000 and not v.tunable, v)
            elif v.name.startswith("x2c.id."):
                self.assertTrue(0x0880 <= v.address < 0x0900 and not v.tunable, v)
            else:
                self.assertTrue(0x0800 <= v.address < 0x0900 and v.tunable and v.size == 2, v)
                self.assertLessEqual(v.min, v.max)
            self.assertEqual(v.address % v.size if v.size > 1 else 0, 0, v)
            self.assertEqual(varmap.TYPE_KINDS[v.type], (v.kind, v.size), v)
        omega = vm.get("motor.smc.omega")
        self.assertEqual((omega.type, omega.unit, omega.full_scale > 0), ("int", "rpm", True))
        # the tunables are consecutive int16s from the window's start (x2c_tune_t)
        self.assertEqual([vm.get(f"x2c.tune.{f}").address for f in tune], [0x0800 + 2 * i for i in range(len(tune))])
        print(f"measured: {len(vm.vars)} variables in the map, {len(tune)} tunable")

    def test_the_map_should_load_as_pyx2cscope_loads_it(self) -> None:
        self.assertEqual(run(SIM, "-o", self.out)[0], 0)
        with open(self.out, encoding="utf-8") as f:
            doc = load_as_pyx2cscope(f.read())
        self.assertEqual(doc["registers"], {})
        for name, info in doc["variables"].items():
            self.assertIsInstance(info, VariableInfo)
            self.assertEqual(info.name, name)
            self.assertEqual((info.array_size, info.bit_size, info.bit_offset, info.valid_values), (0, 0, 0, {}))
            # pyx2cscope's lookup: type.lower() with "_" removed, in its type factory
            self.assertIn(info.type.lower().replace("_", ""), PYX2CSCOPE_TYPES)
        self.assertEqual(set(doc["an1078"]), set(doc["variables"]))

    def test_an_elf_without_the_table_should_be_refused(self) -> None:
        rc, _, err = run(os.path.realpath(sys.executable), "-o", self.out)
        self.assertOneLine(rc, err, "no simulator table", "give --like")
        rc, _, err = run(__file__, "-o", self.out)
        self.assertOneLine(rc, err, "not an ELF")
        self.assertFalse(os.path.exists(self.out))

    def test_rows_of_another_size_should_be_refused(self) -> None:
        from elftools.elf.elffile import ELFFile
        from elftools.elf.sections import SymbolTableSection

        bad = os.path.join(self.tmp.name, "sim_bad")
        shutil.copy(SIM, bad)
        with open(bad, "r+b") as f:
            elf = ELFFile(f)
            symtab = elf.get_section_by_name(".symtab")
            assert isinstance(symtab, SymbolTableSection)
            syms = symtab.get_symbol_by_name(varmap.ROWS_SYMBOL)
            assert syms
            sym = syms[0]
            sec = elf.get_section(sym["st_shndx"])
            at = sec["sh_offset"] + sym["st_value"] - sec["sh_addr"]
            f.seek(at)
            (n,) = struct.unpack("<H", f.read(2))
            f.seek(at)
            f.write(struct.pack("<H", n + 1))  # the same bytes, one row more: rows of 2720/35 bytes
        rc, _, err = run(bad, "-o", self.out)
        self.assertOneLine(rc, err, f"{n * 80} bytes for {n + 1} rows", "not 80-byte rows")
        self.assertFalse(os.path.exists(self.out))

    def test_an_existing_output_should_be_kept_without_force(self) -> None:
        with open(self.out, "w", encoding="utf-8") as f:
            f.write("keep")
        rc, _, err = run(SIM, "-o", self.out)
        self.assertOneLine(rc, err, "exists: not replaced", "--force")
        with open(self.out, encoding="utf-8") as f:
            self.assertEqual(f.read(), "keep")
        rc, _, err = run(SIM, "-o", self.out, "--force")
        self.assertEqual(rc, 0, err)
        with open(self.out, encoding="utf-8") as f:
            self.assertIn("variables:", f.read())


BOARD_C = """
#include <stddef.h>
#include "x2c.h"
static mc_t motor __attribute__((used)); /* as firmware/motor.c has it */
x2c_t x2c;                               /* as firmware/main.c has it */
int main(void) { return 0; }
"""


class BoardMap(unittest.TestCase):
    """an1078-x2cmap <16-bit ELF> --like <sim>: the addresses from the ELF's DWARF."""

    def setUp(self) -> None:
        self.cc = shutil.which("avr-gcc")
        if self.cc is None:
            self.skipTest("avr-gcc is not installed (run tools/bootstrap)")
        self.tmp = tempfile.TemporaryDirectory()
        self.out = os.path.join(self.tmp.name, "board.yml")
        self.inc = [f"-I{os.path.join(ROOT, d)}" for d in ("firmware", "firmware/x2cscope", "foc", "smc_estimator",
                                                             "hal", "boards")]

    def tearDown(self) -> None:
        self.tmp.cleanup()

    def build(self, name: str, text: str, *flags: str) -> str:
        src, elf = os.path.join(self.tmp.name, f"{name}.c"), os.path.join(self.tmp.name, f"{name}.elf")
        with open(src, "w", encoding="utf-8") as f:
            f.write(text)
        assert self.cc is not None
        subprocess.run([self.cc, "-std=gnu99", "-mmcu=atmega2560", "-Os", *flags, *self.inc, *DEFS, src, "-o", elf],
                       check=True, capture_output=True, text=True)
        return elf

    def nm(self, path: str, *flags: str) -> dict[str, tuple[int, int]]:
        """symbol -> (value, size)."""
        p = subprocess.run(["avr-nm", "-S", *flags, path], check=True, capture_output=True, text=True)
        out = {}
        for ln in p.stdout.splitlines():
            f = ln.split()
            if len(f) == 4:
                out[f[3]] = (int(f[0], 16), int(f[1], 16))
        return out

    def test_every_variable_should_sit_where_the_compiler_put_it(self) -> None:
        elf = self.build("board", BOARD_C, "-gdwarf-2")
        rc, _, err = run(elf, "--like", SIM, "-o", self.out)
        self.assertEqual(rc, 0, err)
        vm = varmap.load_map(self.out)
        sim = varmap.read_elf(SIM)
        self.assertEqual(list(vm.vars), [v.name for v in sim])
        # the compiler's own answer: offsetof and sizeof of every path, as the sizes of probe arrays
        probe = ["#include <stddef.h>", '#include "x2c.h"']
        for i, v in enumerate(sim):
            top, path = v.name.split(".", 1)
            t = "mc_t" if top == "motor" else "x2c_t"
            probe.append(f"char off_{i}[offsetof({t}, {path}) + 1]; char size_{i}[sizeof((({t} *)0)->{path})];")
        obj = self.build("probe", "\n".join(probe) + "\n", "-c")
        sizes = self.nm(obj)
        syms = self.nm(elf)
        base = {"motor": syms["motor"][0] & 0xFFFF, "x2c": syms["x2c"][0] & 0xFFFF}
        for i, v in enumerate(sim):
            got = vm.get(v.name)
            want_addr = base[v.name.split(".")[0]] + sizes[f"off_{i}"][1] - 1
            self.assertEqual((got.address, got.size), (want_addr, sizes[f"size_{i}"][1]), v.name)
            self.assertEqual((got.unit, got.full_scale, got.tunable, got.min, got.max),
                             (v.unit, v.full_scale, v.tunable, v.min, v.max), v.name)
            self.assertEqual(varmap.TYPE_KINDS[got.type], (got.kind, got.size), v.name)
        self.assertEqual(vm.get("motor.state").size, 2)  # an enum is an int: 16 bits here, 32 on the PC
        print(f"measured: {len(vm.vars)} variables at the compiler's addresses "
              f"(motor at 0x{base['motor']:04X}, x2c at 0x{base['x2c']:04X})")

    def test_the_wrong_elf_or_none_of_the_variables_should_be_refused(self) -> None:
        rc, _, err = run(SIM, "--like", SIM, "-o", self.out)
        self.assertEqual((rc, len(err.splitlines())), (1, 1), err)
        self.assertIn("give it without --like", err)
        elf = self.build("board", BOARD_C, "-gdwarf-2")
        rc, _, err = run(elf, "-o", self.out)
        self.assertEqual((rc, len(err.splitlines())), (1, 1), err)
        self.assertIn("give --like", err)
        other = self.build("other", "int main(void) { return 0; }\n", "-gdwarf-2")
        rc, _, err = run(other, "--like", SIM, "-o", self.out)
        self.assertEqual((rc, len(err.splitlines())), (1, 1), err)
        self.assertIn("no variable 'motor'", err)
        bare = os.path.join(self.tmp.name, "bare.elf")
        subprocess.run(["avr-objcopy", "--strip-debug", elf, bare], check=True)
        rc, _, err = run(bare, "--like", SIM, "-o", self.out)
        self.assertEqual((rc, len(err.splitlines())), (1, 1), err)
        self.assertIn("no DWARF", err)
        self.assertFalse(os.path.exists(self.out))


if __name__ == "__main__":
    if len(sys.argv) < 2 or not os.path.isfile(sys.argv[1]):
        print("usage: test_x2cmap.py <sim executable> [-DNAME=VALUE...]", file=sys.stderr)
        sys.exit(2)
    SIM = sys.argv[1]
    DEFS = sys.argv[2:]
    unittest.main(verbosity=1, argv=[sys.argv[0]])
