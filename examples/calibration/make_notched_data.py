#!/usr/bin/python3
"""Writes notched_pure_shear_data.csv: a SYNTHETIC notched pure-shear test for the
toughness example, as a test machine's export (extension in mm, force in N). It is not
measured data. docs/method.md reports only the peak of the paper's notched test: 10.25 kPa
with the crack running at stretch about 3. The curve is shaped on that peak:

  * up to stretch 3 the nominal stress is the paper's Gent pure-shear response (eq 36,
    mu = 4.55 kPa, Jm = 162.6) times 10.25 / 14.1 (14.1 kPa: eq 36 at 3), so that the
    peak is 10.25 kPa at stretch 3 (the notched sheet carries less than the un-notched
    one at the same stretch; the shape below the peak does not enter the toughness);
  * past 3 the crack runs through the ligament and the force falls to 40, 8 and 1 % of
    the peak in three samples, then the sheet is cut through (zero force);
  * samples every 0.05 of stretch (0.5 mm of extension), times 1 + 1 % Gaussian noise
    (numpy seed 2026);
  * the paper's sheet: 10 mm between the clamps (H0), 70 mm wide, 3 mm thick, so the
    force is the stress times 2.1e-4 m^2.

    /usr/bin/python3 examples/calibration/make_notched_data.py
"""
import os

import numpy as np

mu, Jm = 4.55e3, 162.6  # Pa, -
H0, width, thickness = 0.010, 0.070, 0.003  # m
peak_stretch, peak_stress = 3.0, 10.25e3  # Pa


def eq36(stretch):
    return mu * Jm * (stretch - stretch**-3) / (Jm - stretch**2 - stretch**-2 + 2)


rng = np.random.default_rng(2026)
stretch = 1.0 + 0.05 * np.arange(1, 47)  # 1.05 to 3.3
stress = np.where(stretch <= peak_stretch + 1e-12, eq36(stretch) * peak_stress / eq36(peak_stretch), 0.0)
after = np.flatnonzero(stretch > peak_stretch + 1e-12)
for k, fraction in zip(after, (0.40, 0.08, 0.01)):
    stress[k] = fraction * peak_stress
noisy = stress * (1 + 0.01 * rng.standard_normal(stretch.size))
header = [
    "# SYNTHETIC, not measured: a notched pure-shear curve shaped on the paper's reported peak (10.25 kPa,",
    "# crack at stretch 3): 10.25/14.1 x eq 36 (mu 4.55 kPa, Jm 162.6) to stretch 3, then the crack's drop;",
    "# 1 % noise, seed 2026 (make_notched_data.py). Sheet: H0 = 10 mm, 70 mm x 3 mm.",
    "# mode: notched_pure_shear",
    "Time (s),Extension (mm),Load (N)",
    "0,0,0",  # the rest point (bapd-fit drops it)
]
rows = [f"{k + 1},{(l - 1) * H0 * 1e3:.4f},{p * width * thickness:.6f}" for k, (l, p) in enumerate(zip(stretch, noisy))]
path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "notched_pure_shear_data.csv")
with open(path, "w") as f:
    f.write("\n".join(header + rows) + "\n")
print(f"wrote {path}")
