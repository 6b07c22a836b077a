"""pvpython: writes Data/RefractaScene.pvsm, the state file TestParaViewStateFile.py loads: the
shared scene (sphere -> Refracta Mesh Voxelizer -> Refracta Render Image), a Refracta Lighting
filter on the medium, and a render view showing the medium with the Refracta representation.

    pvpython MakeStateFile.py ParaView/Testing/Data/RefractaScene.pvsm
"""
import sys

from paraview import simple

import refracta_pv_testing as rt

rt.load_plugin()
sphere, medium, image = rt.make_scene(simple)
lighting = simple.RefractaLighting(Input=medium)
lighting.Lights = rt.LIGHT
lighting.Quality = "Draft"
lighting.NumberOfPhotons = 20000
lighting.MultipleScattering = 0
for proxy, name in ((sphere, "Sphere"), (medium, "Medium"), (image, "Image"),
                    (lighting, "Lighting")):
    simple.RenameSource(name, proxy)
view = simple.CreateRenderView()
view.ViewSize = [160, 160]
display = simple.Show(medium, view)
display.SetRepresentationType("Refracta")
display.RefractaQuality = "Draft"
display.RefractaMultipleScattering = 0
view.CameraPosition = [0, 0, 4]
view.CameraFocalPoint = [0, 0, 0]
view.CameraViewUp = [0, 1, 0]
simple.SaveState(sys.argv[1])
print("wrote", sys.argv[1])
