"""Gallery: two gradient-index lenses, a Luneburg lens and a GRIN rod, in front of a sky.

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 Examples/Python/grin_lenses.py
        [--out grin_lenses.png] [--size 48]

The medium is built procedurally as a vtkImageData with a `RefractiveIndex` point array (the
passes compute grad n from it by central differences):
- left, a Luneburg lens: n(r) = sqrt(2 - (r/R)^2) inside the sphere of radius R, 1 outside. It
  focuses a parallel beam onto the opposite point of its surface;
- right, a GRIN rod along the viewing axis with the parabolic profile n = n0 (1 - A rho^2 / 2)
  (rho the distance from its axis), a quarter of its pitch 2 pi / sqrt(A) long, so it focuses a
  parallel beam onto the centre of its back face.
vtkRefractaImageRenderer traces curved view rays (the ray equation) through it and looks up an
equirectangular sky/ground checkerboard in each ray's bent exit direction. Through both lenses
the world is turned upside down (the sky appears below the horizon); the Luneburg lens fills its
disc with the whole hemisphere behind it, the ring round the rod is its cylinder wall.

Smoke check (the optics of the Luneburg lens): a parallel ray entering at a distance b from the
axis leaves through the focus at the angle asin(b / R) to the axis, on the other side of it (the
lens maps a plane wave to a point and back). A second render with an environment that encodes
the direction (R = u, G = v of the equirectangular map) decodes each pixel's exit direction; the
measured deflection at b/R = 0.3, 0.5, 0.7 must be within 2 degrees of asin(b/R), rays that miss
the lenses must see the undeflected direction, and a ray entering the rod at h0 from its axis
must leave it with x-direction -n0 sin(atan(h0 sqrt(A))) (paraxial, within 0.05).
"""
import argparse
import math

import numpy as np
import refracta
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkCamera

parser = argparse.ArgumentParser()
parser.add_argument("--out", default="grin_lenses.png")
parser.add_argument("--size", type=int, default=48, help="voxels per world unit (the box is 2 x 1 x 1.2)")
args = parser.parse_args()

# --- The medium: a grid over [-1, 1] x [-0.5, 0.5] x [-0.6, 0.6], n at the voxel centres ---
h = 1.0 / (args.size - 1)
dims = [int(round(2.0 / h)) + 1, args.size, int(round(1.2 / h)) + 1]
x = -1.0 + h * np.arange(dims[0])
y = -0.5 + h * np.arange(dims[1])
z = -0.6 + h * np.arange(dims[2])
Z, Y, X = np.meshgrid(z, y, x, indexing="ij")          # VTK's point order: x fastest

R, lune_x = 0.4, -0.5                                   # the Luneburg lens, centred at (-0.5, 0, 0)
r = np.sqrt((X - lune_x) ** 2 + Y ** 2 + Z ** 2) / R
n = np.where(r < 1.0, np.sqrt(2.0 - np.minimum(r, 1.0) ** 2), 1.0)

n0, A, rod_x, a = 1.5, 2.2, 0.5, 0.3                    # the GRIN rod, axis along z at x = 0.5
rod_length = 0.5 * math.pi / math.sqrt(A)               # a quarter pitch: ~1.06
rho2 = (X - rod_x) ** 2 + Y ** 2
in_rod = (rho2 < a * a) & (np.abs(Z) < 0.5 * rod_length)
n = np.where(in_rod, n0 * (1.0 - 0.5 * A * rho2), n)

medium = vtkImageData()
medium.SetDimensions(dims); medium.SetSpacing(h, h, h); medium.SetOrigin(-1.0, -0.5, -0.6)
n_array = numpy_support.numpy_to_vtk(n.ravel().astype(np.float32), deep=True)
n_array.SetName("RefractiveIndex")
medium.GetPointData().AddArray(n_array)


def environment(rgb_of_uv, width=512, height=256):
    """An equirectangular environment (float RGB, linear radiance) from a function of (u, v)."""
    u, v = np.meshgrid((np.arange(width) + 0.5) / width, (np.arange(height) + 0.5) / height)
    image = vtkImageData(); image.SetDimensions(width, height, 1)
    rgb = numpy_support.numpy_to_vtk(rgb_of_uv(u, v).reshape(-1, 3).astype(np.float32), deep=True)
    rgb.SetName("sky"); image.GetPointData().SetScalars(rgb)
    return image


