"""vtkPhotonTracer from Python: a pipeline on a homogeneous absorbing, scattering slab lit by a
vtkLight. Straight parallel photons cross exactly L = 0.8, so the escaped fraction is
exp(-sigma_t L) to float precision (tolerance 1%, the issue's), and the energy books close."""
import math
import sys

import refracta
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkLight


def check(condition, message):
    if not condition:
        print("FAIL:", message)
        sys.exit(1)


n = 8
image = vtkImageData()
image.SetDimensions(n, n, n)
image.SetSpacing(0.1, 0.1, 0.1)
sigma = (0.5, 1.0, 2.0)
extinction = vtkFloatArray()
extinction.SetName("Extinction")
extinction.SetNumberOfComponents(3)
albedo = vtkFloatArray()
albedo.SetName("Albedo")
albedo.SetNumberOfComponents(3)
for _ in range(n * n * n):
    extinction.InsertNextTuple3(*sigma)
    albedo.InsertNextTuple3(0.5, 0.5, 0.5)
image.GetPointData().AddArray(extinction)
image.GetPointData().AddArray(albedo)

light = vtkLight()
light.SetPositional(False)
light.SetPosition(0.35, 0.35, -5)
light.SetFocalPoint(0.35, 0.35, 0)
light.SetIntensity(1.5)

tracer = refracta.vtkPhotonTracer()
tracer.SetInputData(image)
tracer.AddLight(light)
tracer.SetNumberOfPhotons(4096)
tracer.Update()
out = tracer.GetOutput()
fd = out.GetFieldData()
check(out.GetPointData().GetArray("Radiance") is not None, "Radiance array")
check(out.GetPointData().GetArray("RadianceDirection") is not None, "RadianceDirection array")
emitted = fd.GetArray("EnergyEmitted").GetTuple3(0)
escaped = fd.GetArray("EnergyEscaped").GetTuple3(0)
for c in range(3):
    t = math.exp(-sigma[c] * 0.8)
    check(abs(escaped[c] / emitted[c] - t) < 0.01 * t,
          "channel %d transmission %g, expected %g" % (c, escaped[c] / emitted[c], t))
    books = sum(fd.GetArray(name).GetTuple3(0)[c] for name in
                ("EnergyAbsorbed", "EnergyEscaped", "EnergyScattered", "EnergyRemaining"))
    check(abs(books - emitted[c]) < 1e-4 * emitted[c], "energy balance channel %d" % c)
check(not tracer.GetUsedCurvedRays(), "constant n: straight rays")
print("OK")
