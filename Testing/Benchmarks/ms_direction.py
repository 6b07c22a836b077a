"""Multiple scattering's direction, per method, against the reference renderer.

A forward-scattering ball (radius 0.35 with a soft edge, optical diameter about 6, albedo 0.99,
g = 0.8; N^3 voxels over [0, 1]^3) under a directional light from behind (its light travels
towards the camera, 34 degrees off the view axis), from the front and from the side, seen by a
32 x 32 camera: the relative RMSE (the reference's variance taken out) and the bias of the render
pipeline's image against vtkReferenceRenderer's (all orders), for the lattice (D3Q6, D3Q18), the
first-collision split (D3Q6, k = 7) and photons carrying every order (2^20), each with S_ms shaded
about its direction (`MultipleScatteringDirection`) and as isotropic (the same lighting volume
without that array). --turn: camera and light turned together by 30 degrees about y and 25 about
x, so that no lattice direction lines up with the view. Documentation/Physics.md, "The direction
of multiple scattering", has the table.

Usage (from the build tree, with the Python modules on PYTHONPATH):
  python3 ms_direction.py [--size 32] [--spp 4096] [--turn] [--lights back,front,side]
                          [--anisotropy 0.8] [--methods d3q6,d3q18,split,photons] [--directed-only]
  python3 ms_direction.py --time-grid 64 [--runs 3] [--anisotropy 0.8]
--anisotropy g sets the ball's g (Physics.md, "The plan's lattice", has the sweep); --time-grid N
times instead a light move of the ball on N^3 voxels (the lattice alone, lit from behind, a 64 x 64
image) with D3Q6 and D3Q18, alternated within each run, and prints the medians and their ratio.
"""
import argparse, math, time
import numpy as np
import refracta
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkRenderingCore import vtkCamera, vtkLight
from vtkmodules.util.numpy_support import vtk_to_numpy, numpy_to_vtk

parser = argparse.ArgumentParser()
parser.add_argument("--size", type=int, default=32)
parser.add_argument("--spp", type=int, default=4096)
parser.add_argument("--turn", action="store_true")
parser.add_argument("--lights", default="back,front,side")
parser.add_argument("--anisotropy", type=float, default=0.8)
parser.add_argument("--methods", default="d3q6,d3q18,split,photons")
parser.add_argument("--directed-only", action="store_true", help="leave out the isotropic columns")
parser.add_argument("--time-grid", type=int, default=0)
parser.add_argument("--runs", type=int, default=3)
args = parser.parse_args()
if args.time_grid:
    args.size = args.time_grid
N, PIXELS, G = args.size, 32, args.anisotropy

def medium():
    m = vtkImageData(); h = 1.0 / N
    m.SetDimensions(N, N, N); m.SetSpacing(h, h, h); m.SetOrigin(0.5 * h, 0.5 * h, 0.5 * h)
    x = (np.arange(N) + 0.5) * h
    Z, Y, X = np.meshgrid(x, x, x, indexing="ij")
    r = np.sqrt((X - .5) ** 2 + (Y - .5) ** 2 + (Z - .5) ** 2)
    s = ((6.0 / 0.7) * np.clip((0.35 - r) / 0.05, 0, 1)).ravel().astype(np.float32)
    for name, v, comps in (("Extinction", s, 3), ("Albedo", np.full_like(s, 0.99), 3),
                           ("Anisotropy", np.full_like(s, G), 1)):
        a = numpy_to_vtk(np.ascontiguousarray(np.repeat(v[:, None], comps, 1) if comps > 1 else v), deep=1)
        a.SetName(name); m.GetPointData().AddArray(a)
    return m

def turn(p):
    if not args.turn:
        return p
    a, b = math.radians(30), math.radians(25)
    x, y, z = p[0] - .5, p[1] - .5, p[2] - .5
    x, z = x * math.cos(a) + z * math.sin(a), -x * math.sin(a) + z * math.cos(a)
    y, z = y * math.cos(b) - z * math.sin(b), y * math.sin(b) + z * math.cos(b)
    return (x + .5, y + .5, z + .5)

def light(kind):
    l = vtkLight(); l.SetLightTypeToSceneLight(); l.PositionalOff(); l.SetIntensity(1.0)
    l.SetFocalPoint(0.5, 0.5, 0.5)
    at = {"back": (0.5 + 3 * math.sin(0.6), 0.5, 0.5 - 3 * math.cos(0.6)),
          "side": (3.5, 0.5, 0.5), "front": (2.0, 2.0, 3.0)}[kind]
    l.SetPosition(*turn(at)); return l

