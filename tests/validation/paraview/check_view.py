"""Checks what scripts/view_fields.py left: its PNG shows coloured points, and its
state file loads back in ParaView with every point drawn as a sphere half a point
spacing in radius, at the deformed positions (x + u), coloured by a field (the grips,
where the files mark them, in one grey: a second point cloud of load_set > 0 points), at the
last output time; rendered again without the colour bar and the text, the points
cover many pixels each (1-pixel points, ParaView's default, cover one).

    xvfb-run -a pvpython check_view.py VIEW.png VIEW.pvsm RUN_DIR N_POINTS LAST_STEP [DX]
Exits 1 with a line per problem."""
import os
import sys

from paraview import servermanager
from paraview import simple as pv
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

png, pvsm, run = sys.argv[1:4]
n_points, last_step = int(sys.argv[4]), int(sys.argv[5])
dx = float(sys.argv[6]) if len(sys.argv) > 6 else 0.001
problems = []


def pixels(path):
    """RGB of every pixel of a PNG (n x 3)."""
    img = vtkPNGReader()
    img.SetFileName(path)
    img.Update()
    return vtk_to_numpy(img.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)


def coloured(rgb):
    """Pixels that are neither white, black nor grey: the colour map's."""
    return (rgb.max(axis=1) - rgb.min(axis=1)) > 30


# The PNG view_fields.py wrote: a picture with many colours of the map.
rgb = pixels(png)
distinct = len({tuple(c) for c in rgb[coloured(rgb)]})
print(f"{png}: {int(coloured(rgb).sum())} coloured pixels, {distinct} distinct colours")
if distinct < 20:
    problems.append(f"{png}: {distinct} distinct colours: the points are not coloured by a varying field")

# The state: the displayed point clouds and how they are drawn. One is coloured by a
# field (the specimen, or every point); the others, if any, are the grips in one grey.
pv.LoadState(pvsm)
view = pv.GetActiveViewOrCreate("RenderView")
drawn_sources = []
for (name, _), source in pv.GetSources().items():
    rep = pv.GetDisplayProperties(source, view)
    if rep is not None and getattr(rep, "Visibility", 0) and hasattr(rep, "Representation") and rep.Representation == "Point Gaussian":
        drawn_sources.append((name, source, rep))
coloured_sources = [(name, s, r) for name, s, r in drawn_sources if r.ColorArrayName[1]]
if len(coloured_sources) != 1:
    problems.append(f"{pvsm}: {len(coloured_sources)} point clouds coloured by a field, expected 1")
    shown = None
else:
    _, shown, representation = coloured_sources[0]
    field = representation.ColorArrayName[1]
total, shown_points = 0, 0
for name, source, rep in drawn_sources:
    if rep.ShaderPreset != "Sphere":
        problems.append(f"{pvsm}: {name}: shader {rep.ShaderPreset}, expected Sphere")
    radius = rep.GaussianRadius
    if abs(radius - 0.5 * dx) > 1e-9 * dx:  # half the lattice spacing, to round-off
        problems.append(f"{pvsm}: {name}: sphere radius {radius}, expected half the point spacing {0.5 * dx}")
    source.UpdatePipeline(view.ViewTime)
    data = servermanager.Fetch(source)
    pd = data.GetPointData()
    total += data.GetNumberOfPoints()
    if source is shown:
        shown_points = data.GetNumberOfPoints()
    else:
        held = pd.GetArray("load_set")
        if held is None or (vtk_to_numpy(held) <= 0).any():
            problems.append(f"{pvsm}: {name} is drawn uncoloured but holds points no load set holds")
    points = vtk_to_numpy(data.GetPoints().GetData())
    reference, u = pd.GetArray("reference_position"), pd.GetArray("displacement")
    if reference is None:  # files at the reference positions: the warped points are at position
        reference, u = pd.GetArray("position"), None
        if reference is not None and abs(points - vtk_to_numpy(reference)).max() > 1e-12 * abs(vtk_to_numpy(reference)).max():
            problems.append(f"{pvsm}: {name}: the points drawn are not at the current positions (no warp by the displacement?)")
    elif u is not None:
        expected = vtk_to_numpy(reference) + vtk_to_numpy(u)
        if abs(points - expected).max() > 1e-12 * abs(expected).max():
            problems.append(f"{pvsm}: {name}: the points drawn are not at reference_position + displacement")
    step = data.GetFieldData().GetAbstractArray("step")
    if step is None or step.GetVariantValue(0).ToDouble() != last_step:
        problems.append(f"{pvsm}: {name}: not at the last output time (step {last_step})")
if total != n_points:
    problems.append(f"{pvsm}: {total} points drawn, expected {n_points}")
if shown is not None:
    # Rendered again without the colour bar and the text: the spheres cover many pixels each.
    for (name, _), source in pv.GetSources().items():
        if source is not shown:
            pv.Hide(source, view)
    representation.SetScalarBarVisibility(view, False)
    view.OrientationAxesVisibility = 0
    view.ViewSize = [600, 450]
    again = os.path.join(os.path.dirname(os.path.abspath(png)), os.path.basename(png).replace(".png", "_points.png"))
    pv.SaveScreenshot(again, view, ImageResolution=[600, 450])
    drawn = int(coloured(pixels(again)).sum())
    print(f"{again}: {drawn} coloured pixels for {shown_points} points ({drawn / max(shown_points, 1):.1f} each), coloured by {field}")
    # 1-pixel points would colour about 1 pixel each; spheres that touch cover the sheet:
    # at least 20 pixels a point in a 600 x 450 picture of 720 points.
    if drawn < 20 * shown_points:
        problems.append(f"{again}: {drawn} coloured pixels, fewer than 20 a point: the points are not drawn a spacing wide")

# Tear the loaded state down before exit, filters before their inputs, then the view:
# left to the interpreter's exit, the render window's GL context goes first and Xlib
# aborts with GLXBadContext.
for key in sorted(pv.GetSources(), key=lambda k: int(k[1]), reverse=True):
    pv.Delete(pv.GetSources()[key])
pv.Delete(view)
for p in problems:
    print("FAIL", p)
sys.exit(1 if problems else 0)
