#!/usr/bin/env python3
"""The tables of src/linalg/vpow.rs, correctly rounded to f64 (mpmath at 60 digits, then the nearest f64):

    LOG2_CELL[j] = log2(1 + j/512),  j = 0..511   (the logarithm of each cell's left edge)
    EXP2_FRACTION[j] = 2^(j/128),    j = 0..127
    the polynomial coefficients (-1)^(i+1) / (i ln 2), i = 1..5 (log2(1 + r)) and (ln(2)/128)^i / i!, i = 1..5 (2^(s/128), s in [-1/2, 1/2])

    python3 scripts/pow_tables.py > /tmp/tables.rs    # then compare with the constants in vpow.rs
"""
import struct

import mpmath

mpmath.mp.dps = 60


def bits(x):
    """The bits of the f64 nearest to the mpmath number x (mpmath's float() rounds to nearest)."""
    return struct.unpack("<Q", struct.pack("<d", float(x)))[0]


def table(name, values, per_line=4):
    print(f"const {name}: [u64; {len(values)}] = [")
    for i in range(0, len(values), per_line):
        print("    " + " ".join(f"0x{bits(v):016x}," for v in values[i:i + per_line]))
    print("];")


table("LOG2_CELL", [mpmath.log(1 + mpmath.mpf(j) / 512, 2) for j in range(512)])
table("EXP2_FRACTION", [mpmath.power(2, mpmath.mpf(j) / 128) for j in range(128)])
ln2 = mpmath.log(2)
print("LOG2_1P:", ", ".join(repr(float((-1) ** (i + 1) / (i * ln2))) for i in range(1, 6)))
print("EXP2_S128:", ", ".join(repr(float((ln2 / 128)**i / mpmath.factorial(i))) for i in range(1, 6)))
