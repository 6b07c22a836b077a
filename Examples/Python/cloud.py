"""Gallery: a heterogeneous cloud under the sun, single scattering beside multiple scattering.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 Examples/Python/cloud.py
        [--out cloud.png] [--size 48]

The cloud is built procedurally: a cumulus shape (a union of soft spheres) eroded by fractal
Perlin noise (VTK's vtkPerlinNoise sampled by vtkSampleFunction, three octaves), written directly
as the medium's `Extinction` (up to 12 per unit: optically thick), `Albedo` 0.99 and
`Anisotropy` 0.5 (forward scattering) arrays. A directional sun lights it from the upper left,
against a blue sky (a background colour: seen, but it does not illuminate the cloud). It is
rendered twice through the same vtkRefractaImageRenderer: with single scattering only
(vtkRefractaRenderPipeline::SetMultipleScattering(False): the photon pass alone) and with
multiple scattering (the Lattice-Boltzmann pass added). The PNG shows them side by side, left
single, right multiple, at the same exposure (Reinhard tone mapping).

Smoke check: light scattered more than once only adds energy, so with multiple scattering the
cloud is brighter (mean radiance over the cloud > 1.2x), and it lifts the sunlit side and the side
facing away from the sun about equally: the path-traced reference (vtkReferenceRenderer, 256
samples per pixel, at 48) gains x5.74 on the sunlit side and x5.81 on the other, as forward
scattering carries the light through the cloud. The two gains must agree within 15% (shading the
multiply scattered light as isotropic, as before its direction was kept, gave x5.38 and x6.87).
"""
import argparse

import numpy as np
import refracta
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPerlinNoise
from vtkmodules.vtkImagingHybrid import vtkSampleFunction
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight

parser = argparse.ArgumentParser()
parser.add_argument("--out", default="cloud.png")
parser.add_argument("--size", type=int, default=48, help="voxels along y and z (x has twice as many)")
args = parser.parse_args()

# --- The density: soft spheres (a cumulus) minus fractal noise, on [-1, 1] x [-0.5, 0.5]^2 ---
N = args.size
dims = (2 * N, N, N)
h = 1.0 / (N - 1)
origin = (-0.5 * h * (dims[0] - 1), -0.5, -0.5)


def sample(function):
    """The implicit function on the grid, as a numpy array indexed [k, j, i]."""
    sampler = vtkSampleFunction(); sampler.SetImplicitFunction(function)
    sampler.SetSampleDimensions(dims)
    sampler.SetModelBounds(origin[0], -origin[0], -0.5, 0.5, -0.5, 0.5)
    sampler.ComputeNormalsOff(); sampler.Update()
    values = sampler.GetOutput().GetPointData().GetScalars()
    return numpy_support.vtk_to_numpy(values).reshape(dims[2], dims[1], dims[0])


noise = np.zeros((dims[2], dims[1], dims[0]))
for octave in range(3):                                 # fractal noise: 3 octaves, amplitude halving
    perlin = vtkPerlinNoise(); perlin.SetFrequency([3.0 * 2 ** octave] * 3)
    perlin.SetPhase(0.37 * octave, 0.11, 0.73); perlin.SetAmplitude(0.5 ** octave)
    noise += sample(perlin)
z, y, x = np.meshgrid(origin[2] + h * np.arange(dims[2]), origin[1] + h * np.arange(dims[1]),
                      origin[0] + h * np.arange(dims[0]), indexing="ij")
