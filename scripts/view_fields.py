"""Opens a bapd run's fields in ParaView ready to look at: the points as spheres one
point spacing wide, at their deformed positions, coloured by a field with its colour
bar, the run state (step, time, stretch) written on the picture; saves a PNG and, on
request, a ParaView state file that the ParaView window opens as it is.

    xvfb-run -a pvpython scripts/view_fields.py output/pure_shear --png pure_shear.png
    pvpython scripts/view_fields.py output/notched --field damage --state notched.pvsm
    paraview --state=notched.pvsm                        # the same view, interactive
    pvpython scripts/view_fields.py output/run --field cauchy_stress --component yy --time 2.5 --png s.png

RUN is the run's -output_dir or its fields.xdmf (-output_fields). The field is
--field (default: the von Mises stress when the files hold it, else the
displacement), its magnitude or a --component (x, y, z of a vector; xx, xy, ... zz of
a tensor). The time shown is the output time nearest to --time, else the last. Files
written with -output_fields_geometry reference are warped by their displacement, so
the points are always at x + u. The sphere radius is half the point spacing
(estimated from the reference positions), --radius-factor scales it. The points the
load sets hold (the grips; the files' load_set dataset) are grey and out of the colour
scale, --grips show colours them like the specimen. Without a
display, run it under xvfb-run (-noreset keeps Xvfb up between pvpython's X
connections: xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython ...).
Needs ParaView's pvpython (Debian's paraview, python3-paraview; scripts/install-deps.sh).
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
from paraview import servermanager
from paraview import simple as pv
from vtkmodules.util.numpy_support import vtk_to_numpy

# SI unit of each field bapd writes (docs/options.md, "Output")
UNITS = {"damage": "-", "max_bond_stretch": "-", "displacement": "m", "velocity": "m/s", "reference_position": "m",
         "position": "m", "thickness_stretch": "-", "strain_energy_density": "J/m^3", "volume": "m^3",
         "force_density": "N/m^3", "nominal_stress": "Pa", "cauchy_stress": "Pa", "deformation_gradient": "-"}
TENSOR_COMPONENTS = ["xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"]  # row-major 3x3, as in the files


def fail(message):
    print(f"view_fields.py: error: {message}", file=sys.stderr)
    sys.exit(1)


def geometry_of(xdmf):
    """The dataset fields.xdmf draws the points at: position (current) or reference_position."""
    try:
        grid = ET.parse(xdmf).getroot().find("Domain/Grid").find("Grid")
        return grid.find("Geometry/DataItem").text.strip().split(":/")[-1]
    except (ET.ParseError, AttributeError) as e:
        fail(f"{xdmf}: not a bapd field index ({e})")


def point_spacing(reference):
    """The lattice spacing of the reference positions, or for scattered points the
    spacing that fills their bounding box: (box measure / N)^(1/D)."""
    extent = np.ptp(reference, axis=0)
    dims = extent > 1e-12 * max(extent.max(), 1e-300)
    estimate = (np.prod(extent[dims]) / len(reference)) ** (1.0 / max(dims.sum(), 1)) if dims.any() else 1.0
    x = np.unique(np.round(reference[:, 0], 12))
    gaps = np.diff(x)
    gaps = gaps[gaps > 1e-9 * estimate]
    lattice = gaps.min() if len(gaps) else 0.0
    return float(lattice) if lattice > 0.5 * estimate else float(estimate)


def spheres(display, spacing, radius_factor):
    """Draws a display's points as spheres, half a point spacing in radius by default."""
    display.SetRepresentationType("Point Gaussian")
    display.ShaderPreset = "Sphere"
    display.GaussianRadius = 0.5 * spacing * radius_factor
    return display


