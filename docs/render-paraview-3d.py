"""Render the last time step of a 3D run's ParaView series with ParaView itself: the deformed
mesh (displacement at scale 1) coloured by the von Mises stress, with edges, and the contact
slave points coloured by state (0 open, 1 stick, 2 slip).

Usage (headless: Xvfb gives ParaView its window):
  xvfb-run -a -s "-screen 0 1280x1024x24" pvpython docs/render-paraview-3d.py RUN.pvd OUT.png
"""

import sys

from paraview.simple import (ColorBy, ExtractBlock, GetActiveViewOrCreate, GetAnimationScene,
                             GetColorTransferFunction, GetScalarBar, OpenDataFile, Render,
                             SaveScreenshot, Show, WarpByVector)

reader = OpenDataFile(sys.argv[1])
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = reader.TimestepValues[-1]
mesh = ExtractBlock(registrationName="mesh", Input=reader, Selectors=["/Root/Block0"])
contact = ExtractBlock(registrationName="contact", Input=reader, Selectors=["/Root/Block1"])
deformed = WarpByVector(Input=mesh, Vectors=["POINTS", "displacement"], ScaleFactor=1.0)
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1000, 700]
view.Background = [1, 1, 1]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
shown = Show(deformed, view)
shown.SetRepresentationType("Surface With Edges")
ColorBy(shown, ("CELLS", "von_mises"))
lut = GetColorTransferFunction("von_mises")
lut.ApplyPreset("Viridis (matplotlib)", True)
shown.SetScalarBarVisibility(view, True)
bar = GetScalarBar(lut, view)
bar.Title, bar.ComponentTitle = "von Mises", ""
bar.TitleColor, bar.LabelColor = [0, 0, 0], [0, 0, 0]
points = Show(contact, view)
points.SetRepresentationType("Points")
points.PointSize = 6
points.RenderPointsAsSpheres = 1
ColorBy(points, ("POINTS", "state"))
view.CameraPosition = [2.8, -3.2, 2.2]
view.CameraFocalPoint = [0.45, 0.45, 0.2]
view.CameraViewUp = [0, 0, 1]
Render(view)
SaveScreenshot(sys.argv[2], view, ImageResolution=[1000, 700])
print("written", sys.argv[2])
