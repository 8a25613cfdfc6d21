#!/usr/bin/python3
"""Reads a bapd field series the way ParaView does, through its XDMF index, and
checks it: a temporal collection of Polyvertex point clouds whose data items name
datasets of the right shape in existing HDF5 files; reference positions on the
lattice in natural order; an explicit Polyvertex connectivity 0 .. N-1 (the natural ids);
the run state (time_s, step, stretch) as one-value Grid attributes that agree with the
frame; no displacement at t = 0 (no velocity off the grips); position = reference +
displacement; damage in [0, 1], zero at first and non-zero at the end; bond stretch 1
at rest; volume dx^2 thickness; no stress, energy or thickness change at rest; the
Cauchy stress P F^T / J of the written nominal stress and deformation gradient, whose
F_33 is the thickness stretch; sum V W = the internal energy of history.csv."""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def fail(message):
    print("FAILED:", message)
    sys.exit(1)


def read_item(base, item, n):
    """The array a DataItem names ("file.h5:/dataset"), checked against its Dimensions."""
    if item.get("Format") != "HDF":
        fail(f"DataItem format {item.get('Format')}")
    path, dataset = item.text.strip().split(":")
    dims = tuple(int(d) for d in item.get("Dimensions").split())
    if dims[0] != n:
        fail(f"{item.text.strip()}: {dims[0]} rows for {n} points")
    with h5py.File(os.path.join(base, path), "r") as f:
        data = f[dataset][()]
    if data.shape != dims:
        fail(f"{item.text.strip()}: shape {data.shape}, the XDMF says {dims}")
    return data


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--dx", type=float, required=True)
    p.add_argument("--nx", type=int, required=True)
    p.add_argument("--ny", type=int, required=True)
    p.add_argument("--grip_rows", type=int, default=0, help="rows of each grip outside the sheet, below and above it")
    p.add_argument("--interval", type=int, required=True)
    p.add_argument("--last", type=int, required=True, help="the run's last step")
    p.add_argument("--thickness", type=float, required=True)
    p.add_argument("--ranks", type=int, required=True, help="the run's rank count")
    p.add_argument("xdmf")
    args = p.parse_args()
    base = os.path.dirname(os.path.abspath(args.xdmf))
    rows = args.ny + 2 * args.grip_rows  # the grips' rows outside the sheet: j from -grip_rows
    n = args.nx * rows

    root = ET.parse(args.xdmf).getroot()
    series = root.find("Domain/Grid")
    if series.get("GridType") != "Collection" or series.get("CollectionType") != "Temporal":
        fail("the top grid is not a temporal collection")
    frames = []
    for grid in series.findall("Grid"):
        topology = grid.find("Topology")
        if topology.get("TopologyType") != "Polyvertex" or int(topology.get("NumberOfElements")) != n:
            fail(f"{grid.get('Name')}: topology {topology.attrib}")
        if not np.array_equal(read_item(base, topology.find("DataItem"), n), np.arange(n)):
            fail(f"{grid.get('Name')}: the connectivity is not 0 .. {n - 1}")
        if grid.find("Geometry").get("GeometryType") != "XYZ":
            fail(f"{grid.get('Name')}: geometry type")
        fields = {"position": read_item(base, grid.find("Geometry/DataItem"), n)}
        state = {}
        for attribute in grid.findall("Attribute"):
            item = attribute.find("DataItem")
            if attribute.get("Center") == "Grid":
                if item.get("Format") != "XML" or item.get("Dimensions") != "1":
                    fail(f"{grid.get('Name')}: run state {attribute.get('Name')} is not one value")
                state[attribute.get("Name")] = float(item.text)
            else:
                fields[attribute.get("Name")] = read_item(base, item, n)
        time = float(grid.find("Time").get("Value"))
        if sorted(state) != ["step", "stretch", "time_s"]:
            fail(f"{grid.get('Name')}: run state {sorted(state)}")
        if state["time_s"] != time or f"step {state['step']:.0f}" != grid.get("Name") or not state["stretch"] >= 1:
            fail(f"{grid.get('Name')}: run state {state} at t = {time}")
        frames.append((time, grid.get("Name"), fields))
    expected = list(range(0, args.last + 1, args.interval))
    if expected[-1] != args.last:
        expected.append(args.last)
    names = [name for _, name, _ in frames]
    if names != [f"step {s}" for s in expected]:
        fail(f"frames {names}, expected steps {expected}")
    times = [t for t, _, _ in frames]
    if times[0] != 0 or any(b <= a for a, b in zip(times, times[1:])):
        fail(f"times {times} do not increase from 0")

    # Natural order is lattice order: x fastest, cell centres (i + 1/2) dx.
    i, j = np.meshgrid(np.arange(args.nx), np.arange(-args.grip_rows, args.ny + args.grip_rows))
    lattice = np.column_stack([(i.ravel() + 0.5) * args.dx, (j.ravel() + 0.5) * args.dx, np.zeros(n)])
    for t, name, f in frames:
        if not np.allclose(f["reference_position"], lattice, rtol=0, atol=1e-15):  # round-off of (i + 1/2) dx
            fail(f"{name}: reference positions are not the lattice in natural order")
        if not np.array_equal(f["position"], f["reference_position"] + f["displacement"]):
            fail(f"{name}: position != reference + displacement")
        if np.any(f["displacement"][:, 2] != 0) or np.any(f["velocity"][:, 2] != 0):
            fail(f"{name}: out-of-plane components")
        d = f["damage"]
        if not (np.all(d >= 0) and np.all(d <= 1)):
            fail(f"{name}: damage outside [0, 1]: {d.min()} .. {d.max()}")
        if not np.all(np.isfinite(f["max_bond_stretch"])) or np.any(f["max_bond_stretch"] < 0):
            fail(f"{name}: bad max_bond_stretch")
        if not np.array_equal(f["natural_id"], np.arange(n)):
            fail(f"{name}: natural_id is not the row")
        if sorted(set(f["rank"].tolist())) != list(range(args.ranks)):
            fail(f"{name}: ranks {sorted(set(f['rank'].tolist()))}, expected 0 .. {args.ranks - 1}")
        if not np.allclose(f["volume"], args.dx * args.dx * args.thickness, rtol=1e-15, atol=0):
            fail(f"{name}: volume is not dx^2 thickness")
        P, F, sigma = (f[k].reshape(n, 3, 3) for k in ("nominal_stress", "deformation_gradient", "cauchy_stress"))
        if not np.array_equal(F[:, 2, 2], f["thickness_stretch"]):
            fail(f"{name}: F_33 is not the thickness stretch")
        J = np.linalg.det(F)
        stressed = J > 0  # points whose bonds carry force (else all zeros)
        if np.any(P[~stressed] != 0) or np.any(sigma[~stressed] != 0):
            fail(f"{name}: stress at points without a stressed bond")
        expected = np.einsum("nik,njk->nij", P[stressed], F[stressed]) / J[stressed, None, None]
        if not np.allclose(sigma[stressed], expected, rtol=0, atol=1e-12 * max(np.abs(sigma).max(), 1.0)):  # round-off
            fail(f"{name}: cauchy_stress != P F^T / J")
        if np.any(f["strain_energy_density"] < 0) or np.any(f["force_density"][:, 2] != 0):
            fail(f"{name}: negative energy density or out-of-plane force")
    # sum_i V_i W_i is the history's internal energy (the same per-point energies; the
    # history sums them reproducibly, numpy in another order: round-off only).
    history = os.path.join(base, "history.csv")
    compared = 0
    if os.path.exists(history):
        rows = np.genfromtxt(history, delimiter=",", names=True)
        energy = {int(r["step"]): r["internal_energy_J"] for r in np.atleast_1d(rows)}
        for _, name, f in frames:
            step = int(name.split()[-1])
            if step in energy:
                total = float(np.sum(f["volume"] * f["strain_energy_density"]))
                if abs(total - energy[step]) > 1e-12 * max(abs(energy[step]), 1e-18):  # (1e-18 J: an energy of 0 at rest)
                    fail(f"{name}: sum V W = {total!r} J, history.csv says internal_energy_J = {energy[step]!r}")
                compared += 1
    first, last = frames[0][2], frames[-1][2]
    if np.any(first["displacement"] != 0):
        fail("the displacement at t = 0 is not zero")
    inside = (j.ravel() >= 0) & (j.ravel() < args.ny)  # off the grips, which move from t = 0
    if np.any(first["velocity"][inside] != 0):
        fail("the velocity at t = 0 is not zero off the grips")
    if np.any(first["damage"] != 0) or not np.allclose(first["max_bond_stretch"], 1, rtol=0, atol=1e-15):
        fail("the body at t = 0 is not intact and unstretched")
    # At rest F_ij = I up to round-off (~1e-15), so P ~ K 1e-15 with K = 100 mu ~ 5e5 Pa.
    if np.abs(first["nominal_stress"]).max() > 1e-6 or np.abs(first["thickness_stretch"] - 1).max() > 1e-12:
        fail("stress or a thickness change at t = 0")
    if np.abs(first["strain_energy_density"]).max() > 1e-12:
        fail("strain energy at t = 0")
    if not np.abs(last["cauchy_stress"]).max() > 0 or not last["strain_energy_density"].max() > 0:
        fail("no stress or energy at the end of a stretched run")
    if not last["damage"].max() > 0:
        fail("no damage at the end of a run whose crack has run")
    print(f"{len(frames)} frames of {n} points, t = 0 .. {times[-1]:.6g} s; final damage up to {last['damage'].max():.3f}, "
          f"largest bond stretch {last['max_bond_stretch'].max():.3f}, largest Cauchy stress {np.abs(last['cauchy_stress']).max():.4g} Pa, "
          f"thickness stretch {last['thickness_stretch'][last['thickness_stretch'] > 0].min():.3f} .. {last['thickness_stretch'].max():.3f}; "
          f"sum V W = the history's internal energy at {compared} frames")


if __name__ == "__main__":
    main()
