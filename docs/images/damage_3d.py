"""Renders the damage field of a 3D bapd run (its last output time) in ParaView, as a
user would open it: fields.xdmf, the points in their current positions, coloured by
damage (0 blue .. 1 red), seen from the front (x right, y up) and tilted, so that the
crack through the thickness shows.

    xvfb-run -a pvpython docs/images/damage_3d.py RUN_DIR OUT.png
(docs/images/notched_block_3d_damage.png: examples/notched_block_3d.yaml, docs/validation_3d.md 7.3)"""
import sys

from paraview import simple as pv

run, png = sys.argv[1], sys.argv[2]
reader = pv.OpenDataFile(f"{run}/fields.xdmf")
times = reader.TimestepValues
view = pv.CreateRenderView()
view.ViewSize = [1000, 600]
view.Background = [1, 1, 1]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
view.ViewTime = times[-1] if hasattr(times, "__len__") and len(times) else 0.0
display = pv.Show(reader, view)
display.SetRepresentationType("Points")
display.PointSize = 6
display.RenderPointsAsSpheres = 1
pv.ColorBy(display, ("POINTS", "damage"))
lut = pv.GetColorTransferFunction("damage")
lut.ApplyPreset("Jet", True)
lut.RescaleTransferFunction(0.0, 1.0)
display.SetScalarBarVisibility(view, True)
bar = pv.GetScalarBar(lut, view)
bar.Title = "damage"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0, 0, 0]
view.CameraPosition = [0.015, -0.02, 0.09]
view.CameraFocalPoint = [0.015, 0.005, 0.002]
view.CameraViewUp = [0, 1, 0]
pv.ResetCamera(view)
view.CameraParallelProjection = 0
pv.SaveScreenshot(png, view, ImageResolution=[1000, 600])
print(f"wrote {png}")
