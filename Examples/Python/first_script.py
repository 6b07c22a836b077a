"""README's first script: a glass sphere in fog, lit by a spot light, through the render pipeline.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 Examples/Python/first_script.py
        [--out first.png] [--size 64]

vtkMeshVoxelizer turns the sphere and its materials into a medium; vtkRefractaImageRenderer runs
the render pipeline on it headless (effect plan, photon pass with caustics, multiple scattering,
view rays refracted at the sphere) at the DRAFT quality preset. As a smoke test it checks that the
sphere focuses the spot light: the caustic below the sphere is brighter than the beam beside it.
"""
import argparse

import refracta
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight

parser = argparse.ArgumentParser()
parser.add_argument("--out", default="first.png")
parser.add_argument("--size", type=int, default=64, help="voxels per axis")
args = parser.parse_args()

glass = refracta.vtkMediumMaterial(); glass.SetRefractiveIndex(1.5)
fog = refracta.vtkMediumMaterial(); fog.SetExtinction(0.35, 0.35, 0.35); fog.SetAlbedo(0.9, 0.9, 0.9)
sphere = vtkSphereSource(); sphere.SetRadius(0.42); sphere.SetThetaResolution(64); sphere.SetPhiResolution(64)
medium = refracta.vtkMeshVoxelizer()                 # meshes + materials -> a medium (vtkImageData)
medium.AddInputConnection(sphere.GetOutputPort()); medium.SetMaterial(0, glass)
medium.SetSurroundingMaterial(fog); medium.SetDimensions(args.size, args.size, args.size)
medium.SetBounds(-1, 1, -1, 1, -1, 1)
light = vtkLight(); light.SetPositional(True); light.SetConeAngle(12); light.SetIntensity(60)
light.SetPosition(0, 3, 0); light.SetFocalPoint(0, 0, 0)   # a spot light above the sphere
camera = vtkCamera(); camera.SetPosition(0, 0.55, 3.2); camera.SetFocalPoint(0, -0.1, 0)
image = refracta.vtkRefractaImageRenderer()          # the render pipeline, headless (no OpenGL)
image.SetInputConnection(medium.GetOutputPort()); image.AddLight(light)
image.SetCamera(camera); image.SetImageSize(256, 256)
image.GetPipeline().SetQuality(refracta.vtkEffectPlan.DRAFT)   # a measured quality preset
writer = vtkPNGWriter(); writer.SetInputConnection(image.GetOutputPort())
writer.SetFileName(args.out); writer.Write()
print(image.GetPipeline().GetEffectPlan().GetSummary())

# Smoke check: the focus below the sphere (column 128, rows 30-50 from the bottom) outshines the
# lit fog beside the beam (column 60).
hdr = image.GetOutput().GetPointData().GetArray("HDR")
def luminance(i, j):
    r, g, b, _ = hdr.GetTuple4(i + 256 * j)
    return 0.2126 * r + 0.7152 * g + 0.0722 * b
focus = max(luminance(128, j) for j in range(30, 50))
beside = max(luminance(60, j) for j in range(30, 50))
print("caustic %.4g, fog beside it %.4g" % (focus, beside))
assert focus > 2.0 * beside, "the sphere must focus the spot light below it"
