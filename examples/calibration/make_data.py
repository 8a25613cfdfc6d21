#!/usr/bin/python3
"""Writes pure_shear_data.csv: SYNTHETIC pure-shear test data for the calibration
example. docs/method.md gives no measured points (only eq 36 and three of its values), so
the data are the paper's Gent response (eq 36, mu = 4.55 kPa, Jm = 162.6) at 25
stretches from 1.2 to 5.125, times 1 + 1 % Gaussian noise (numpy seed 2026).

    /usr/bin/python3 examples/calibration/make_data.py
"""
import os

import numpy as np

mu, Jm = 4.55, 162.6  # kPa, -
rng = np.random.default_rng(2026)
stretch = np.linspace(1.2, 5.125, 25)
stress = mu * Jm * (stretch - stretch**-3) / (Jm - stretch**2 - stretch**-2 + 2)
noisy = stress * (1 + 0.01 * rng.standard_normal(stretch.size))
path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "pure_shear_data.csv")
with open(path, "w") as f:
    f.write("# SYNTHETIC: paper eq 36 (mu 4.55 kPa, Jm 162.6) with 1 % noise, seed 2026 (make_data.py)\n")
    f.write("# mode: pure_shear\n")
    f.write("stretch,nominal_stress_kPa\n")
    for l, p in zip(stretch, noisy):
        f.write(f"{l:.6f},{p:.6f}\n")
print(f"wrote {path}")
