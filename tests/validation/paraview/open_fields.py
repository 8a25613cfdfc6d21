"""Opens a bapd run's fields.xdmf in ParaView as a user would, with the reader that
ParaView picks by default (OpenDataFile: Xdmf3ReaderS in 5.11) and with the legacy
"Xdmf Reader" the README names, and checks what a user would see: every point, a cell
per point (without cells the default Surface and Points views are blank), the point
arrays with their components, the run state (time_s, step, stretch) as field data,
every output time, the points drawn at the geometry asked for, and a rendered damage
picture in which the points are drawn (at least a pixel for every other point).

    xvfb-run -a pvpython open_fields.py RUN_DIR N_POINTS N_TIMES OUT_DIR
        [--last-step S] [--ranks R] [--geometry current|reference]
Exits 1 with a line per problem."""
import argparse
import os
import sys

from paraview import servermanager
from paraview import simple as pv
from vtkmodules.util.numpy_support import vtk_to_numpy

p = argparse.ArgumentParser()
p.add_argument("run")
p.add_argument("n_points", type=int)
p.add_argument("n_times", type=int)
p.add_argument("out")
p.add_argument("--last-step", type=int, help="the step of the last output time")
p.add_argument("--ranks", type=int, default=0, help="the run's rank count (the rank array spans 0 .. R-1)")
p.add_argument("--geometry", choices=["current", "reference"], default="current")
args = p.parse_args()
n_points = args.n_points
xdmf = os.path.join(args.run, "fields.xdmf")
# name -> components, as ParaView shows them (vectors 3, tensors 9)
ARRAYS = {"natural_id": 1, "rank": 1, "volume": 1, "damage": 1, "max_bond_stretch": 1, "thickness_stretch": 1,
          "strain_energy_density": 1, "displacement": 3, "velocity": 3, "force_density": 3,
          "nominal_stress": 9, "cauchy_stress": 9, "deformation_gradient": 9}
ARRAYS["position" if args.geometry == "reference" else "reference_position"] = 3
RUN_STATE = ["time_s", "step", "stretch"]
problems = []


def point_array_info(reader):
    return {reader.PointData.GetArray(k).GetName(): reader.PointData.GetArray(k) for k in range(len(reader.PointData))}


def check_data(reader_name, reader, time):
    """Arrays, field data and point coordinates of the fetched output at `time`."""
    data = servermanager.Fetch(reader)
    if data.IsA("vtkMultiBlockDataSet") or data.IsA("vtkCompositeDataSet"):
        problems.append(f"{reader_name}: a composite data set, expected one point cloud")
        return
    fd = data.GetFieldData()
    state = {}
    for name in RUN_STATE:
        a = fd.GetAbstractArray(name)
        if a is None or a.GetNumberOfTuples() != 1:
            problems.append(f"{reader_name}: no field data '{name}' with one value")
        else:
            state[name] = a.GetVariantValue(0).ToDouble()
    if "time_s" in state and abs(state["time_s"] - time) > 1e-12 * max(1.0, abs(time)):
        problems.append(f"{reader_name}: field data time_s {state['time_s']} at the time step {time}")
    if args.last_step is not None and "step" in state and state["step"] != args.last_step:
        problems.append(f"{reader_name}: field data step {state['step']} at the last time, expected {args.last_step}")
    if "stretch" in state and not state["stretch"] > 1.0:
        problems.append(f"{reader_name}: field data stretch {state['stretch']} at the last time: the sheet is pulled")
    pd = data.GetPointData()
    points = vtk_to_numpy(data.GetPoints().GetData())
    ref = pd.GetArray("reference_position") if args.geometry == "current" else None
    if args.geometry == "current":
        u = pd.GetArray("displacement")
        if ref is not None and u is not None:
            expected = vtk_to_numpy(ref) + vtk_to_numpy(u)
            if abs(points - expected).max() > 1e-12 * abs(expected).max():
                problems.append(f"{reader_name}: the points are not at reference_position + displacement")
    else:
        y = pd.GetArray("position")
        u = pd.GetArray("displacement")
        if y is not None and u is not None:
            if abs(points + vtk_to_numpy(u) - vtk_to_numpy(y)).max() > 1e-12 * abs(vtk_to_numpy(y)).max():
                problems.append(f"{reader_name}: -output_fields_geometry reference, but the points are not at position - displacement")
            if not abs(vtk_to_numpy(u)).max() > 0:
                problems.append(f"{reader_name}: no displacement at the last time")
    ids = pd.GetArray("natural_id")
    if ids is not None and sorted(vtk_to_numpy(ids).tolist()) != list(range(n_points)):
        problems.append(f"{reader_name}: natural_id is not 0 .. {n_points - 1}")
    rank = pd.GetArray("rank")
    if rank is not None and args.ranks and sorted(set(vtk_to_numpy(rank).tolist())) != list(range(args.ranks)):
        problems.append(f"{reader_name}: rank takes {sorted(set(vtk_to_numpy(rank).tolist()))}, expected 0 .. {args.ranks - 1}")
    damage = pd.GetArray("damage")
    if damage is not None and not vtk_to_numpy(damage).max() > 0:
        problems.append(f"{reader_name}: no damage at the last time (the test scene's crack has run)")
    stress = pd.GetArray("cauchy_stress")
    if stress is not None and not abs(vtk_to_numpy(stress)).max() > 0:
        problems.append(f"{reader_name}: the Cauchy stress is zero everywhere at the last time")
    return state


