"""Voxelize a sphere through `import refracta`: volume, n inside, a valid medium."""
import math
import sys

import refracta
from vtkmodules.vtkFiltersSources import vtkSphereSource


def check(condition, message):
    if not condition:
        print("FAIL:", message)
        sys.exit(1)


radius = 0.7
sphere = vtkSphereSource()
sphere.SetRadius(radius)
sphere.SetThetaResolution(120)
sphere.SetPhiResolution(120)

glass = refracta.vtkMediumMaterial()
glass.SetRefractiveIndex(1.5)
glass.SetExtinction(0.1, 0.2, 0.3)

voxelizer = refracta.vtkMeshVoxelizer()
voxelizer.AddInputConnection(sphere.GetOutputPort())
voxelizer.SetMaterial(0, glass)
voxelizer.SetDimensions(48, 48, 48)
voxelizer.SetPadding(0.2)
voxelizer.Update()
medium = voxelizer.GetOutput()

check(medium.GetDimensions() == (48, 48, 48), "dimensions")
occupancy = medium.GetPointData().GetArray("Occupancy")
spacing = medium.GetSpacing()
volume = sum(occupancy.GetValue(i) for i in range(occupancy.GetNumberOfTuples()))
volume *= spacing[0] * spacing[1] * spacing[2]
analytic = 4.0 / 3.0 * math.pi * radius ** 3
print("volume %.6f analytic %.6f relative error %.2e" % (volume, analytic, volume / analytic - 1))
check(abs(volume / analytic - 1) < 0.005, "sphere volume within 0.5%")

n = medium.GetPointData().GetArray("RefractiveIndex")
centre = medium.ComputePointId([24, 24, 24])
check(abs(n.GetValue(centre) - 1.5) < 1e-6, "n inside equals the material's")
check(abs(n.GetValue(0) - 1.0) < 1e-6, "n outside is vacuum's")
validator = refracta.vtkMediumValidator()
check(validator.Validate(medium), "valid medium: " + validator.GetErrorMessage())
for stage in range(refracta.vtkMeshVoxelizer.NUMBER_OF_STAGES):
    print(refracta.vtkMeshVoxelizer.GetStageName(stage), voxelizer.GetStageTime(stage))
print("OK")
