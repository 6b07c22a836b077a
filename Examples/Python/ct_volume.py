"""Gallery: a CT-like scalar volume through transfer functions, lit by two lights (the scientific path).

    PYTHONPATH=build/lib/python3.11/dist-packages /usr/bin/python3 Examples/Python/ct_volume.py
        [--out ct_volume.png] [--size 48]

A procedural phantom in Hounsfield-like units (-1000 air, 40 soft tissue, 900 bone, 2500 a dense
inclusion such as a calcification or a metal bead): a sphere of tissue of radius 80 mm inside a
bone shell 8 mm thick, open towards the camera (a trepanned skull, so to speak), with a 30 mm
inclusion off centre. vtkTransferFunctionMedium maps it
through an ordinary vtkVolumeProperty (scalar opacity per voxel -> extinction, colour -> albedo)
to a medium; vtkRefractaImageRenderer lights it with a warm key light from the left and a
weak cool fill light from the right (photon pass for single scattering, the Lattice-Boltzmann
pass for multiple scattering, DRAFT preset) and renders it headless, with Reinhard tone mapping.

Smoke check: (1) the inclusion is denser, so the ray through it is more opaque than a ray through
tissue beside it that crosses the same shell: the HDR alpha (A = 1 - mean transmittance) through
the inclusion exceeds the alpha beside it; (2) the half of the phantom facing the key light is
brighter than the half facing away from it (by more than 1.5x).
"""
import argparse

import numpy as np
import refracta
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkPiecewiseFunction
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import vtkCamera, vtkColorTransferFunction, vtkLight, vtkVolumeProperty

parser = argparse.ArgumentParser()
parser.add_argument("--out", default="ct_volume.png")
parser.add_argument("--size", type=int, default=48, help="voxels per axis")
args = parser.parse_args()

# --- The phantom: a scalar vtkImageData in mm, values in HU ---
N, extent_mm = args.size, 200.0
h = extent_mm / (N - 1)
c = -0.5 * extent_mm + h * np.arange(N)
Z, Y, X = np.meshgrid(c, c, c, indexing="ij")          # VTK's point order: x fastest
r = np.sqrt(X ** 2 + Y ** 2 + Z ** 2)
hu = np.full(r.shape, -1000.0)                          # air
hu[(r < 88.0) & (Z < 45.0)] = 900.0                     # bone shell, 80..88 mm, open towards +z
hu[r < 80.0] = 40.0                                     # soft tissue
inclusion = (-25.0, 15.0, 10.0)                         # a dense bead, radius 15 mm
hu[np.sqrt((X - inclusion[0]) ** 2 + (Y - inclusion[1]) ** 2 + (Z - inclusion[2]) ** 2) < 15.0] = 2500.0
ct = vtkImageData()
ct.SetDimensions(N, N, N); ct.SetSpacing(h, h, h); ct.SetOrigin(-0.5 * extent_mm, -0.5 * extent_mm, -0.5 * extent_mm)
scalars = numpy_support.numpy_to_vtk(hu.ravel().astype(np.float32), deep=True); scalars.SetName("HU")
ct.GetPointData().SetScalars(scalars)

# --- Transfer functions, as for any VTK volume rendering ---
opacity = vtkPiecewiseFunction()                        # opacity of a slab one voxel thick
opacity.AddPoint(-1000, 0.0); opacity.AddPoint(-200, 0.0); opacity.AddPoint(40, 0.02)
opacity.AddPoint(300, 0.04); opacity.AddPoint(900, 0.35); opacity.AddPoint(2500, 0.7)
colour = vtkColorTransferFunction()                     # read as the albedo (scattered fraction)
colour.AddRGBPoint(-1000, 0.0, 0.0, 0.0); colour.AddRGBPoint(40, 0.85, 0.45, 0.35)   # tissue: pink
colour.AddRGBPoint(900, 0.95, 0.93, 0.85)                                           # bone: ivory
colour.AddRGBPoint(2500, 0.9, 0.75, 0.25)                                           # bead: gold
prop = vtkVolumeProperty(); prop.SetScalarOpacity(opacity); prop.SetColor(colour)
prop.SetScalarOpacityUnitDistance(h)
medium = refracta.vtkTransferFunctionMedium()
medium.SetInputData(ct); medium.SetVolumeProperty(prop); medium.SetAnisotropy(0.3)

# --- Two directional lights (irradiance per unit area) and the camera ---
key = vtkLight(); key.SetPositional(False); key.SetPosition(-1, 0.6, 0.1); key.SetFocalPoint(0, 0, 0)
key.SetDiffuseColor(1.0, 0.9, 0.75); key.SetIntensity(1.0)        # warm, from the left
fill = vtkLight(); fill.SetPositional(False); fill.SetPosition(1, -0.2, 0.3); fill.SetFocalPoint(0, 0, 0)
fill.SetDiffuseColor(0.6, 0.75, 1.0); fill.SetIntensity(0.1)     # cool, weak, from the right
camera = vtkCamera(); camera.SetPosition(0, 0, 600); camera.SetFocalPoint(0, 0, 0); camera.SetViewAngle(22)

width = height = 4 * N
image = refracta.vtkRefractaImageRenderer()
image.SetInputConnection(medium.GetOutputPort()); image.AddLight(key); image.AddLight(fill)
image.SetCamera(camera); image.SetImageSize(width, height); image.SetBackgroundColor(0.0, 0.0, 0.0)
image.SetToneMapping(refracta.vtkRefractaImageRenderer.REINHARD); image.SetExposure(12.0)
image.GetPipeline().SetQuality(refracta.vtkEffectPlan.DRAFT)
writer = vtkPNGWriter(); writer.SetInputConnection(image.GetOutputPort())
writer.SetFileName(args.out); writer.Write()
print(image.GetPipeline().GetEffectPlan().GetSummary())

# --- Smoke check ---
hdr = numpy_support.vtk_to_numpy(image.GetOutput().GetPointData().GetArray("HDR")).reshape(height, width, 4)


def pixel_of(point):                                    # project a world point (mm) to a pixel
    camera_z = 600.0 - point[2]
    scale = 0.5 * height / (camera_z * np.tan(np.radians(11.0)))
    return int(round(point[0] * scale + 0.5 * width - 0.5)), int(round(point[1] * scale + 0.5 * height - 0.5))


i, j = pixel_of(inclusion)
i_beside, j_beside = pixel_of((-inclusion[0], inclusion[1], inclusion[2]))   # mirrored in x: tissue only
alpha_bead, alpha_tissue = hdr[j, i, 3], hdr[j_beside, i_beside, 3]
print("alpha through the inclusion %.3f, through tissue beside it %.3f" % (alpha_bead, alpha_tissue))
assert alpha_bead > alpha_tissue + 0.05, "the dense inclusion must be more opaque than tissue"

luminance = hdr[..., :3] @ np.array([0.2126, 0.7152, 0.0722])
yy, xx = np.mgrid[0:height, 0:width] - 0.5 * (height - 1)
towards_key = (-xx + 0.6 * yy) / np.hypot(1.0, 0.6)   # image-plane distance towards the key light
on_phantom = hdr[..., 3] > 0.5
lit = luminance[on_phantom & (towards_key > 0.15 * width)].mean()     # the half facing the key
shade = luminance[on_phantom & (towards_key < -0.15 * width)].mean()  # the half facing away
print("mean radiance, side facing the key light %.4g, side facing away %.4g (ratio %.2f)" % (lit, shade, lit / shade))
assert lit > 1.5 * shade, "the side facing the key light must be brighter"
