"""Axis labels from bapd's column and field names, for scripts/plot_*.py.

A name carries its SI unit as a suffix (history.csv: top_nominal_stress_Pa, time_s,
P_ux_m, crack_area_m2, effective_fracture_energy_J_m2) or is a dimensionless
quantity (stretch, damage, broken_bonds). `axis_label` turns it into words and a unit
scaled to the values plotted, and gives the factor the values are multiplied by:

    >>> axis_label("top_nominal_stress_Pa", [0.0, 2.4e4])
    ('top nominal stress (kPa)', 0.001)
    >>> axis_label("stretch", [1.0, 5.0])
    ('applied stretch λ (-)', 1.0)
    >>> axis_label("P_uy_m", [0.0, 0.012])
    ('P displacement y (mm)', 1000.0)
"""
import math

# suffix -> SI unit, longest first so that _J_m2 wins over _m2 and _m
SUFFIXES = [("_J_m2", "J/m²"), ("_m_s", "m/s"), ("_m2", "m²"), ("_m3", "m³"), ("_kPa", "kPa"), ("_Pa", "Pa"),
            ("_N", "N"), ("_J", "J"), ("_m", "m"), ("_s", "s")]
# names without a unit suffix: the words and the unit to show
DIMENSIONLESS = {"stretch": ("applied stretch λ", "-"), "step": ("time step number", None),
                 "broken_bonds": ("broken bonds", None), "damage": ("damage", "-"),
                 "max_bond_stretch": ("largest bond stretch", "-"), "thickness_stretch": ("thickness stretch λ₃", "-"),
                 "deformation_gradient": ("deformation gradient F", "-"), "natural_id": ("natural id", None),
                 "rank": ("rank", None), "weighted_rms": ("weighted RMS error", "-"), "aic": ("AIC", None)}
# words within a name
WORDS = {"ux": "displacement x", "uy": "displacement y", "uz": "displacement z", "dt": "time step", "rms": "RMS",
         "x": "x", "y": "y", "z": "z"}
# SI unit -> the units a plot may show it in, with their factor per SI unit
SCALES = {"Pa": [("Pa", 1.0), ("kPa", 1e-3), ("MPa", 1e-6), ("GPa", 1e-9)],
          "kPa": [("kPa", 1.0), ("MPa", 1e-3)],
          "N": [("µN", 1e6), ("mN", 1e3), ("N", 1.0), ("kN", 1e-3)],
          "J": [("µJ", 1e6), ("mJ", 1e3), ("J", 1.0)],
          "s": [("µs", 1e6), ("ms", 1e3), ("s", 1.0)],
          "m": [("µm", 1e6), ("mm", 1e3), ("m", 1.0)],
          "m²": [("mm²", 1e6), ("m²", 1.0)],
          "m/s": [("mm/s", 1e3), ("m/s", 1.0)],
          "J/m³": [("J/m³", 1.0), ("kJ/m³", 1e-3), ("MJ/m³", 1e-6)],
          "N/m³": [("N/m³", 1.0), ("kN/m³", 1e-3), ("MN/m³", 1e-6), ("GN/m³", 1e-9)]}
# lengths and areas stay in mm and mm² from 1 µm and 1 µm² up: a gel sheet is measured in mm
PREFERRED = {"m": ("mm", 1e3, 1e-6), "m²": ("mm²", 1e6, 1e-12)}


def split_name(name):
    """(words, SI unit or None) of a column name: top_nominal_stress_Pa -> ('top nominal stress', 'Pa')."""
    if name in DIMENSIONLESS:
        return DIMENSIONLESS[name]
    unit = None
    for suffix, si in SUFFIXES:
        if name.endswith(suffix) and len(name) > len(suffix):
            name, unit = name[: -len(suffix)], si
            break
    words = " ".join(WORDS.get(w, w) for w in name.split("_"))
    if name in DIMENSIONLESS:  # e.g. a dimensionless name given a suffix
        words = DIMENSIONLESS[name][0]
    return words, unit


def display_unit(unit, values):
    """(unit shown, factor per SI unit) for values in `unit`: the largest unit in which
    the largest |value| is at least 1 (kPa for 2.4e4 Pa), lengths in mm from 1 µm up."""
    scales = SCALES.get(unit)
    if not scales:
        return unit, 1.0
    finite = [abs(float(v)) for v in values if v is not None and math.isfinite(float(v))]
    top = max(finite) if finite else 0.0
    if unit in PREFERRED and top >= PREFERRED[unit][2]:
        return PREFERRED[unit][:2]
    if top == 0.0:
        return unit, 1.0
    chosen = scales[0]
    for shown, factor in scales:  # ordered from the smallest unit to the largest
        if top * factor >= 1.0:
            chosen = (shown, factor)
    return chosen


def axis_label(name, values=()):
    """(label, factor): 'top nominal stress (kPa)', 1e-3 for top_nominal_stress_Pa."""
    words, unit = split_name(name)
    if unit is None:
        return words, 1.0
    if unit == "-":
        return f"{words} (-)", 1.0
    shown, factor = display_unit(unit, values)
    return f"{words} ({shown})", factor


def common_label(names, values):
    """(label, factor) for several columns drawn on one axis: their words joined and the
    unit they share, scaled to all their values; None when the units differ."""
    parts = [split_name(n) for n in names]
    units = {u for _, u in parts}
    if len(units) != 1:
        return None
    unit = units.pop()
    everything = [v for vs in values for v in vs]
    words = ", ".join(w for w, _ in parts)
    if unit is None:
        return words, 1.0
    if unit == "-":
        return f"{words} (-)", 1.0
    shown, factor = display_unit(unit, everything)
    return f"{words} ({shown})", factor