def default_field(arrays):
    for name in arrays:
        if "von_mises" in name.lower():
            return name
    return "displacement"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run", help="the run's -output_dir, or its fields.xdmf")
    p.add_argument("--field", help="the point array to colour by (default: von Mises stress if present, else displacement)")
    p.add_argument("--component", default="magnitude",
                   choices=["magnitude", "x", "y", "z", *TENSOR_COMPONENTS], help="of a vector or tensor field")
    p.add_argument("--time", type=float, help="the output time nearest to this [s] (default: the last)")
    p.add_argument("--png", help="write the picture to this PNG")
    p.add_argument("--state", help="write a ParaView state file (.pvsm): paraview --state=FILE opens this view")
    p.add_argument("--resolution", nargs=2, type=int, default=[1200, 900], metavar=("W", "H"))
    p.add_argument("--radius-factor", type=float, default=1.0, help="sphere radius in half point spacings (default 1)")
    p.add_argument("--grips", choices=["apart", "show"], default="apart",
                   help="apart (default): the points the load sets hold in grey, out of the colour scale; "
                        "show: coloured like the specimen")
    args = p.parse_args()
    if not args.png and not args.state:
        fail("nothing to write: give --png FILE.png and/or --state FILE.pvsm")

    xdmf = os.path.abspath(args.run if args.run.endswith(".xdmf") else os.path.join(args.run, "fields.xdmf"))
    if not os.path.exists(xdmf):
        fail(f"{xdmf} not found: run bapd with -output_fields")
    geometry = geometry_of(xdmf)

    reader = pv.OpenDataFile(xdmf)
    reader.UpdatePipelineInformation()
    times = list(getattr(reader, "TimestepValues", []) or [0.0])
    time = min(times, key=lambda t: abs(t - args.time)) if args.time is not None else times[-1]
    reader.UpdatePipeline(time)
    arrays = [reader.PointData.GetArray(k).GetName() for k in range(len(reader.PointData))]
    field = args.field or default_field(arrays)
    if field not in arrays:
        fail(f"no point array '{field}' in {xdmf}; it has {', '.join(sorted(arrays))}")
    components = reader.PointData[field].GetNumberOfComponents()

    data = servermanager.Fetch(reader)
    pd = data.GetPointData()
    if pd.GetArray("reference_position") is not None:
        reference = vtk_to_numpy(pd.GetArray("reference_position"))
    else:  # drawn at the reference positions: the points are they
        reference = vtk_to_numpy(data.GetPoints().GetData())
    spacing = point_spacing(reference)
    state = {}
    for name in ("step", "time_s", "stretch"):
        a = data.GetFieldData().GetAbstractArray(name)
        if a is not None and a.GetNumberOfTuples() == 1:
            state[name] = a.GetVariantValue(0).ToDouble()

    # The points at x + u: the file's geometry already, or warped from the reference.
    source = reader
    if geometry == "reference_position" and "displacement" in arrays:
        source = pv.WarpByVector(registrationName="deformed", Input=reader, Vectors=["POINTS", "displacement"], ScaleFactor=1.0)

    view = pv.GetActiveViewOrCreate("RenderView")
    scene = pv.GetAnimationScene()  # the time shown, before the colour range is taken
    scene.UpdateAnimationUsingDataTimeSteps()
    scene.AnimationTime = time
    view.ViewTime = time
    view.ViewSize = list(args.resolution)
    view.OrientationAxesVisibility = 1
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]  # white, for reports; text and labels black
    # The grips (the points the load sets hold, dataset load_set > 0) in grey, apart from
    # the specimen and out of its colour scale: their stresses are the clamp's.
    grips = None
    if "load_set" in arrays and args.grips == "apart":
        specimen = pv.Threshold(registrationName="specimen", Input=source, Scalars=["POINTS", "load_set"],
                                LowerThreshold=-0.5, UpperThreshold=0.5, ThresholdMethod="Between")
        grips = pv.Threshold(registrationName="grips", Input=source, Scalars=["POINTS", "load_set"],
                             LowerThreshold=0.5, UpperThreshold=1e9, ThresholdMethod="Between")
        source = specimen
    display = spheres(pv.Show(source, view), spacing, args.radius_factor)
    if grips is not None:
        grip_display = spheres(pv.Show(grips, view), spacing, args.radius_factor)
        pv.ColorBy(grip_display, None)
        grip_display.AmbientColor = grip_display.DiffuseColor = [0.6, 0.6, 0.6]

    # Colour: the magnitude or one component, the range of the shown time.
    if components == 1 and args.component != "magnitude":
        fail(f"{field} is a scalar: it has no component {args.component}")
    if components == 3 and args.component in TENSOR_COMPONENTS:
        fail(f"{field} is a vector: give --component x, y, z or magnitude")
    if components == 9 and args.component in ("x", "y", "z"):
        fail(f"{field} is a tensor: give --component xx, xy, ... zz or magnitude")
    pv.ColorBy(display, ("POINTS", field))
    lut = pv.GetColorTransferFunction(field)
    if components > 1:
        if args.component == "magnitude":
            lut.VectorMode = "Magnitude"
        else:
            lut.VectorMode = "Component"
            lut.VectorComponent = ("xyz" if components == 3 else TENSOR_COMPONENTS).index(args.component)
    display.RescaleTransferFunctionToDataRange(False, True)
    unit = UNITS.get(field, "Pa" if "stress" in field else "")
    words = field.replace("_", " ")
    what = words if components == 1 else f"{words} {args.component}"  # ("|" is not in ParaView's text font)
    display.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(lut, view)
    bar.Title = what + (f" ({unit})" if unit else "")
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]

    # The run state at the shown time, in the corner.
    run_state = ", ".join(text.format(state[k]) for k, text in (("step", "step {:.0f}"), ("time_s", "t = {:.6g} s"),
                                                                  ("stretch", "stretch {:.6g}")) if k in state)
    text = pv.Text(registrationName="run state", Text=f"{os.path.basename(os.path.dirname(xdmf))}: {what}\n{run_state}")
    text_display = pv.Show(text, view)
    text_display.FontSize = 12
    text_display.WindowLocation = "Upper Center"
    text_display.Color = [0.0, 0.0, 0.0]

    # A camera that frames the body: looking down z on a sheet.
    flat = np.ptp(reference[:, 2]) <= 1e-12 * max(np.ptp(reference).max(), 1e-300) if reference.shape[1] > 2 else True
    if flat:
        view.InteractionMode = "2D"
        view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0, 0, 1], [0, 0, 0], [0, 1, 0]
    else:
        view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [1, -1.5, 1], [0, 0, 0], [0, 0, 1]
    pv.ResetCamera(view)
    view.GetActiveCamera().Zoom(0.8)  # room for the text above and the colour bar beside
    pv.Render(view)

    held = int((vtk_to_numpy(pd.GetArray("load_set")) > 0).sum()) if grips is not None else 0
    print(f"{xdmf}: {data.GetNumberOfPoints()} points at t = {time:.6g} s ({run_state}), coloured by {what}, "
          f"spheres of radius {display.GaussianRadius:.4g} m (point spacing {spacing:.4g} m)"
          + (f"; {held} grip points in grey" if grips is not None else ""))
    if args.png:
        pv.SaveScreenshot(args.png, view, ImageResolution=list(args.resolution))
        print(f"wrote {args.png}")
    if args.state:
        pv.SaveState(args.state)
        print(f"wrote {args.state} (paraview --state={args.state})")


if __name__ == "__main__":
    main()
