"""import refracta works with Debian's VTK Python, and wrapped classes round-trip parameters."""
import sys

import refracta
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonCore import vtkFloatArray


def check(condition, message):
    if not condition:
        print("FAIL:", message)
        sys.exit(1)


material = refracta.vtkMediumMaterial()
material.SetRefractiveIndex(1.5)
material.SetExtinction(0.5, 1.0, 2.0)
material.SetAlbedo(0.9, 0.8, 0.7)
material.SetAnisotropy(0.3)
check(material.GetRefractiveIndex() == 1.5, "refractive index round trip")
check(material.GetExtinction() == (0.5, 1.0, 2.0), "extinction round trip")
check(abs(material.GetAnisotropy() - 0.3) < 1e-12, "anisotropy round trip")
material.SetAlbedo(2.0, 0.5, 0.5)
check(material.GetAlbedo()[0] == 1.0, "albedo clamped to 1")
check(refracta.vtkRefractaMedium.ExtinctionName() == "Extinction", "array names")

image = vtkImageData()
image.SetDimensions(2, 2, 2)
n = vtkFloatArray()
n.SetName("RefractiveIndex")
n.SetNumberOfTuples(8)
n.Fill(0.5)
image.GetPointData().AddArray(n)
validator = refracta.vtkMediumValidator()
check(not validator.Validate(image), "validator rejects n < 1")
check("RefractiveIndex" in validator.GetErrorMessage(), "message names the array")
n.Fill(1.33)
check(validator.Validate(image), "validator accepts water")

context = refracta.vtkOpenCLContext.GetDefault()
check(context.Initialize(), "OpenCL context initializes")
check(context.BuildProgram("refracta_atomics.cl, selftest.cl", ""), "kernels build from Python")
print("device:", context.GetDeviceName())
print("classes:", sorted(c for c in dir(refracta) if c.startswith("vtk")))