shape = np.full(noise.shape, -10.0)
for cx, cy, cz, radius in ((-0.45, -0.12, 0.0, 0.3), (0.0, 0.0, 0.0, 0.4), (0.42, -0.1, 0.05, 0.32),
                           (0.15, 0.18, -0.05, 0.25), (-0.2, 0.12, 0.08, 0.22)):
    d = np.sqrt((x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2) / radius
    shape = np.maximum(shape, 1.0 - d)                  # > 0 inside the union of the spheres
shape = np.where(y > -0.3, shape, shape - 3.0 * (-0.3 - y))   # a flat-ish base
density = np.clip(4.0 * (shape + 0.12 * noise), 0.0, 1.0)

sigma_t = 12.0 * density                                # extinction per world unit
medium = vtkImageData()
medium.SetDimensions(dims); medium.SetSpacing(h, h, h); medium.SetOrigin(origin)
for name, values in (("Extinction", np.repeat(sigma_t.ravel()[:, None], 3, axis=1)),
                     ("Albedo", np.full((sigma_t.size, 3), 0.99)),
                     ("Anisotropy", np.full(sigma_t.size, 0.5))):
    array = numpy_support.numpy_to_vtk(values.astype(np.float32), deep=True); array.SetName(name)
    medium.GetPointData().AddArray(array)

# --- The sun, the sky, the camera ---
sun = vtkLight(); sun.SetPositional(False); sun.SetPosition(-1.0, 0.8, 0.4); sun.SetFocalPoint(0, 0, 0)
sun.SetDiffuseColor(1.0, 0.95, 0.85); sun.SetIntensity(1.0)      # irradiance 1 (warm white)
camera = vtkCamera(); camera.SetPosition(0, -0.1, 2.3); camera.SetFocalPoint(0, 0, 0); camera.SetViewAngle(30)
width, height = 4 * N, 2 * N
image = refracta.vtkRefractaImageRenderer()
image.SetInputData(medium); image.AddLight(sun); image.SetCamera(camera); image.SetImageSize(width, height)
image.SetBackgroundColor(0.015, 0.03, 0.07)             # sky radiance, seen between the clouds
pipeline = image.GetPipeline()
pipeline.SetQuality(refracta.vtkEffectPlan.DRAFT)
pipeline.GetEffectPlan().SetEffectMode(refracta.vtkEffectPlan.MULTIPLE_SCATTERING, refracta.vtkEffectPlan.FORCE_ON)

renders = {}
for multiple in (False, True):
    pipeline.SetMultipleScattering(multiple)
    image.Update()
    hdr = numpy_support.vtk_to_numpy(image.GetOutput().GetPointData().GetArray("HDR"))
    renders[multiple] = hdr.reshape(height, width, 4).copy()
    print("multiple scattering %-5s: %s" % (multiple, pipeline.GetEffectPlan().GetSummary()))

# --- The PNG: single | multiple, same exposure, Reinhard, sRGB ---
exposure = 12.0
panels = []
for multiple in (False, True):
    v = exposure * renders[multiple][..., :3]
    v = v / (1.0 + v)
    srgb = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)
    panels.append(np.round(255 * np.clip(srgb, 0, 1)).astype(np.uint8))
both = np.concatenate([panels[0], np.full((height, 2, 3), 255, np.uint8), panels[1]], axis=1)
picture = vtkImageData(); picture.SetDimensions(both.shape[1], both.shape[0], 1)
rgb = numpy_support.numpy_to_vtk(both.reshape(-1, 3), deep=True); rgb.SetName("RGB")
picture.GetPointData().SetScalars(rgb)
writer = vtkPNGWriter(); writer.SetInputData(picture); writer.SetFileName(args.out); writer.Write()

# --- Smoke check ---
weights = np.array([0.2126, 0.7152, 0.0722])
single, multi = renders[False][..., :3] @ weights, renders[True][..., :3] @ weights
cloud = renders[True][..., 3] > 0.9                     # pixels whose rays the cloud nearly stops
yy, xx = np.mgrid[0:height, 0:width] - 0.5 * (np.array([height, width])[:, None, None] - 1)
towards_sun = (-xx + 0.8 * yy) / np.hypot(1.0, 0.8)     # image-plane distance towards the sun
lit, shadowed = cloud & (towards_sun > 0.1 * width), cloud & (towards_sun < -0.1 * width)
total_gain = multi[cloud].mean() / single[cloud].mean()
lit_gain = multi[lit].mean() / single[lit].mean()
shadow_gain = multi[shadowed].mean() / single[shadowed].mean()
print("cloud pixels %d: mean radiance single %.4g, multiple %.4g (x%.2f)" %
      (cloud.sum(), single[cloud].mean(), multi[cloud].mean(), total_gain))
print("gain on the sunlit side x%.2f, on the side away from the sun x%.2f" % (lit_gain, shadow_gain))
assert cloud.sum() > 0.1 * width * height, "the cloud must cover a good part of the image"
assert total_gain > 1.2, "multiple scattering must add light"
assert abs(shadow_gain / lit_gain - 1) < 0.15, \
    "multiple scattering must lift both sides about equally (forward scattering carries it across)"
