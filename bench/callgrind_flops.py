#!/usr/bin/python3
"""Instructions and floating-point operations per bond from a callgrind profile.

    callgrind_flops.py BINARY PROFILE COUNT [--label NAME] [--json]

PROFILE is one region dumped by kernel_profile (--callgrind), recorded with
`valgrind --tool=callgrind --collect-atstart=no --dump-instr=yes`; COUNT is what the
region did (bond evaluations, model calls): every figure is divided by it.

How: callgrind gives the execution count of every instruction address and the source
file and line it came from (inlined code keeps its own header's line). objdump gives
the mnemonic of every address of the statically linked BINARY. Each executed
instruction is then
  * a floating-point operation count: add/sub/mul/div/sqrt = 1 per lane, FMA = 2 per
    lane (ymm = 4 doubles, xmm packed = 2, scalar = 1); compares, min/max, logic,
    moves and conversions are 0 (the convention of hardware FLOP counters);
  * given a part: the function of the header it came from (bond_geometry.hpp's
    gather_point, sum_selected/masked_sums, bond_kinematics, force_scale; the model in
    hyperelastic.hpp/plane_stress.hpp/gent.hpp/tensor.hpp and libm's cbrt; the loop in ba_force.hpp;
    assemble_force_density).
Deterministic: the same binary and inputs give the same counts on any x86-64 machine.
"""
import argparse
import json
import re
import subprocess
import sys
from collections import defaultdict

FLOP_RE = re.compile(r"^v?(add|sub|mul|div|sqrt)(s|p)d$")
FMA_RE = re.compile(r"^vf(n?)m(add|sub)(132|213|231)(s|p)d$")
HADD_RE = re.compile(r"^v?h(add|sub)pd$")


def flops_of(mnemonic, operands):
    """Double-precision flops of one instruction (0 if none)."""
    m = FLOP_RE.match(mnemonic)
    fma = FMA_RE.match(mnemonic)
    if not m and not fma and not HADD_RE.match(mnemonic):
        return 0
    packed = (m.group(2) if m else (fma.group(4) if fma else "p")) == "p"
    lanes = 1
    if packed:
        lanes = 4 if "ymm" in operands else 2
    return lanes * (2 if fma else 1)


def disassemble(binary):
    """address -> (mnemonic, operands) for every instruction of the binary."""
    out = subprocess.run(["objdump", "-d", "--no-show-raw-insn", "-w", binary], capture_output=True, text=True,
                         check=True).stdout
    table = {}
    for line in out.splitlines():
        m = re.match(r"^\s+([0-9a-f]+):\s+(\S+)\s*(.*)$", line)
        if m:
            table[int(m.group(1), 16)] = (m.group(2), m.group(3))
    return table


def function_ranges(path):
    """Sorted (first line, function name) of the functions defined in a source file."""
    ranges = []
    try:
        lines = open(path).read().splitlines()
    except OSError:
        return ranges
    decl = re.compile(r"^\s*(?:template\s*<[^>]*>\s*)?(?:static\s+|inline\s+|constexpr\s+|\[\[[^\]]*\]\]\s*)*"
                      r"[A-Za-z_][\w:<>,]*(?:\s*[&*])?\s+[&*]?(\w+)\s*\(")
    for k, text in enumerate(lines, start=1):
        s = text.strip()
        if s.startswith(("//", "#", "return", "if", "for", "while", "else", "const ", "auto ", "using")):
            continue
        m = decl.match(text)
        if m and m.group(1) not in ("if", "for", "while", "switch", "return", "sizeof"):
            ranges.append((k, m.group(1)))
    return ranges


def enclosing(ranges, line):
    name = "?"
    for first, fn in ranges:
        if first > line:
            break
        name = fn
    return name


def part_of(path, fn_name, line, ranges_cache):
    """The part of the kernel an instruction belongs to."""
    base = path.rsplit("/", 1)[-1] if path else ""
    if fn_name and ("cbrt" in fn_name or fn_name in ("frexp", "__scalbn", "scalbn", "ldexp", "__ldexp")):
        return "model: libm cbrt"
    model_files = ("hyperelastic.hpp", "plane_stress.hpp", "hyperelastic_numerics.hpp", "gent.hpp",
                   "neo_hookean.hpp", "tensor.hpp", "lanes.hpp")
    if base in model_files:
        if base in ("hyperelastic.hpp", "plane_stress.hpp", "hyperelastic_numerics.hpp"):
            if path not in ranges_cache:
                ranges_cache[path] = function_ranges(path)
            return "model: " + enclosing(ranges_cache[path], line)
        return "model: " + base
    if base == "bond_geometry.hpp":
        if path not in ranges_cache:
            ranges_cache[path] = function_ranges(path)
        fn = enclosing(ranges_cache[path], line)
        return {"gather_point": "gather (per point)", "sum_selected": "masked sums", "masked_sums": "masked sums", "masked_sum": "masked sums",
                "bond_kinematics": "K^-1 and F", "force_scale": "force vector"}.get(fn, "geometry: " + fn)
    if base == "ba_force.hpp":
        return "kernel loop, force vector, stores"
    if base == "ba_force.cpp" or (fn_name and "assemble_force_density" in fn_name):
        return "assembly"
    return "other"


