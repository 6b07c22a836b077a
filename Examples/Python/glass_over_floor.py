"""Glass objects over a floor, with caustics: surfaces in the light and view passes.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 Examples/Python/glass_over_floor.py
        [--out glass_over_floor.png] [--size 64] [--width 320]

A glass sphere (n = 1.5) and a water-like cube (n = 1.33, slightly blue-absorbing) are voxelized
into a medium in a thin haze; a checkered floor (vtkPlaneSource) and a red back wall
(vtkCubeSource) are opaque Lambertian surfaces (vtkRefractaSurfaceSet). A spot light from above
shines through the glass: the sphere focuses it into a bright caustic on the floor, the cube's
faces throw a sharp-edged, refracted patch of light and the absorbing cube a tinted shadow. The
view pass shows the floor and the wall bent through the glass. vtkRefractaImageRenderer runs it
all headless at the DRAFT preset.

Smoke check: the floor under the sphere (the caustic) is much brighter than the lit floor beside
it, in the rendered image itself (HDR radiance at the pixels where the camera sees those two
floor points).
"""
import argparse

import refracta
from vtkmodules.vtkFiltersSources import vtkCubeSource, vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight

parser = argparse.ArgumentParser()
parser.add_argument("--out", default="glass_over_floor.png")
parser.add_argument("--size", type=int, default=64, help="voxels per axis")
parser.add_argument("--width", type=int, default=320, help="image width (height 3/4 of it)")
args = parser.parse_args()
width, height = args.width, args.width * 3 // 4

# The medium: glass sphere and water cube in a thin haze, above the floor (y = -0.6).
glass = refracta.vtkMediumMaterial(); glass.SetRefractiveIndex(1.5)
glass.SetExtinction(0.02, 0.02, 0.02)
water = refracta.vtkMediumMaterial(); water.SetRefractiveIndex(1.33)
water.SetExtinction(0.6, 0.25, 0.05)
haze = refracta.vtkMediumMaterial(); haze.SetExtinction(0.08, 0.08, 0.08)
haze.SetAlbedo(0.9, 0.9, 0.9)
sphere = vtkSphereSource(); sphere.SetCenter(-0.35, -0.05, 0.1); sphere.SetRadius(0.32)
sphere.SetThetaResolution(64); sphere.SetPhiResolution(48)
cube = vtkCubeSource(); cube.SetBounds(0.15, 0.65, -0.45, 0.05, -0.35, 0.15)
medium = refracta.vtkMeshVoxelizer()
medium.AddInputConnection(sphere.GetOutputPort()); medium.SetMaterial(0, glass)
medium.AddInputConnection(cube.GetOutputPort()); medium.SetMaterial(1, water)
medium.SetSurroundingMaterial(haze)
medium.SetDimensions(args.size, args.size * 3 // 4, args.size * 3 // 4)
medium.SetBounds(-1, 1, -0.7, 0.9, -0.75, 0.75)  # the floor inside the grid

# The surfaces: a checkered floor and a back wall (model coordinates, no matrices).
floor = vtkPlaneSource(); floor.SetOrigin(-1.6, -0.6, 1.2); floor.SetPoint1(1.6, -0.6, 1.2)
floor.SetPoint2(-1.6, -0.6, -1.2); floor.Update()
checker = refracta.vtkRefractaSurfaceMaterial(); checker.UseCheckerOn()
checker.SetCheckerSquares(8, 6)
checker.SetCheckerColor1(0.85, 0.82, 0.75); checker.SetCheckerColor2(0.35, 0.35, 0.38)
wall = vtkCubeSource(); wall.SetBounds(-1.6, 1.6, -0.6, 1.2, -1.3, -1.2); wall.Update()
red = refracta.vtkRefractaSurfaceMaterial(); red.SetAlbedo(0.7, 0.18, 0.12)
surfaces = refracta.vtkRefractaSurfaceSet()
surfaces.AddSurface(floor.GetOutput(), checker, None)
surfaces.AddSurface(wall.GetOutput(), red, None)

light = vtkLight(); light.SetPositional(True); light.SetConeAngle(25); light.SetIntensity(40)
light.SetPosition(-0.1, 3.0, 0.3); light.SetFocalPoint(-0.1, 0, 0)
camera = vtkCamera(); camera.SetPosition(0.0, 0.9, 3.0); camera.SetFocalPoint(0.0, -0.25, 0.0)
camera.SetViewAngle(38)
image = refracta.vtkRefractaImageRenderer()
image.SetInputConnection(medium.GetOutputPort()); image.AddLight(light)
image.SetSurfaces(surfaces)
image.SetCamera(camera); image.SetImageSize(width, height)
image.SetBackgroundColor(0.02, 0.03, 0.05)
image.SetToneMapping(refracta.vtkRefractaImageRenderer.REINHARD); image.SetExposure(1.5)
image.GetPipeline().SetQuality(refracta.vtkEffectPlan.DRAFT)
writer = vtkPNGWriter(); writer.SetInputConnection(image.GetOutputPort())
writer.SetFileName(args.out); writer.Write()
print(image.GetPipeline().GetEffectPlan().GetSummary())

# Smoke check: HDR luminance where the camera sees the floor under the sphere's focus and the
# lit floor beside it (projected with the camera; the brightest pixel within 2 pixels).
hdr = image.GetOutput().GetPointData().GetArray("HDR")
projection = camera.GetCompositeProjectionTransformMatrix(width / height, -1, 1)


def floor_luminance(x, z):
    p = projection.MultiplyPoint((x, -0.6, z, 1.0))
    i0 = int((p[0] / p[3] + 1) * 0.5 * width)
    j0 = int((p[1] / p[3] + 1) * 0.5 * height)
    best = 0.0
    for j in range(j0 - 2, j0 + 3):
        for i in range(i0 - 2, i0 + 3):
            r, g, b, _ = hdr.GetTuple4(i + width * j)
            best = max(best, 0.2126 * r + 0.7152 * g + 0.0722 * b)
    return best


caustic = max(floor_luminance(-0.35 + dx, 0.1 + dz) for dx in (-0.04, 0, 0.04)
              for dz in (-0.04, 0, 0.04))
beside = floor_luminance(-0.35 - 0.55, 0.1 + 0.35)
print("floor: caustic %.4g, lit floor beside it %.4g (ratio %.1f)"
      % (caustic, beside, caustic / max(beside, 1e-12)))
assert beside > 0, "the floor beside the sphere must be lit"
assert caustic > 4.0 * beside, "the sphere must focus the spot light into a caustic on the floor"
