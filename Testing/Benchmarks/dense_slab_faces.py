"""Single scattering at a dense face, per method, against the reference renderer.

A dense slab (the lower half of a 32^3 box over [0, 1]^3, albedo 0.8) under a directional light
from above, single scattering only, seen from above: the image mean of the render pipeline over
vtkReferenceRenderer's (64 samples per pixel, about +-1.6%) for each voxel optical depth, with
the light rays' box means at sharp voxels (vtkLightRaySingleScattering::SharpVoxelBoxMeans) on
and off, the interpolation, and unsmoothed photons (2^18). Documentation/Physics.md, "Single
scattering without noise", has the table.

Usage (from the build tree, with the Python modules on PYTHONPATH):
  python3 dense_slab_faces.py [optical depth per voxel ...]   (default 0.1 0.32 0.52 0.97 9.7)
"""
import math, sys
import refracta
from vtkmodules.vtkCommonCore import vtkFloatArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight

N, SIZE = 32, 32
def medium(sigma):
    m = vtkImageData(); h = 1.0 / N
    m.SetDimensions(N, N, N); m.SetSpacing(h, h, h); m.SetOrigin(0.5 * h, 0.5 * h, 0.5 * h)
    e = vtkFloatArray(); e.SetName("Extinction"); e.SetNumberOfComponents(3)
    a = vtkFloatArray(); a.SetName("Albedo"); a.SetNumberOfComponents(3)
    for k in range(N):
        for j in range(N):
            s = sigma if (j + 0.5) * h < 0.5 else 0.0
            for i in range(N):
                e.InsertNextTuple3(s, s, s); a.InsertNextTuple3(0.8, 0.8, 0.8)
    m.GetPointData().AddArray(e); m.GetPointData().AddArray(a)
    return m
def light():
    l = vtkLight(); l.SetLightTypeToSceneLight(); l.PositionalOff()
    l.SetPosition(0.8, 3.0, 0.9); l.SetFocalPoint(0.5, 0.5, 0.5); l.SetIntensity(1.0)
    return l
def camera():
    c = vtkCamera(); c.SetPosition(0.5, 2.0, 2.2); c.SetFocalPoint(0.5, 0.45, 0.5)
    c.SetViewUp(0, 1, 0); c.SetViewAngle(30); return c
def mean(img):
    a = img.GetPointData().GetArray("HDR")
    n = a.GetNumberOfTuples()
    return sum(a.GetComponent(i, 0) for i in range(n)) / n
def reference(m, spp):
    r = refracta.vtkReferenceRenderer(); r.SetInputData(m); r.SetCamera(camera()); r.AddLight(light())
    r.SetMaximumScatteringDepth(1); r.SetImageSize(SIZE, SIZE); r.SetSamplesPerPixel(spp); r.SetSeed(3)
    r.Update(); return mean(r.GetOutput())
def pipeline(m, method, box=True, smoothing=False):
    r = refracta.vtkRefractaImageRenderer(); p = r.GetPipeline()
    p.SetMultipleScattering(False); p.SetSingleScatteringMethod(method)
    p.GetLightRays().SetSharpVoxelBoxMeans(box)
    p.GetPhotonTracer().SetNumberOfPhotons(1 << 18); p.GetPhotonTracer().SetSmoothing(smoothing)
    r.AddLight(light()); r.SetInputData(m); r.SetCamera(camera()); r.SetImageSize(SIZE, SIZE)
    r.Update()
    a = r.GetOutput().GetPointData().GetArray("HDR")
    if a is None:
        a = r.GetOutput().GetPointData().GetScalars()
    n = a.GetNumberOfTuples()
    return sum(a.GetComponent(i, 0) for i in range(n)) / n
taus = [float(t) for t in sys.argv[1:]] or [0.1, 0.32, 0.52, 0.97, 9.7]
E = refracta.vtkEffectPlan
print("tau  reference  rays(box)  rays(centres)  interp(box)  photons(unsmoothed)")
for t in taus:
    m = medium(t * N)
    ref = reference(m, 64)
    print(f"{t:5.2f} {ref:.5f} {pipeline(m, E.LIGHT_RAYS)/ref:.3f} {pipeline(m, E.LIGHT_RAYS, False)/ref:.3f} "
          f"{pipeline(m, E.INTERPOLATED)/ref:.3f} {pipeline(m, E.PHOTONS)/ref:.3f}", flush=True)
