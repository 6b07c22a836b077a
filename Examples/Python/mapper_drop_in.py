"""vtkRefractiveVolumeMapper where a VTK scene had vtkGPUVolumeRayCastMapper.

    PYTHONPATH=build/lib/python3.11/dist-packages xvfb-run -a /usr/bin/python3 \
        Examples/Python/mapper_drop_in.py [--out mapper.png]

An ordinary VTK volume scene (VTK's wavelet, colour and opacity transfer functions, the
renderer's default headlight) with the mapper line changed: the scalar volume is mapped to a
medium through the volume property, lit by the headlight (read in VTK light units) and exposed
automatically. As a smoke test it checks that the volume shows against the black background.
"""
import argparse
import sys

import refracta
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkImagingCore import vtkRTAnalyticSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkColorTransferFunction, vtkRenderer, vtkRenderWindow,
                                         vtkVolume, vtkWindowToImageFilter)

parser = argparse.ArgumentParser()
parser.add_argument("--out", default="mapper.png")
args = parser.parse_args()
if not refracta.vtkRefractaRenderWindowCheck.CanOpen():      # an X11 VTK would abort instead
    sys.exit("no render window: " + refracta.vtkRefractaRenderWindowCheck.GetReason())

wavelet = vtkRTAnalyticSource()                      # any scalar vtkImageData (extent -10..10)
opacity = vtkPiecewiseFunction(); opacity.AddPoint(37, 0.0); opacity.AddPoint(277, 0.3)
colour = vtkColorTransferFunction(); colour.AddRGBPoint(37, 0.2, 0.3, 0.9); colour.AddRGBPoint(277, 0.9, 0.4, 0.1)
volume = vtkVolume(); volume.GetProperty().SetScalarOpacity(opacity); volume.GetProperty().SetColor(colour)
mapper = refracta.vtkRefractiveVolumeMapper()        # instead of vtkGPUVolumeRayCastMapper
mapper.SetInputConnection(wavelet.GetOutputPort()); volume.SetMapper(mapper)
renderer = vtkRenderer(); renderer.AddVolume(volume); renderer.ResetCamera()   # the default headlight
window = vtkRenderWindow(); window.SetOffScreenRendering(1); window.SetSize(300, 300)
window.AddRenderer(renderer); window.Render()
grab = vtkWindowToImageFilter(); grab.SetInput(window); grab.Update()
writer = vtkPNGWriter(); writer.SetInputConnection(grab.GetOutputPort())
writer.SetFileName(args.out); writer.Write()
print(mapper.GetPipeline().GetEffectPlan().GetSummary(), "| exposure", mapper.GetLastExposure())

rgb = grab.GetOutput().GetPointData().GetScalars()
centre = sum(rgb.GetTuple3(150 + 300 * 150)) / 3.0
corner = sum(rgb.GetTuple3(5 + 300 * 5)) / 3.0
print("centre %.1f, corner %.1f (0..255)" % (centre, corner))
assert centre > 40 and corner < 5, "the lit wavelet shows, the background stays black"
