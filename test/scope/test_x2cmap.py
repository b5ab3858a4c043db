"""an1078-x2cmap on the built simulator: the map holds exactly the whitelist's rows
(firmware/x2cscope/x2c_vars.h: motor.<path> read-only, x2c.tune.<field> tunable) in the
target's 16-bit window, with the XC16 type of each width; it loads as pyx2cscope loads it
(PyYAML's FullLoader and a !VariableInfo constructor; pyx2cscope itself is not imported); and
the tool refuses, in one line, an ELF without the table, a table whose rows are not 80 bytes,
and an existing output without --force.

usage: test_x2cmap.py <sim executable>   (CTest: test_x2cmap, label unit)
"""

from __future__ import annotations

import contextlib
import importlib.util
import io
import os
import re
import shutil
import struct
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
ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# the type names pyx2cscope's get_variable_raw knows (its type_factory keys), as read from it
PYX2CSCOPE_TYPES = {"bool", "char", "double", "float", "int", "long", "long double", "long int", "long long",
                    "long long unsigned int", "long unsigned int", "pointer", "short", "short int",
                    "short unsigned int", "signed char", "signed int", "signed long", "signed long long",
                    "unsigned char", "unsigned int", "unsigned long", "unsigned long long", "enum"}


def whitelist() -> tuple[list[str], list[str]]:
    """The motor paths and tunable fields of x2c_vars.h's two X-macro tables."""
    with open(os.path.join(ROOT, "firmware", "x2cscope", "x2c_vars.h"), encoding="utf-8") as f:
        text = f.read()

    def table(name: str) -> list[str]:
        body = text[text.index(f"#define {name}(X)"):]
        lines = []
        for ln in body.splitlines()[1:]:
            lines.append(ln)
            if not ln.rstrip().endswith("\\"):
                break
        return re.findall(r"\bX\(\s*([\w.\[\]]+)\s*,", " ".join(lines))

    return table("X2C_MOTOR_VARS"), table("X2C_TUNABLES")


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
        motor, tune = whitelist()
        self.assertEqual(list(vm.vars), [f"motor.{p}" for p in motor] + [f"x2c.tune.{f}" for f in tune])
        for v in vm.vars.values():
            if v.name.startswith("motor."):
                self.assertTrue(0x1000 <= v.address < 0x10000 and not v.tunable, v)
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
        self.assertOneLine(rc, err, "no symbol 'sim_x2c_map'")
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


if __name__ == "__main__":
    if len(sys.argv) != 2 or not os.path.isfile(sys.argv[1]):
        print("usage: test_x2cmap.py <sim executable>", file=sys.stderr)
        sys.exit(2)
    SIM = sys.argv[1]
    unittest.main(verbosity=1, argv=[sys.argv[0]])