def camera():
    c = vtkCamera(); c.SetPosition(*turn((0.5, 0.5, 3.0))); c.SetFocalPoint(0.5, 0.5, 0.5)
    c.SetViewUp(*[q - .5 for q in turn((0.5, 1.5, 0.5))]); c.SetViewAngle(22); return c

def hdr(image):
    return vtk_to_numpy(image.GetPointData().GetArray("HDR"))[:, :3].astype(np.float64)

def reference(m, kind):
    r = refracta.vtkReferenceRenderer(); r.SetInputData(m); r.SetCamera(camera()); r.AddLight(light(kind))
    r.SetImageSize(PIXELS, PIXELS); r.SetSamplesPerPixel(args.spp); r.SetSeed(3); r.Update()
    o = r.GetOutput()
    return hdr(o), vtk_to_numpy(o.GetPointData().GetArray("StandardError"))[:, :3]

def renderer(m, kind, lighting=None):
    r = refracta.vtkRefractaImageRenderer()
    if lighting is not None:
        r.SetLightingData(lighting)
    r.AddLight(light(kind)); r.SetInputData(m); r.SetCamera(camera()); r.SetImageSize(PIXELS, PIXELS)
    return r

def pipeline(m, kind, method, lattice, orders=0):
    r = renderer(m, kind); p = r.GetPipeline()
    p.SetMultipleScatteringMethod(method); p.SetScatteringOrders(orders)
    p.SetLattice(lattice); p.GetPhotonTracer().SetNumberOfPhotons(1 << 20)
    r.Update()
    if args.directed_only:
        return hdr(r.GetOutput()), None
    isotropic = vtkImageData(); isotropic.DeepCopy(p.GetLighting())
    isotropic.GetPointData().RemoveArray("MultipleScatteringDirection")
    r2 = renderer(m, kind, isotropic); r2.Update()
    return hdr(r.GetOutput()), hdr(r2.GetOutput())

def stats(img, ref, se):
    seen = (se > 1e-6 * ref).any(1)
    d = img[seen] - ref[seen]
    rmse = math.sqrt(max(0, (d ** 2).sum() - (se[seen] ** 2).sum()) / (ref[seen] ** 2).sum())
    bias = img[seen].sum() / ref[seen].sum() - 1
    return f"{100 * rmse:.1f}%, {100 * bias:+.1f}%"

E = refracta.vtkEffectPlan
m = medium()

def time_light_move(lattice):
    """Seconds of a light move (the lattice's solve from the new S1 and the view pass)."""
    r = renderer(m, "back"); p = r.GetPipeline()
    p.SetMultipleScatteringMethod(E.LATTICE_ONLY); p.SetLattice(lattice); r.SetImageSize(64, 64)
    r.Update()
    l = r.GetPipeline().GetLights().GetItemAsObject(0)
    l.SetPosition(0.5 + 3 * math.sin(0.7), 0.5, 0.5 - 3 * math.cos(0.7)); r.Modified()
    t = time.perf_counter(); r.Update()
    return time.perf_counter() - t

if args.time_grid:
    times = {6: [], 18: []}
    for run in range(args.runs):
        for lattice in (6, 18):
            times[lattice].append(time_light_move(lattice))
    med = {k: sorted(v)[len(v) // 2] for k, v in times.items()}
    print(f"{N}^3, g = {G}, light move, medians of {args.runs} (alternated): D3Q6 {med[6]:.2f} s, "
          f"D3Q18 {med[18]:.2f} s, ratio {med[18] / med[6]:.2f}")
    raise SystemExit(0)
every = {"d3q6": ("lattice D3Q6", E.LATTICE_ONLY, 6, 0), "d3q18": ("lattice D3Q18", E.LATTICE_ONLY, 18, 0),
         "split": ("split D3Q6, k = 7", E.FIRST_COLLISION_SPLIT, 6, 7),
         "photons": ("photons, every order", E.PHOTONS_EVERY_ORDER, 6, 0)}
methods = [every[k] for k in args.methods.split(",")]
print(f"g = {G}: lighting | " + " | ".join(n if args.directed_only else f"{n} | {n} isotropic"
                                          for n, *_ in methods))
for kind in args.lights.split(","):
    t = time.time(); ref, se = reference(m, kind)
    noise = math.sqrt((se ** 2).sum() / (ref ** 2).sum())
    cells = []
    for name, method, lattice, orders in methods:
        directed, isotropic = pipeline(m, kind, method, lattice, orders)
        cells += [stats(directed, ref, se)] + ([] if isotropic is None else [stats(isotropic, ref, se)])
    print(f"{kind}{', turned' if args.turn else ''} | " + " | ".join(cells) +
          f"   (reference noise {100 * noise:.1f}%, {time.time() - t:.0f} s)", flush=True)
