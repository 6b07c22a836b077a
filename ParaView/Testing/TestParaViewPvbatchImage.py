"""pvbatch: Refracta in a batch script, both ways a script can show a medium.

1. Refracta Render Image (the headless pipeline as a filter): a glass sphere with a scattering
   interior, lit from the upper left, rendered 96 x 96 at DRAFT quality with seed 7, is compared
   with Testing/Baselines/ParaViewRenderImage.png by vtkTesting (threshold 15, as the C++
   baseline tests). Its field data carries the effect plan and the stage times.
2. The "Refracta" representation in an ordinary render view (vtkRefractiveVolumeMapper inside
   ParaView's volume representation): the medium, lit by the view's light kit, must darken and
   tint the background behind it (its centre pixel differs from the corner by more than 10 grey
   levels while the corner keeps the background colour).

    pvbatch TestParaViewPvbatchImage.py [--screenshot out.png]   (the documentation picture)
"""
import argparse
import os

import numpy as np
from paraview import servermanager
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

import refracta_pv_testing as rt

parser = argparse.ArgumentParser()
parser.add_argument("--screenshot", default=os.path.join(rt.OUTPUT, "paraview_representation.png"))
args = parser.parse_args()

rt.load_plugin()
sphere, medium, image = rt.make_scene(simple)

# --- 1. Refracta Render Image against its baseline ---
image.UpdatePipeline()
picture = servermanager.Fetch(image)
fd = picture.GetFieldData()
print("plan:", fd.GetAbstractArray("PlanSummary").GetValue(0))
print("stages: plan %.3f s, lighting %.3f s, view %.3f s" % tuple(
    fd.GetArray(n).GetValue(0) for n in ("PlanSeconds", "LightingSeconds", "ViewSeconds")))
hdr = vtk_to_numpy(picture.GetPointData().GetArray("HDR")).reshape(96, 96, 4)
assert np.isfinite(hdr).all() and (hdr >= 0).all(), "finite, non-negative radiance"
assert hdr[48, 48, 3] > 0.5 and hdr[2, 2, 3] == 0.0, "the sphere is opaque-ish, the corner empty"
assert rt.matches_baseline(picture, "ParaViewRenderImage"), "matches Testing/Baselines"

# --- 2. The Refracta representation in a render view ---
rt.stop_without_render_window("Refracta Render Image against its baseline")
view = simple.CreateRenderView()
view.ViewSize = [240, 240]
view.OrientationAxesVisibility = 0
view.Background = [0.32, 0.34, 0.43]
if hasattr(view, "UseColorPaletteForBackground"):
    view.UseColorPaletteForBackground = 0
display = simple.Show(medium, view)
display.SetRepresentationType("Refracta")
display.RefractaQuality = "Draft"
display.RefractaMultipleScattering = 0
display.RefractaExposure = 1.0
view.CameraPosition = [0, 0, 4]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
view.CameraViewAngle = 30
simple.Render(view)
simple.SaveScreenshot(args.screenshot, view, ImageResolution=[240, 240])
reader = vtkPNGReader()
reader.SetFileName(args.screenshot)
reader.Update()
shot = reader.GetOutput()
w, h, _ = shot.GetDimensions()
pixels = vtk_to_numpy(shot.GetPointData().GetScalars()).reshape(h, w, -1)[..., :3].astype(float)
centre, corner = pixels[h // 2, w // 2], pixels[4, 4]
print("representation: centre", centre, "corner", corner)
assert np.abs(corner - np.array([0.32, 0.34, 0.43]) * 255).max() < 3, "background outside"
assert np.abs(centre - corner).max() > 10, "the medium must change what is behind it"
print("OK")
