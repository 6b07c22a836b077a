"""Ground-truth rendering of a smoothed glass sphere in thin fog with vtkReferenceRenderer.

The medium is built procedurally: a sphere whose refractive index rises smoothly from 1 to 1.5
over a thin shell (rays bend only there), clear inside, in a forward-scattering fog, lit by a spot
light; a checkerboard environment map shows the refraction through the sphere.

Usage: /usr/bin/python3 reference_glass_sphere.py [--smoke] [--size W H] [--spp N] [--out file.png]
Prints the render time and the mean standard error; writes the tone-mapped RGB image as PNG.
"""
import argparse
import math

import refracta
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight

parser = argparse.ArgumentParser()
parser.add_argument("--smoke", action="store_true", help="tiny image, few samples")
parser.add_argument("--size", type=int, nargs=2, default=[160, 120])
parser.add_argument("--spp", type=int, default=32)
parser.add_argument("--out", default="reference_glass_sphere.png")
args = parser.parse_args()
if args.smoke:
    args.size, args.spp = [24, 18], 2

n = 40
spacing = 2.0 / n
medium = vtkImageData()
medium.SetDimensions(n, n, n)
medium.SetSpacing(spacing, spacing, spacing)
medium.SetOrigin(-1 + spacing / 2, -1 + spacing / 2, -1 + spacing / 2)
arrays = {}
for name, comps in (("RefractiveIndex", 1), ("Extinction", 3), ("Albedo", 3), ("Anisotropy", 1)):
    a = vtkDoubleArray()
    a.SetName(name)
    a.SetNumberOfComponents(comps)
    a.SetNumberOfTuples(n ** 3)
    medium.GetPointData().AddArray(a)
    arrays[name] = a
radius, shell = 0.55, 0.12
for k in range(n):
    for j in range(n):
        for i in range(n):
            x, y, z = (-1 + (c + 0.5) * spacing for c in (i, j, k))
            r = math.sqrt(x * x + y * y + z * z)
            t = min(max((radius + shell / 2 - r) / shell, 0.0), 1.0)
            inside = t * t * (3 - 2 * t)  # smoothstep: 1 inside, 0 outside
            idx = i + n * (j + n * k)
            arrays["RefractiveIndex"].SetValue(idx, 1.0 + 0.5 * inside)
            sigma = 0.6 * (1 - inside) + 0.05 * inside
            arrays["Extinction"].SetTuple3(idx, sigma, sigma, sigma)
            arrays["Albedo"].SetTuple3(idx, 0.95, 0.95, 0.95)
            arrays["Anisotropy"].SetValue(idx, 0.6)

env = vtkImageData()
env.SetDimensions(64, 32, 1)
checks = vtkFloatArray()
checks.SetNumberOfComponents(3)
checks.SetNumberOfTuples(64 * 32)
for j in range(32):
    for i in range(64):
        v = 0.8 if (i // 4 + j // 4) % 2 else 0.15
        checks.SetTuple3(i + 64 * j, v, v * 0.9, v * 0.7)
env.GetPointData().SetScalars(checks)

camera = vtkCamera()
camera.SetPosition(0.3, -3.2, 0.6)
camera.SetFocalPoint(0, 0, 0)
camera.SetViewUp(0, 0, 1)
camera.SetViewAngle(38)

spot = vtkLight()
spot.PositionalOn()
spot.SetPosition(-1.6, -0.8, 2.2)
spot.SetFocalPoint(0, 0, 0)
spot.SetConeAngle(30)
spot.SetExponent(1)
spot.SetIntensity(6.0)
spot.SetDiffuseColor(1.0, 0.85, 0.6)

renderer = refracta.vtkReferenceRenderer()
renderer.SetInputData(medium)
renderer.SetCamera(camera)
renderer.AddLight(spot)
renderer.SetEnvironmentMap(env)
renderer.SetEnvironmentUp(0, 0, 1)  # the scene is z-up (vtkRefractaEnvironmentMap convention)
# A spot light needs an explicit radius in the reference renderer (LightRadius 0 is a delta light,
# which its estimator cannot reach): about 1% of the medium's diagonal.
renderer.SetLightRadius(0.035)
renderer.SetImageSize(*args.size)
renderer.SetSamplesPerPixel(args.spp)
renderer.SetSeed(1)
renderer.Update()
out = renderer.GetOutput()
se = out.GetPointData().GetArray("StandardError")
hdr = out.GetPointData().GetArray("HDR")
npx = out.GetNumberOfPoints()
mean = sum(hdr.GetComponent(p, 0) for p in range(npx)) / npx
mean_se = sum(se.GetComponent(p, 0) for p in range(npx)) / npx
seconds = out.GetFieldData().GetArray("RenderSeconds").GetValue(0)
print(f"{args.size[0]}x{args.size[1]} pixels, {args.spp} samples/pixel: {seconds:.2f} s, "
      f"mean radiance {mean:.4f}, mean per-pixel standard error {mean_se:.4f}")
assert npx == args.size[0] * args.size[1] and math.isfinite(mean) and mean > 0
writer = vtkPNGWriter()
writer.SetInputData(out)
writer.SetFileName(args.out)
writer.Write()
