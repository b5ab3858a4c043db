# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
"""an1078-x2cmap: the simulator's X2Cscope variable map, from its ELF, in the YAML format
pyx2cscope's import_variables reads; and the reader of that file for tools/scope.

    an1078-x2cmap build/host/tools/sim/sim -o x2cmap.yml [--force]

The simulator presents the target's variables in a 16-bit window that its own (64-bit) symbols
cannot describe, so it carries a table of them, `sim_x2c_map` (tools/sim/sim_x2c_map.h): rows of
80 bytes (name[48], unit[8], full_scale double, min i32, max i32, address u16, size u16,
tunable u8, kind u8 'S', 'U' or 'B', 2 pad bytes) and their count `sim_x2c_map_rows` (u16). This
tool reads both from the section that holds them and writes

    variables:                       # pyx2cscope's VariableInfo, one per row
      motor.i_dq.d: !VariableInfo {address: 4174, array_size: 0, bit_offset: 0, bit_size: 0,
                                   byte_size: 2, name: motor.i_dq.d, type: int, valid_values: {}}
    registers: {}
    an1078:                          # ours (pyx2cscope reads only the two keys above)
      motor.i_dq.d: {unit: A, full_scale: 4.4, tunable: false, min: 0, max: 0}

`type` is the XC16 type of the width, which is how pyx2cscope picks a variable's width and sign.

The board's firmware (`make firmware`'s ELF) carries no such table: its addresses are its own, and
the ELF's DWARF describes them, which is what X2Cscope clients read on the board. For our client,

    an1078-x2cmap build/firmware/mclv.elf --like build/host/tools/sim/sim -o board.yml

takes the names, units, full scales and ranges from the simulator built with the same BOARD and
MOTOR (the same whitelist, x2c_vars.h) and each variable's address and width from the board ELF's
DWARF: the variable (`motor`, `x2c`), its members' offsets, an array's element size. A name the
DWARF does not resolve to a scalar of a width the target reads is refused.

Every failure is one line on stderr and exit status 1 (2 for a usage error); an existing output is
replaced only with --force.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import re
import struct
import sys
import tempfile
from dataclasses import dataclass
from typing import Any, NoReturn

MAP_SYMBOL = "sim_x2c_map"
ROWS_SYMBOL = "sim_x2c_map_rows"
ROW_FORMAT = "<48s8sdiiHHBB2x"
ROW_SIZE = 80
assert struct.calcsize(ROW_FORMAT) == ROW_SIZE

# XC16's type names by kind and width (int is 16-bit, long 32-bit there).
XC16_TYPES: dict[tuple[str, int], str] = {
    ("S", 1): "signed char", ("S", 2): "int", ("S", 4): "long int",
    ("U", 1): "unsigned char", ("U", 2): "unsigned int", ("U", 4): "long unsigned int",
    ("B", 1): "bool",
}
# ... and back, for any map (also one pyx2cscope exported from a board's ELF): kind, width.
TYPE_KINDS: dict[str, tuple[str, int]] = {
    "bool": ("B", 1), "char": ("S", 1), "signed char": ("S", 1), "unsigned char": ("U", 1),
    "short": ("S", 2), "short int": ("S", 2), "int": ("S", 2), "signed int": ("S", 2),
    "short unsigned int": ("U", 2), "unsigned int": ("U", 2), "unsigned short": ("U", 2),
    "long": ("S", 4), "long int": ("S", 4), "signed long": ("S", 4),
    "long unsigned int": ("U", 4), "unsigned long": ("U", 4),
    "float": ("F", 4), "double": ("F", 4), "long double": ("F", 4),
}
VARIABLE_INFO_TAG = "!VariableInfo"
EXTRA_KEY = "an1078"


class MapError(Exception):
    """The ELF or the map is not what this tool reads (one line)."""


@dataclass(frozen=True)
class Var:
    """One variable of the map."""

    name: str
    address: int
    size: int
    kind: str  # S, U, B or F
    type: str  # the XC16 type name
    unit: str = ""
    full_scale: float = 0.0  # engineering value of 32768 raw counts; 0: the raw value is the value
    tunable: bool = False
    min: int = 0
    max: int = 0

    def to_eng(self, raw: float) -> float:
        return raw / 32768.0 * self.full_scale if self.full_scale > 0 else float(raw)

    def from_eng(self, value: float) -> float:
        """The raw value of an engineering one (not rounded)."""
        return value * 32768.0 / self.full_scale if self.full_scale > 0 else value

    @property
    def raw_range(self) -> tuple[int, int]:
        if self.kind == "B":
            return 0, 1
        if self.kind == "S":
            return -(1 << (8 * self.size - 1)), (1 << (8 * self.size - 1)) - 1
        return 0, (1 << (8 * self.size)) - 1

    @property
    def access(self) -> str:
        return f"RW {self.min}..{self.max}" if self.tunable else "RO"


# ---- the ELF ------------------------------------------------------------------------------------


def _symbol_bytes(elf: Any, name: str) -> tuple[bytes, int]:
    """The bytes of symbol name (st_size of them) and st_size."""
    from elftools.elf.sections import SymbolTableSection

    found = None
    for sec in elf.iter_sections():
        if isinstance(sec, SymbolTableSection):
            syms = sec.get_symbol_by_name(name)
            if syms:
                found = syms[0]
                break
    if found is None:
        raise MapError(f"no symbol {name!r} (is it the simulator built with the X2Cscope target?)")
    shndx = found["st_shndx"]
    if not isinstance(shndx, int):
        raise MapError(f"symbol {name!r} is not defined in a section ({shndx})")
    sec = elf.get_section(shndx)
    if sec["sh_type"] == "SHT_NOBITS":
        raise MapError(f"symbol {name!r} lies in {sec.name}, which holds no bytes in the file")
    size = int(found["st_size"])
    off = int(found["st_value"]) - (0 if elf["e_type"] == "ET_REL" else int(sec["sh_addr"]))
    data = sec.data()
    if off < 0 or off + size > len(data):
        raise MapError(f"symbol {name!r} ({size} bytes) lies outside its section {sec.name}")
    return bytes(data[off:off + size]), size


def _cstr(b: bytes, what: str) -> str:
    if b"\0" not in b:
        raise MapError(f"{what}: not NUL-terminated")
    try:
        return b.split(b"\0", 1)[0].decode("ascii")
    except UnicodeDecodeError:
        raise MapError(f"{what}: not ASCII") from None


def read_elf(path: str) -> list[Var]:
    """The rows of sim_x2c_map in the ELF at path."""
    from elftools.common.exceptions import ELFError
    from elftools.elf.elffile import ELFFile

    try:
        with open(path, "rb") as f:
            try:
                elf = ELFFile(f)
                if not elf.little_endian:
                    raise MapError(f"{path}: a big-endian ELF; the map's rows are little-endian")
                table, table_size = _symbol_bytes(elf, MAP_SYMBOL)
                rows_b, rows_size = _symbol_bytes(elf, ROWS_SYMBOL)
            except ELFError as e:
                raise MapError(f"{path}: not an ELF file this tool reads ({_one_line(e)})") from None
    except OSError as e:
        raise MapError(f"cannot read {path!r}: {e.strerror or e}") from None
    except MapError as e:
        msg = str(e)
        raise MapError(msg if msg.startswith(path) else f"{path}: {msg}") from None
    if rows_size != 2:
        raise MapError(f"{path}: {ROWS_SYMBOL} is {rows_size} bytes, want 2 (uint16_t)")
    (n,) = struct.unpack("<H", rows_b)
    if n == 0:
        raise MapError(f"{path}: {ROWS_SYMBOL} is 0: no variables")
    if table_size != n * ROW_SIZE:
        raise MapError(f"{path}: {MAP_SYMBOL} is {table_size} bytes for {n} rows: not {ROW_SIZE}-byte rows "
                       f"(tools/sim/sim_x2c_map.h changed without this reader?)")
    out: list[Var] = []
    seen: set[str] = set()
    for i in range(n):
        name_b, unit_b, fs, lo, hi, addr, size, tunable, kind_b = struct.unpack_from(ROW_FORMAT, table, i * ROW_SIZE)
        name = _cstr(name_b, f"{path}: row {i}'s name")
        unit = _cstr(unit_b, f"{path}: row {i} ({name})'s unit")
        kind = chr(kind_b)
        if not name or name in seen:
            raise MapError(f"{path}: row {i}: name {name!r} is empty or repeated")
        if (kind, size) not in XC16_TYPES:
            raise MapError(f"{path}: row {i} ({name}): kind {kind!r} of {size} bytes has no XC16 type here")
        if tunable > 1 or fs < 0 or fs != fs:
            raise MapError(f"{path}: row {i} ({name}): tunable {tunable}, full scale {fs}: not a map row")
        seen.add(name)
        out.append(Var(name, addr, size, kind, XC16_TYPES[(kind, size)], unit, float(fs), bool(tunable), lo, hi))
    return out


# ---- a board's ELF: the addresses from its DWARF ----------------------------------------------------

EM_AVR = 83  # its ELF numbers data addresses from 0x800000 (the 16-bit check's test ELFs)
_PATH_STEP = re.compile(r"\.?([A-Za-z_]\w*)|\[(\d+)\]")


def _die_type(die: Any) -> Any:
    """The type DIE behind typedefs and qualifiers (None for void)."""
    t = die.get_DIE_from_attribute("DW_AT_type") if "DW_AT_type" in die.attributes else None
    while t is not None and t.tag in ("DW_TAG_typedef", "DW_TAG_const_type", "DW_TAG_volatile_type"):
        t = t.get_DIE_from_attribute("DW_AT_type") if "DW_AT_type" in t.attributes else None
    return t


def _member_offset(m: Any, where: str) -> int:
    at = m.attributes.get("DW_AT_data_member_location")
    if at is None:
        return 0  # a union's member
    v = at.value
    if isinstance(v, int):
        return v
    if isinstance(v, list) and len(v) >= 2 and v[0] == 0x23:  # DW_OP_plus_uconst ULEB128, DWARF 2
        off, shift = 0, 0
        for b in v[1:]:
            off |= (int(b) & 0x7F) << shift
            shift += 7
            if not int(b) & 0x80:
                return off
    raise MapError(f"{where}: a member location this tool does not read ({v!r})")


def _dwarf_globals(elf: Any, wanted: set[str]) -> dict[str, tuple[int, Any]]:
    """name -> (address, the variable's DIE) for the variables named, where a definition with a
    static address exists."""
    out: dict[str, tuple[int, Any]] = {}
    dwarf = elf.get_dwarf_info()
    for cu in dwarf.iter_CUs():
        for die in cu.iter_DIEs():
            if die.tag != "DW_TAG_variable" or "DW_AT_location" not in die.attributes:
                continue
            name_at = die.attributes.get("DW_AT_name")
            spec = None
            if name_at is None and "DW_AT_specification" in die.attributes:
                spec = die.get_DIE_from_attribute("DW_AT_specification")
                name_at = spec.attributes.get("DW_AT_name")
            if name_at is None:
                continue
            name = name_at.value.decode("utf-8", "replace")
            loc = die.attributes["DW_AT_location"].value
            if name not in wanted or not isinstance(loc, list) or len(loc) < 2 or loc[0] != 0x03:
                continue  # only DW_OP_addr: a static address
            addr = 0
            for i, b in enumerate(loc[1:]):
                addr |= int(b) << (8 * i)
            out[name] = (addr, die if "DW_AT_type" in die.attributes else spec)
    return out


def _resolve(path: str, base: tuple[int, Any], where: str) -> tuple[int, int, str]:
    """Address, byte size and base-type name of the scalar at path ('motor.i_dq.d', 'motor.duty[1]')."""
    addr, die = base
    steps = _PATH_STEP.findall(path)
    t = _die_type(die)
    for member, index in steps[1:]:
        if t is None:
            raise MapError(f"{where}: {path!r}: a step into void")
        if member:
            if t.tag not in ("DW_TAG_structure_type", "DW_TAG_union_type"):
                raise MapError(f"{where}: {path!r}: .{member} of a {t.tag[7:]}")
            for m in t.iter_children():
                if m.tag == "DW_TAG_member" and m.attributes.get("DW_AT_name") and \
                        m.attributes["DW_AT_name"].value.decode() == member:
                    addr += _member_offset(m, where)
                    t = _die_type(m)
                    break
            else:
                raise MapError(f"{where}: {path!r}: no member {member!r} in the ELF's type")
        else:
            if t.tag != "DW_TAG_array_type":
                raise MapError(f"{where}: {path!r}: [{index}] of a {t.tag[7:]}")
            elem = _die_type(t)
            if elem is None or "DW_AT_byte_size" not in elem.attributes:
                raise MapError(f"{where}: {path!r}: an array of elements of unknown size")
            addr += int(index) * int(elem.attributes["DW_AT_byte_size"].value)
            t = elem
    if t is None or t.tag not in ("DW_TAG_base_type", "DW_TAG_enumeration_type"):
        raise MapError(f"{where}: {path!r} is not a scalar in the ELF ({t.tag[7:] if t is not None else 'void'})")
    size = int(t.attributes["DW_AT_byte_size"].value)
    name = "enum" if t.tag == "DW_TAG_enumeration_type" else t.attributes["DW_AT_name"].value.decode()
    return addr, size, name


def read_board_elf(path: str, like: list[Var]) -> list[Var]:
    """The variables of `like` (a simulator's map: names, units, scales, ranges) at the addresses
    and widths the board ELF's DWARF gives them."""
    from elftools.common.exceptions import DWARFError, ELFError
    from elftools.elf.elffile import ELFFile

    tops = {_PATH_STEP.findall(v.name)[0][0] for v in like}
    try:
        with open(path, "rb") as f:
            try:
                elf = ELFFile(f)
                if not elf.has_dwarf_info():
                    raise MapError(f"{path}: no DWARF (build it with -g, as make firmware does)")
                found = _dwarf_globals(elf, tops)
                avr = elf["e_machine"] in ("EM_AVR", EM_AVR)
                out: list[Var] = []
                for v in like:
                    top = _PATH_STEP.findall(v.name)[0][0]
                    if top not in found:
                        raise MapError(f"{path}: no variable {top!r} with a static address in its DWARF "
                                       f"(is it the firmware built with the X2Cscope target?)")
                    addr, size, tname = _resolve(v.name, found[top], path)
                    if avr:
                        addr &= 0xFFFF
                    kind = "B" if tname in ("_Bool", "bool") else v.kind
                    xt = XC16_TYPES.get((kind, size))
                    if xt is None or addr + size > 0x10000:
                        raise MapError(f"{path}: {v.name!r}: {size} bytes ({tname}) at 0x{addr:X}: not a "
                                       f"variable the target reads")
                    out.append(Var(v.name, addr, size, kind, xt, v.unit, v.full_scale, v.tunable, v.min, v.max))
            except (ELFError, DWARFError) as e:
                raise MapError(f"{path}: not an ELF file this tool reads ({_one_line(e)})") from None
    except OSError as e:
        raise MapError(f"cannot read {path!r}: {e.strerror or e}") from None
    return out


def has_sim_table(path: str) -> bool:
    """Whether the ELF at path carries the simulator's table (a missing or foreign file: True,
    so that read_elf says what is wrong with it)."""
    from elftools.common.exceptions import ELFError
    from elftools.elf.elffile import ELFFile
    from elftools.elf.sections import SymbolTableSection

    try:
        with open(path, "rb") as f:
            elf = ELFFile(f)
            return any(isinstance(s, SymbolTableSection) and s.get_symbol_by_name(MAP_SYMBOL)
                       for s in elf.iter_sections())
    except (OSError, ELFError):
        return True


# ---- the YAML ------------------------------------------------------------------------------------


def to_document(rows: list[Var]) -> dict[str, Any]:
    """The map as plain data; VariableInfo rows are marked for the dumper."""
    return {
        "variables": {v.name: _VariableInfo(v) for v in rows},
        "registers": {},
        EXTRA_KEY: {v.name: {"unit": v.unit, "full_scale": v.full_scale, "tunable": v.tunable, "min": v.min,
                             "max": v.max} for v in rows},
    }


class _VariableInfo:
    def __init__(self, v: Var) -> None:
        self.fields = {"address": v.address, "array_size": 0, "bit_offset": 0, "bit_size": 0,
                       "byte_size": v.size, "name": v.name, "type": v.type, "valid_values": {}}


def dump(rows: list[Var], board: bool = False) -> str:
    import yaml

    class Dumper(yaml.SafeDumper):
        pass

    def represent(dumper: yaml.SafeDumper, data: _VariableInfo) -> yaml.Node:
        return dumper.represent_mapping(VARIABLE_INFO_TAG, data.fields)

    Dumper.add_representer(_VariableInfo, represent)
    what = "a board's firmware (its DWARF)" if board else "the AN1078 simulator's 16-bit window"
    head = (f"# X2Cscope variable map of {what} (an1078-x2cmap).\n"
            "# pyx2cscope: X2CScope.import_variables('this.yml'); tools/scope: --map this.yml\n")
    return head + yaml.dump(to_document(rows), Dumper=Dumper, sort_keys=False, default_flow_style=False)


def _loader() -> type:
    import yaml

    class Loader(yaml.SafeLoader):
        pass

    def construct(loader: yaml.SafeLoader, node: yaml.Node) -> dict[Any, Any]:
        if not isinstance(node, yaml.MappingNode):
            raise MapError(f"a {VARIABLE_INFO_TAG} that is not a mapping (line {node.start_mark.line + 1})")
        return loader.construct_mapping(node, deep=True)

    Loader.add_constructor(VARIABLE_INFO_TAG, construct)
    return Loader


@dataclass
class VarMap:
    vars: dict[str, Var]
    has_units: bool  # the an1078 key was there

    def get(self, name: str) -> Var:
        v = self.vars.get(name)
        if v is None:
            near = [n for n in self.vars if name.lower() in n.lower()]
            hint = f"; did you mean {', '.join(near[:4])}?" if near else ""
            raise MapError(f"unknown variable {name!r}{hint} (`list` shows the {len(self.vars)} variables)")
        return v


def _int(d: dict[Any, Any], key: str, where: str) -> int:
    x = d.get(key)
    if not isinstance(x, int) or isinstance(x, bool):
        raise MapError(f"{where}: {key} is {x!r}, not a whole number")
    return x


def parse_map(text: str, where: str = "map") -> VarMap:
    """A map in pyx2cscope's YAML format (with or without our an1078 key)."""
    import yaml

    try:
        doc = yaml.load(text, Loader=_loader())  # a SafeLoader subclass
    except yaml.YAMLError as e:
        raise MapError(f"{where}: not YAML ({_one_line(e)})") from None
    if not isinstance(doc, dict) or not isinstance(doc.get("variables"), dict):
        raise MapError(f"{where}: no 'variables' mapping: not a variable map (an1078-x2cmap writes one)")
    extra = doc.get(EXTRA_KEY)
    if extra is not None and not isinstance(extra, dict):
        raise MapError(f"{where}: '{EXTRA_KEY}' is not a mapping")
    out: dict[str, Var] = {}
    for name, info in doc["variables"].items():
        w = f"{where}: variable {name!r}"
        if not isinstance(name, str) or not isinstance(info, dict):
            raise MapError(f"{w}: not a {VARIABLE_INFO_TAG} mapping")
        addr, size = _int(info, "address", w), _int(info, "byte_size", w)
        t = info.get("type")
        if not isinstance(t, str):
            raise MapError(f"{w}: type {t!r} is not a type name")
        kt = TYPE_KINDS.get(" ".join(t.lower().replace("_", " ").split()))
        if kt is None:
            raise MapError(f"{w}: type {t!r} is not one this client reads")
        kind, width = kt
        if info.get("array_size", 0) or info.get("bit_size", 0):
            raise MapError(f"{w}: arrays and bit fields are not read by this client")
        if size != width or not 0 <= addr <= 0xFFFF - size + 1:
            raise MapError(f"{w}: {size} bytes at 0x{addr:X} do not fit a {t!r} in a 16-bit space")
        unit, fs, tunable, lo, hi = "", 0.0, False, 0, 0
        ex = extra.get(name) if extra is not None else None
        if ex is not None:
            if not isinstance(ex, dict):
                raise MapError(f"{where}: {EXTRA_KEY} {name!r} is not a mapping")
            unit, fs, tunable = ex.get("unit", ""), ex.get("full_scale", 0.0), ex.get("tunable", False)
            wx = f"{where}: {EXTRA_KEY} {name!r}"
            lo, hi = _int(ex, "min", wx), _int(ex, "max", wx)
            if (not isinstance(unit, str) or not isinstance(fs, int | float) or isinstance(fs, bool)
                    or not fs >= 0 or fs == float("inf") or not isinstance(tunable, bool)):
                raise MapError(f"{where}: {EXTRA_KEY} {name!r}: unit, full_scale or tunable malformed")
        out[name] = Var(name, addr, size, kind, t, unit, float(fs), tunable, lo, hi)
    if not out:
        raise MapError(f"{where}: no variables")
    return VarMap(out, extra is not None)


def load_map(path: str) -> VarMap:
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        raise MapError(f"--map {path!r}: {e.strerror or e}") from None
    except UnicodeDecodeError:
        raise MapError(f"--map {path!r}: not UTF-8 text") from None
    return parse_map(text, f"--map {path!r}")


# ---- writing ------------------------------------------------------------------------------------


def write_new(path: str, text: str, force: bool) -> None:
    """Writes text to path whole (a temporary beside it, renamed); refuses an existing path
    unless force, and anything but a regular file even then."""
    real = os.path.realpath(path)
    if os.path.lexists(path) or os.path.lexists(real):
        if not force:
            raise MapError(f"{path!r} exists: not replaced (--force replaces it)")
        if not os.path.isfile(real):
            raise MapError(f"{path!r} exists and is not a regular file: not replaced")
    folder = os.path.dirname(real) or "."
    try:
        fd, tmp = tempfile.mkstemp(prefix=".x2cmap-", suffix=".tmp", dir=folder)
    except OSError as e:
        raise MapError(f"cannot write {path!r}: {e.strerror or e}") from None
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, real)
    except OSError as e:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise MapError(f"cannot write {path!r}: {e.strerror or e}") from None


def _one_line(e: BaseException) -> str:
    return " ".join(str(e).split()) or type(e).__name__


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        print(f"an1078-x2cmap: {' '.join(message.split())} (--help)", file=sys.stderr)
        sys.exit(2)


def main(argv: list[str] | None = None) -> int:
    ap = _Parser(prog="an1078-x2cmap", description="The simulator's X2Cscope variable map, from its ELF, "
                 "as pyx2cscope's import_variables YAML.")
    ap.add_argument("elf", help="the simulator executable (build/host/tools/sim/sim), or with --like the "
                    "board's ELF (build/firmware/mclv.elf)")
    ap.add_argument("-o", "--output", required=True, help="the map to write (.yml)")
    ap.add_argument("--like", metavar="SIM", help="for a board's ELF: the simulator built with the same BOARD and "
                    "MOTOR, for the names, units and ranges")
    ap.add_argument("--force", action="store_true", help="replace an existing output")
    args = ap.parse_args(sys.argv[1:] if argv is None else argv)
    try:
        if args.like is not None:
            if has_sim_table(args.elf):
                raise MapError(f"{args.elf}: the simulator's own ELF: give it without --like")
            rows = read_board_elf(args.elf, read_elf(args.like))
        else:
            if not has_sim_table(args.elf):
                raise MapError(f"{args.elf}: no simulator table; for a board's ELF give --like <the simulator "
                               f"built with the same BOARD and MOTOR>")
            rows = read_elf(args.elf)
        write_new(args.output, dump(rows, board=args.like is not None), args.force)
    except MapError as e:
        print(f"an1078-x2cmap: {e}", file=sys.stderr)
        return 1
    except ImportError as e:
        print(f"an1078-x2cmap: {e.name or 'a package'} is not installed (run tools/bootstrap)", file=sys.stderr)
        return 1
    except Exception as e:  # never a traceback
        print(f"an1078-x2cmap: internal error, {type(e).__name__}: {_one_line(e)}", file=sys.stderr)
        return 1
    print(f"an1078-x2cmap: {len(rows)} variables -> {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
