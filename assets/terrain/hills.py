"""Writes hills.npy, the example height file of docs/terrain.md: 24 Gaussian hills and hollows
(4 to 10 cm high or deep, 0.5 to 1.3 m wide, from a seeded stream) on an 81 x 81 grid, meant to
be laid over the default 16 m square (0.2 m apart). Standard library only:

    python3 assets/terrain/hills.py assets/terrain/hills.npy
"""

import math
import random
import struct
import sys

rng = random.Random(7)
bumps = [
    (rng.uniform(-8, 8), rng.uniform(-8, 8), rng.choice([-1, 1]) * rng.uniform(0.04, 0.10), rng.uniform(0.5, 1.3))
    for _ in range(24)
]
n = 81
values = []
for i in range(n):  # the first axis runs along +x
    x = -8 + 16 * i / (n - 1)
    for j in range(n):  # the second along +y
        y = -8 + 16 * j / (n - 1)
        values.append(sum(a * math.exp(-((x - bx) ** 2 + (y - by) ** 2) / (2 * s * s)) for bx, by, a, s in bumps))
header = "{'descr': '<f4', 'fortran_order': False, 'shape': (%d, %d), }" % (n, n)
header += " " * (64 - (10 + len(header) + 1) % 64) + "\n"
with open(sys.argv[1], "wb") as f:
    f.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode())
    f.write(b"".join(struct.pack("<f", v) for v in values))