def parse(profile):
    """Yields (object, file, function, address, line, Ir) for every self-cost line."""
    names = {"ob": {}, "fl": {}, "fn": {}}
    cur = {"ob": "", "fl": "", "fi": None, "fn": ""}
    addr, line = 0, 0
    skip_next = False
    positions = ["instr", "line"]

    def name(kind, value):
        m = re.match(r"^\((\d+)\)\s*(.*)$", value)
        table = names["fl" if kind in ("fl", "fi", "fe", "cfi", "cfl") else kind.lstrip("c")]
        if not m:
            return value
        if m.group(2):
            table[m.group(1)] = m.group(2)
        return table.get(m.group(1), m.group(1))

    def sub(token, prev, base):
        if token == "*":
            return prev
        if token.startswith(("+", "-")):
            return prev + int(token, 0 if token[1:].startswith("0x") else 10)
        return int(token, base)

    for raw in open(profile):
        s = raw.rstrip("\n")
        if not s or s.startswith("#"):
            continue
        if s.startswith("positions:"):
            positions = s.split()[1:]
            continue
        m = re.match(r"^(ob|fl|fi|fe|fn|cob|cfi|cfl|cfn)=(.*)$", s)
        if m:
            kind, value = m.groups()
            v = name(kind, value)
            if kind == "ob":
                cur["ob"] = v
            elif kind == "fl":
                cur["fl"], cur["fi"] = v, None
            elif kind in ("fi", "fe"):
                cur["fi"] = None if v == cur["fl"] else v
            elif kind == "fn":
                cur["fn"] = v
            continue
        if s.startswith("calls="):
            skip_next = True
            continue
        if not (s[0].isdigit() or s[0] in "+-*"):
            continue
        tokens = s.split()
        if len(tokens) < len(positions):
            continue
        k = 0
        if "instr" in positions:
            addr = sub(tokens[k], addr, 16)
            k += 1
        if "line" in positions:
            line = sub(tokens[k], line, 10)
            k += 1
        cost = int(tokens[k]) if len(tokens) > k else 0
        if skip_next:
            skip_next = False
            continue
        yield cur["ob"], cur["fi"] or cur["fl"], cur["fn"], addr, line, cost


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("binary")
    ap.add_argument("profile")
    ap.add_argument("count", type=float)
    ap.add_argument("--label", default="region")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--brief", action="store_true", help="only the totals line")
    a = ap.parse_args()
    binary, profile, count, label = a.binary, a.profile, a.count, a.label
    asm = disassemble(binary)
    ranges_cache = {}
    parts = defaultdict(lambda: [0, 0, 0, 0, 0])  # instructions, flops, divisions+sqrt, fma instr, cbrt-less
    total_ir = total_flops = 0
    divs = 0
    unknown = 0
    cbrt_calls = 0
    for ob, path, fn, addr, line, ir in parse(profile):
        mnemonic, operands = asm.get(addr, ("?", ""))
        if mnemonic == "?":
            unknown += ir
        fl = flops_of(mnemonic, operands) * ir
        p = parts[part_of(path, fn, line, ranges_cache)]
        p[0] += ir
        p[1] += fl
        if re.match(r"^v?(div|sqrt)(s|p)d$", mnemonic):
            p[2] += ir
            divs += ir
        if mnemonic.startswith("call") and "cbrt" in operands:
            cbrt_calls += ir
        total_ir += ir
        total_flops += fl
    result = {
        "label": label,
        "count": count,
        "instructions_per_unit": total_ir / count,
        "flops_per_unit": total_flops / count,
        "div_sqrt_per_unit": divs / count,
        "cbrt_calls_per_unit": cbrt_calls / count,
        "unmapped_instruction_fraction": unknown / max(1, total_ir),
        "parts": {k: {"instructions": v[0] / count, "flops": v[1] / count, "div_sqrt": v[2] / count}
                  for k, v in sorted(parts.items(), key=lambda kv: -kv[1][0])},
    }
    if a.json:
        print(json.dumps(result))
        return
    print(f"{label}: {result['instructions_per_unit']:.1f} instructions, {result['flops_per_unit']:.1f} flops, "
          f"{result['div_sqrt_per_unit']:.2f} div/sqrt, {result['cbrt_calls_per_unit']:.2f} cbrt per unit "
          f"(unmapped {100 * result['unmapped_instruction_fraction']:.2f} %)")
    if a.brief:
        return
    for k, v in result["parts"].items():
        print(f"  {k:36s} {v['instructions']:8.1f} instr ({100 * v['instructions'] / result['instructions_per_unit']:5.1f} %)"
              f"  {v['flops']:7.1f} flops  {v['div_sqrt']:5.2f} div/sqrt")


if __name__ == "__main__":
    main()
