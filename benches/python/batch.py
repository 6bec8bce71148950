"""The hunting motion of benches/c_host/hunting.c through railcontact.solve_batch: prints the
wall-clock µs per row of one batch (rows carried as the FMU's steps), the same poses, inputs and
parameters as the C host's `hunting` run.

Usage: python benches/python/batch.py STEPS NORMAL TANGENTIAL PLANAR
"""

import sys
import time

import numpy as np
import railcontact

steps, normal, tangential, planar = (int(a) for a in sys.argv[1:5])
h, q, v = 1e-3, 78500.0, 30.0
w = 2.0 * np.pi * 5.0
case = {
    "normalModel": normal,
    "tangentialModel": tangential,
    "planarPatch": bool(planar),
    "Qleft": q,
    "Qright": q,
    "vx": v,
    "omega": v / 0.46 * 1.001,
}
# The C host's untimed first step (start values), then its timed steps at t = h, 2h, ...
t = np.arange(steps + 1) * h
s, c = np.sin(w * t), np.cos(w * t)
inputs = {"y": 3e-3 * s, "yaw": 1e-3 * s, "vy": 3e-3 * w * c, "yawRate": 1e-3 * w * c}
for name in inputs:
    inputs[name][0] = 0.0
start = time.perf_counter()
out = railcontact.solve_batch(case, inputs)
elapsed = time.perf_counter() - start
if np.any(out["status"] == 2):
    sys.exit("a row was refused")
print(f"{1e6 * elapsed / (steps + 1):.2f}")
