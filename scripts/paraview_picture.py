"""The ParaView picture of doc/reference.md: fields.xdmf of the SWE example at its last time, the
full model's water surface (Warp By Scalar of chi_fom) beside the pointwise difference of a
hyper-reduced model to it, as a ParaView user would set them up.

usage: xvfb-run -a pvbatch scripts/paraview_picture.py DIR/fields.xdmf DIFFERENCE_FIELD OUT.png
"""
import sys

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, GetScalarBar, Show, Text,
                             WarpByScalar, XDMFReader, AssignViewToLayout, CreateLayout, SaveScreenshot)

xdmf, difference, png = sys.argv[1:4]
reader = XDMFReader(FileNames=[xdmf])
reader.UpdatePipelineInformation()
t = reader.TimestepValues[-1]
layout = CreateLayout("fields")


def view_of(source, field, title, camera):
    view = CreateView("RenderView")
    view.ViewTime = t
    view.OrientationAxesVisibility = 0
    AssignViewToLayout(view=view, layout=layout, hint=0)
    display = Show(source, view)
    ColorBy(display, ("POINTS", field))
    display.RescaleTransferFunctionToDataRange(True, False)
    bar = GetScalarBar(GetColorTransferFunction(field), view)
    bar.Title, bar.ComponentTitle, bar.Visibility = "", "", 1
    bar.LabelFontSize, bar.ScalarBarLength = 9, 0.5
    bar.WindowLocation = "Lower Right Corner"
    label = Show(Text(Text=f"{title}, t = {t:g}"), view)
    label.WindowLocation, label.FontSize = "Upper Center", 9
    view.CameraPosition, view.CameraViewUp = camera
    view.ResetCamera()
    return view


surface = WarpByScalar(Input=reader, Scalars=["POINTS", "chi_fom"], ScaleFactor=3.0)
view_of(surface, "chi_fom", "chi_fom (Warp By Scalar)", ([6, -9, 9], [0, 0, 1]))
view = view_of(reader, difference, difference, ([0, 0, 10], [0, 1, 0]))
lut = GetColorTransferFunction(difference)
lut.ApplyPreset("Cool to Warm", True)
low, high = reader.PointData[difference].GetRange()
bound = max(abs(low), abs(high))
lut.RescaleTransferFunction(-bound, bound)  # symmetric: white where the model is right
layout.SetSize(1000, 420)
SaveScreenshot(png, layout, ImageResolution=[1000, 420])
