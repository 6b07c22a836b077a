"""vtkLatticeBoltzmannLighting from Python: a photon pass (vtkPhotonTracer) feeds the
Lattice-Boltzmann pass; with mirror faces nothing escapes the lattice, so in the steady state all
of the injected S1 is absorbed: sum S1 = sum S_ms (1 - a) / a (tolerance 1e-3)."""
import sys

import refracta
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkLight


def check(condition, message):
    if not condition:
        print("FAIL:", message)
        sys.exit(1)


n = 12
albedo = 0.8
image = vtkImageData()
image.SetDimensions(n, n, n)
image.SetSpacing(0.1, 0.1, 0.1)
for name, value in (("Extinction", 5.0), ("Albedo", albedo)):
    array = vtkFloatArray()
    array.SetName(name)
    array.SetNumberOfComponents(3)
    array.SetNumberOfTuples(image.GetNumberOfPoints())
    array.Fill(value)
    image.GetPointData().AddArray(array)

light = vtkLight()
light.SetPositional(False)
light.SetPosition(-10, 0.5, 0.5)
light.SetFocalPoint(0, 0.5, 0.5)

tracer = refracta.vtkPhotonTracer()
tracer.SetInputData(image)
tracer.AddLight(light)
tracer.SetNumberOfPhotons(4096)

lbl = refracta.vtkLatticeBoltzmannLighting()
lbl.SetInputData(image)
lbl.SetLightingConnection(tracer.GetOutputPort())
lbl.SetBoundary(1)
lbl.SetTolerance(1e-7)
lbl.SetMaximumIterations(20000)
lbl.Update()
out = lbl.GetOutput()
check(out.GetNumberOfPoints() == n * n * n, "output grid")
ms = out.GetPointData().GetArray("MultipleScattering")
s1 = out.GetPointData().GetArray("Radiance")
check(ms is not None and s1 is not None, "arrays")
check(out.GetFieldData().GetArray("LatticeBoltzmannConverged").GetValue(0) == 1, "converged")
for c in range(3):
    injected = sum(s1.GetComponent(t, c) for t in range(out.GetNumberOfPoints()))
    absorbed = sum(ms.GetComponent(t, c) for t in range(out.GetNumberOfPoints())) * (1 - albedo) / albedo
    print("channel", c, "injected", injected, "absorbed", absorbed)
    check(injected > 0, "light arrived")
    check(abs(absorbed - injected) < 1e-3 * injected, "energy balance")
print("OK")