def drawn_pixels(png):
    from vtkmodules.vtkIOImage import vtkPNGReader

    img = vtkPNGReader()
    img.SetFileName(png)
    img.Update()
    rgb = vtk_to_numpy(img.GetOutput().GetPointData().GetScalars())[:, :3]
    return int((rgb < 250).any(axis=1).sum())


def check(reader_name, reader):
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) if hasattr(reader, "TimestepValues") else []
    if len(times) != args.n_times:
        problems.append(f"{reader_name}: {len(times)} time steps, expected {args.n_times}")
    time = times[-1] if times else 0.0
    reader.UpdatePipeline(time)
    info = reader.GetDataInformation()
    points, cells = info.GetNumberOfPoints(), info.GetNumberOfCells()
    if points != n_points:
        problems.append(f"{reader_name}: {points} points, expected {n_points}")
    if cells != n_points:
        problems.append(f"{reader_name}: {cells} cells, expected one per point ({n_points}): the default views draw nothing")
    arrays = point_array_info(reader)
    for name, components in ARRAYS.items():
        if name not in arrays:
            problems.append(f"{reader_name}: no point array '{name}' (has {sorted(arrays)})")
        elif arrays[name].GetNumberOfComponents() != components:
            problems.append(f"{reader_name}: point array '{name}' has {arrays[name].GetNumberOfComponents()} components, expected {components}")
    field = [reader.FieldData.GetArray(k).GetName() for k in range(len(reader.FieldData))]
    for name in RUN_STATE:
        if name not in field:
            problems.append(f"{reader_name}: no field data array '{name}' (has {field})")
    state = check_data(reader_name, reader, time)
    # Render damage in the default representation and count the pixels that differ
    # from the background: the points must be visible.
    view = pv.CreateRenderView()
    view.ViewSize = [400, 400]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    display = pv.Show(reader, view)
    if "damage" in arrays:
        pv.ColorBy(display, ("POINTS", "damage"))
    view.ViewTime = time
    pv.ResetCamera(view)
    png = os.path.join(args.out, f"damage_{reader_name}_{args.geometry}.png")
    pv.SaveScreenshot(png, view, ImageResolution=[400, 400])
    pv.Delete(view)
    try:
        drawn = drawn_pixels(png)
    except Exception as e:  # noqa: BLE001
        problems.append(f"{reader_name}: could not read back {png}: {e}")
        return
    print(f"{reader_name} ({reader.GetXMLName()}): {points} points, {cells} cells, {len(times)} times, "
          f"field data {state}, point arrays {sorted(arrays)}; {drawn} pixels drawn -> {png}")
    # Every point covers at least a pixel of the 400 x 400 picture (the default point
    # size); half of them leaves room for points that overlap on screen.
    if drawn < n_points // 2:
        problems.append(f"{reader_name}: only {drawn} pixels of the rendered picture show points, fewer than half the {n_points} points")


check("default", pv.OpenDataFile(xdmf))
check("XdmfReader", pv.XDMFReader(FileNames=[xdmf]))
for p in problems:
    print("FAIL", p)
sys.exit(1 if problems else 0)
