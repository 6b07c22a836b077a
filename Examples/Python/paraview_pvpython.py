"""ParaView's pvpython: a ParaView source rendered as a lit, scattering medium by Refracta.

    PYTHONPATH=build/lib/python3.11/dist-packages pvpython Examples/Python/paraview_pvpython.py
        [--out pvpython.png] [--extent 10]

There is no ParaView plugin with Refracta proxies yet (no Refracta filter in the Filters menu, no
representation in a render view); this is the scripting route that works today. pvpython
(ParaView 5.11) runs on the same VTK 9.2 that Refracta is built against, so `import refracta`
works with the build tree's package on PYTHONPATH and Refracta's filters take the data that
ParaView's pipeline produces:

1. `paraview.simple.Wavelet()` makes ParaView's wavelet source (the RTData field, 37..277,
   largest at the centre) on the server side of the session;
2. `servermanager.Fetch()` brings its output to the client as a plain vtkImageData;
3. refracta.vtkTransferFunctionMedium maps RTData through an ordinary vtkVolumeProperty (scalar
   opacity per voxel -> extinction, colour -> albedo) to a medium;
4. refracta.vtkRefractaImageRenderer lights it with a directional light from the left (photon
   pass and multiple scattering, DRAFT preset) and renders it headless to a PNG.

No ParaView render view or window is created, so it runs without a display (`env -u DISPLAY`).
The smoke check asserts that the lit medium shows against the black background (the centre
pixel is opaque and much brighter than a corner) and that it is lit from the left (the half of
the wavelet facing the light is brighter than the half facing away).
"""
import argparse

from paraview.simple import Wavelet
from paraview import servermanager

import refracta
from vtkmodules.vtkCommonDataModel import vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkCamera, vtkColorTransferFunction, vtkLight, vtkVolumeProperty
from vtkmodules.util import numpy_support

parser = argparse.ArgumentParser()
parser.add_argument("--out", default="pvpython.png")
parser.add_argument("--extent", type=int, default=10, help="wavelet extent -E..E per axis")
args = parser.parse_args()
E = args.extent

# --- ParaView: a source, fetched to the client ---
wavelet = Wavelet(WholeExtent=[-E, E, -E, E, -E, E])
wavelet.UpdatePipeline()
data = servermanager.Fetch(wavelet)                     # a vtkImageData with point array RTData
data.GetPointData().SetActiveScalars("RTData")
low, high = data.GetPointData().GetScalars().GetRange()
print("ParaView wavelet: %d x %d x %d points, RTData %.1f..%.1f"
      % (data.GetDimensions() + (low, high)))

# --- Refracta: transfer functions -> medium -> headless render ---
opacity = vtkPiecewiseFunction()                        # opacity of a slab one voxel thick
opacity.AddPoint(low, 0.0); opacity.AddPoint(150.0, 0.0); opacity.AddPoint(210.0, 0.2)
opacity.AddPoint(high, 0.6)
colour = vtkColorTransferFunction()                     # read as the albedo (scattered fraction)
colour.AddRGBPoint(low, 0.2, 0.3, 0.9); colour.AddRGBPoint(190.0, 0.9, 0.9, 0.9)
colour.AddRGBPoint(high, 0.95, 0.6, 0.2)
prop = vtkVolumeProperty(); prop.SetScalarOpacity(opacity); prop.SetColor(colour)
prop.SetScalarOpacityUnitDistance(data.GetSpacing()[0])
medium = refracta.vtkTransferFunctionMedium()
medium.SetInputData(data); medium.SetVolumeProperty(prop); medium.SetAnisotropy(0.3)

light = vtkLight(); light.SetPositional(False)          # directional, from the left and above
light.SetPosition(-1, 0.4, 0.2); light.SetFocalPoint(0, 0, 0); light.SetIntensity(1.0)
camera = vtkCamera(); camera.SetPosition(0, 0, 6 * E); camera.SetFocalPoint(0, 0, 0)
camera.SetViewAngle(30)

size = 256
image = refracta.vtkRefractaImageRenderer()
image.SetInputConnection(medium.GetOutputPort()); image.AddLight(light)
image.SetCamera(camera); image.SetImageSize(size, size); image.SetBackgroundColor(0.0, 0.0, 0.0)
image.SetToneMapping(refracta.vtkRefractaImageRenderer.REINHARD); image.SetExposure(20.0)
image.GetPipeline().SetQuality(refracta.vtkEffectPlan.DRAFT)
writer = vtkPNGWriter(); writer.SetInputConnection(image.GetOutputPort())
writer.SetFileName(args.out); writer.Write()
print(image.GetPipeline().GetEffectPlan().GetSummary())

# --- Smoke check ---
hdr = numpy_support.vtk_to_numpy(image.GetOutput().GetPointData().GetArray("HDR")).reshape(size, size, 4)
luminance = hdr[..., :3] @ [0.2126, 0.7152, 0.0722]
c = size // 2
centre = luminance[c - 2:c + 2, c - 2:c + 2].mean()
corner = luminance[:8, :8].mean()
alpha = hdr[c, c, 3]
print("centre radiance %.4g (alpha %.3f), corner %.4g" % (centre, alpha, corner))
assert alpha > 0.5 and centre > 10.0 * corner + 1e-6, "the lit medium must show against the background"
on_medium = hdr[..., 3] > 0.2
left = luminance[:, :c][on_medium[:, :c]].mean()        # the half facing the light
right = luminance[:, c:][on_medium[:, c:]].mean()
print("mean radiance, half facing the light %.4g, half facing away %.4g (ratio %.2f)"
      % (left, right, left / right))
assert left > 1.3 * right, "the half facing the light must be brighter"
