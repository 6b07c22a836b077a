"""Render through `import refracta`: a homogeneous emitting, absorbing cube seen head-on by a
parallel camera must give L = eps / sigma (1 - exp(-sigma l)) + exp(-sigma l) L_bg per pixel
(l = the box depth), the transfer-function mapping must be usable from Python, and a bad input
must fail with a message instead of an image."""
import math
import sys

import refracta
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkCommand
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkRenderingCore import vtkCamera, vtkColorTransferFunction, vtkVolumeProperty


def check(condition, message):
    if not condition:
        print("FAIL:", message)
        sys.exit(1)


def constant(image, name, values):
    array = vtkFloatArray()
    array.SetName(name)
    array.SetNumberOfComponents(len(values))
    array.SetNumberOfTuples(image.GetNumberOfPoints())
    for c, v in enumerate(values):
        array.FillComponent(c, v)
    image.GetPointData().AddArray(array)
    return array


medium = vtkImageData()
medium.SetDimensions(10, 10, 10)
medium.SetSpacing(0.1, 0.1, 0.1)
sigma = (1.0, 2.0, 4.0)
eps = (0.5, 0.5, 0.5)
background = (0.2, 0.1, 0.0)
constant(medium, "Extinction", sigma)
constant(medium, "Emission", eps)

camera = vtkCamera()
camera.ParallelProjectionOn()
camera.SetParallelScale(0.3)
camera.SetFocalPoint(0.45, 0.45, 0.45)
camera.SetPosition(0.45, 0.45, 5.0)

renderer = refracta.vtkRefractaImageRenderer()
renderer.SetInputData(medium)
renderer.SetCamera(camera)
renderer.SetImageSize(16, 16)
renderer.SetBackgroundColor(*background)
renderer.Update()
out = renderer.GetOutput()
hdr = out.GetPointData().GetArray("HDR")
check(hdr is not None and hdr.GetNumberOfComponents() == 4, "HDR array (RGBA)")
check(out.GetPointData().GetScalars().GetName() == "RGB", "RGB are the active scalars")
depth = 1.0  # 10 voxels of 0.1
for pixel in (0, 17, 136, 255):
    for c in range(3):
        t = math.exp(-sigma[c] * depth)
        expected = eps[c] / sigma[c] * (1 - t) + t * background[c]
        got = hdr.GetComponent(pixel, c)
        check(abs(got - expected) < 1e-5 + 1e-5 * expected,
              "pixel %d channel %d: %g, expected %g" % (pixel, c, got, expected))

# Transfer functions -> medium, from Python.
scalars = vtkImageData()
scalars.SetDimensions(4, 4, 4)
scalars.GetPointData().SetScalars(constant(scalars, "density", (3.0,)))
opacity = vtkPiecewiseFunction()
opacity.AddPoint(0, 0)
opacity.AddPoint(3, 0.5)
colour = vtkColorTransferFunction()
colour.AddRGBPoint(0, 1, 1, 1)
prop = vtkVolumeProperty()
prop.SetScalarOpacity(opacity)
prop.SetColor(colour)
prop.SetScalarOpacityUnitDistance(1.0)
mapping = refracta.vtkTransferFunctionMedium()
mapping.SetInputData(scalars)
mapping.SetVolumeProperty(prop)
mapping.Update()
ext = mapping.GetOutput().GetPointData().GetArray("Extinction").GetComponent(0, 0)
check(abs(ext - math.log(2.0)) < 1e-6, "opacity 0.5 per unit distance -> sigma = ln 2, got %g" % ext)

# Bad input: an image without any medium array is rejected with a message.
errors = []
renderer.AddObserver(vtkCommand.ErrorEvent, lambda obj, event: errors.append(event))
renderer.GetViewPass().AddObserver(vtkCommand.ErrorEvent, lambda obj, event: errors.append(event))
renderer.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda obj, event: errors.append(event))
renderer.SetInputData(scalars)
renderer.Update()
check(len(errors) > 0, "a scalar image is not a medium: error expected")
check(renderer.GetOutput().GetNumberOfPoints() == 0, "no image after an error")
print("rendered from Python on", refracta.vtkOpenCLContext.GetDefault().GetDeviceName())
