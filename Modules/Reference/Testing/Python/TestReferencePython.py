"""vtkReferenceRenderer from Python: an absorbing, emitting slab seen head-on by a parallel camera.

Every pixel sees L = eps / sigma (1 - exp(-tau)) + L_bg exp(-tau); the image mean must lie within
4 reported standard errors of it, and the output must carry the documented arrays.
"""
import math
import sys

import refracta
from vtkmodules.vtkCommonCore import vtkDoubleArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkCamera

medium = vtkImageData()
medium.SetDimensions(4, 4, 4)
medium.SetSpacing(1.0, 1.0, 0.25)
n = 64
sigma, eps, bg = 0.8, 0.3, 0.5
for name, value in (("Extinction", sigma), ("Emission", eps)):
    a = vtkDoubleArray()
    a.SetName(name)
    a.SetNumberOfComponents(3)
    a.SetNumberOfTuples(n)
    for i in range(n):
        a.SetTuple3(i, value, value, value)
    medium.GetPointData().AddArray(a)

camera = vtkCamera()
camera.ParallelProjectionOn()
camera.SetFocalPoint(1.5, 1.5, 0.375)
camera.SetPosition(1.5, 1.5, 10.0)
camera.SetViewUp(0, 1, 0)
camera.SetParallelScale(1.0)

renderer = refracta.vtkReferenceRenderer()
renderer.SetInputData(medium)
renderer.SetCamera(camera)
renderer.SetImageSize(8, 8)
renderer.SetSamplesPerPixel(32)
renderer.SetBackgroundColor(bg, bg, bg)
renderer.SetSeed(1)
renderer.Update()
out = renderer.GetOutput()

hdr = out.GetPointData().GetArray("HDR")
se = out.GetPointData().GetArray("StandardError")
assert out.GetDimensions() == (8, 8, 1), out.GetDimensions()
assert hdr.GetNumberOfComponents() == 4 and se.GetNumberOfComponents() == 3
assert out.GetPointData().GetScalars().GetName() == "RGB"
assert out.GetFieldData().GetArray("SamplesPerPixel").GetValue(0) == 32

tau = sigma * 1.0  # thickness 4 x 0.25
expected = eps / sigma * (1 - math.exp(-tau)) + bg * math.exp(-tau)
mean = sum(hdr.GetComponent(i, 0) for i in range(64)) / 64
err = math.sqrt(sum(se.GetComponent(i, 0) ** 2 for i in range(64))) / 64
print(f"mean {mean:.5f} +- {err:.5f}, analytic {expected:.5f}")
if not err > 0 or abs(mean - expected) > 4 * err:
    sys.exit("reference renderer disagrees with the analytic slab radiance")