def sky(u, v):
    """A checkerboard, blue above the horizon (v > 0.5), brown below; 24 x 12 squares."""
    odd = ((np.floor(u * 24) + np.floor(v * 12)) % 2)[..., None]
    above = np.array([0.35, 0.55, 0.95]) * (0.45 + 0.55 * odd)
    below = np.array([0.55, 0.38, 0.22]) * (0.35 + 0.65 * odd)
    return np.where((v > 0.5)[..., None], above, below)


width, height = 8 * args.size, 4 * args.size
camera = vtkCamera(); camera.SetPosition(0, 0, 2.6); camera.SetFocalPoint(0, 0, 0)
camera.SetViewAngle(26)                                  # perspective, looking along -z
image = refracta.vtkRefractaImageRenderer()              # curved view rays through the medium
image.SetInputData(medium); image.SetCamera(camera); image.SetImageSize(width, height)
image.SetEnvironmentMap(environment(sky))
writer = vtkPNGWriter(); writer.SetInputConnection(image.GetOutputPort())
writer.SetFileName(args.out); writer.Write()
print("view pass %.2f s, curved rays %d" % (image.GetOutput().GetFieldData().GetArray("ViewPassSeconds").GetValue(0),
                                            image.GetOutput().GetFieldData().GetArray("CurvedRays").GetValue(0)))

# --- Smoke check: an orthographic camera (parallel rays, 2 x 1 world units across the image) and
# an environment that encodes the direction: decode every pixel's exit direction ---
camera.ParallelProjectionOn(); camera.SetParallelScale(0.5)
image.SetEnvironmentMap(environment(lambda u, v: np.stack([u, v, 0 * u], axis=-1)))
image.Update()                                           # only the view pass runs again
hdr = numpy_support.vtk_to_numpy(image.GetOutput().GetPointData().GetArray("HDR")).reshape(height, width, 4)


def exit_direction(i, j):
    """The world direction (x, y, z) whose environment texel pixel (i, j) shows."""
    u, v = hdr[j, i, 0], hdr[j, i, 1]
    lon, lat = 2 * math.pi * (u - 0.5), math.pi * (v - 0.5)   # the inverse of VTK's skybox map
    return math.cos(lat) * math.sin(lon), math.sin(lat), -math.cos(lat) * math.cos(lon)


def pixel_of(xw):                                        # column of world x on the middle row
    return int(round((xw + 1.0) / 2.0 * width - 0.5))


row = height // 2                                        # the middle row: y ~ 0 (half a pixel off)
dx, dy, dz = exit_direction(2, row)
print("ray missing the lenses: exit direction (%.4f, %.4f, %.4f)" % (dx, dy, dz))
assert abs(dx) < 0.01 and abs(dy) < 0.01, "rays that miss the lenses must not be deflected"
for b in (0.3, 0.5, 0.7):                                # Luneburg: deflection asin(b / R)
    i = pixel_of(lune_x + b * R)
    b_pixel = ((i + 0.5) * 2.0 / width - 1.0 - lune_x) / R
    dx, dy, dz = exit_direction(i, row)
    measured = math.degrees(math.atan2(-dx, -dz))       # towards -x: across the axis
    predicted = math.degrees(math.asin(b_pixel))
    print("Luneburg b/R = %.3f: deflection %.1f deg, predicted asin(b/R) = %.1f deg" % (b_pixel, measured, predicted))
    assert abs(measured - predicted) < 2.0, "the Luneburg lens must deflect a ray by asin(b/R)"
for side in (-1, 1):   # GRIN rod, quarter pitch: the ray reaches the axis at the back face with
    i = pixel_of(rod_x + side * 0.5 * a)                 # slope -h0 sqrt(A), then Snell (n0 -> 1)
    h0 = (i + 0.5) * 2.0 / width - 1.0 - rod_x
    slope = h0 * math.sqrt(A)
    predicted = -n0 * slope / math.sqrt(1.0 + slope * slope)
    dx, _, _ = exit_direction(i, row)
    print("GRIN rod, offset %+.3f: exit direction x %+.3f, predicted %+.3f" % (h0, dx, predicted))
    assert abs(dx - predicted) < 0.05, "the quarter-pitch GRIN rod must focus onto its back face"
