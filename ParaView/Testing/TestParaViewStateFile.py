"""pvbatch: a ParaView state file with Refracta proxies (Data/RefractaScene.pvsm, written by
MakeStateFile.py) loads and renders.

- After LoadState, the sources Medium (Refracta Mesh Voxelizer), Lighting (Refracta Lighting) and
  Image (Refracta Render Image) exist with the properties the state recorded (Materials, Lights,
  ImageSize, Seed).
- Image renders the same picture as the scene built by script: it matches
  Testing/Baselines/ParaViewRenderImage.png (vtkTesting, threshold 15).
- Lighting yields a lighting volume (Radiance) and the effect plan in its field data.
- The state's render view shows the medium with the Refracta representation: the centre of the
  screenshot differs from its corner (the background) by more than 10 grey levels.
"""
import os

import numpy as np
from paraview import servermanager
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

import refracta_pv_testing as rt

rt.load_plugin()
state = os.path.join(os.path.dirname(os.path.abspath(__file__)), "Data", "RefractaScene.pvsm")
simple.LoadState(state)
medium, lighting, image = (simple.FindSource(n) for n in ("Medium", "Lighting", "Image"))
assert medium and lighting and image, "the state's Refracta proxies must load"
assert list(medium.Materials) == rt.GLASS and list(image.Lights) == rt.LIGHT
assert list(image.ImageSize) == [96, 96] and image.Seed == 7

image.UpdatePipeline()
picture = servermanager.Fetch(image)
print("plan:", picture.GetFieldData().GetAbstractArray("PlanSummary").GetValue(0))
assert rt.matches_baseline(picture, "ParaViewRenderImage"), "the state renders the baseline"

lighting.UpdatePipeline()
lit = servermanager.Fetch(lighting)
assert lit.GetPointData().GetArray("Radiance") is not None
assert lit.GetFieldData().GetAbstractArray("PlanSummary") is not None

rt.stop_without_render_window("loading the state and its Refracta images")
view = simple.GetActiveViewOrCreate("RenderView")
shot_file = os.path.join(rt.OUTPUT, "paraview_state.png")
simple.SaveScreenshot(shot_file, view, ImageResolution=[160, 160])
reader = vtkPNGReader()
reader.SetFileName(shot_file)
reader.Update()
w, h, _ = reader.GetOutput().GetDimensions()
pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars()).reshape(h, w, -1)[..., :3]
centre, corner = pixels[h // 2, w // 2].astype(float), pixels[3, 3].astype(float)
print("state view: centre", centre, "corner", corner)
assert np.abs(centre - corner).max() > 10, "the Refracta representation must show the medium"
print("OK")
