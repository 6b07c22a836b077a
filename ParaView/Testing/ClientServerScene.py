"""pvpython client, run by TestParaViewClientServer.py: connects to the pvserver on
localhost:<argv[1]>, loads the plugin on both sides and builds the shared scene there."""
import sys

import numpy as np
from paraview import servermanager
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy

import refracta_pv_testing as rt

simple.Connect("localhost", int(sys.argv[1]))
assert servermanager.ActiveConnection.IsRemote(), "the session must be client/server"
rt.load_plugin(remote=True)
sphere, medium, image = rt.make_scene(simple)
image.UpdatePipeline()                      # runs in pvserver; Fetch brings the image here
picture = servermanager.Fetch(image)
print("plan (server):", picture.GetFieldData().GetAbstractArray("PlanSummary").GetValue(0))
assert rt.matches_baseline(picture, "ParaViewRenderImage"), "the server renders the baseline"

# The colour map and opacity function are proxies on both sides; the server maps with them.
wavelet = simple.Wavelet(WholeExtent=[-4, 4, -4, 4, -4, 4])
tf = simple.RefractaTransferFunctionMedium(Input=wavelet)
tf.Scalars = ["POINTS", "RTData"]
tf.ColorTransferFunction = simple.GetColorTransferFunction("RTData")
opacity = simple.GetOpacityTransferFunction("RTData")
opacity.Points = [40.0, 0.0, 0.5, 0.0, 280.0, 0.7, 0.5, 0.0]
tf.ScalarOpacityFunction = opacity
tf.UpdatePipeline()
extinction = vtk_to_numpy(servermanager.Fetch(tf).GetPointData().GetArray("Extinction"))
assert extinction.shape == (729, 3) and extinction.max() > 0, "the server maps the wavelet"
print("OK client/server")
