"""pvpython, run by TestParaViewBadInput.py: three kinds of bad input, each updated twice (the
second update after a change that re-executes the filter) and shown in a render view (where one
can be made)."""
from paraview import simple

import refracta_pv_testing as rt

rt.load_plugin()
view = None
if rt.render_window_available("the messages are checked"):
    view = simple.CreateRenderView()


def show(source):
    if view:
        simple.Show(source, view)
        simple.Render(view)


# A non-closed mesh: a plane is a single open quad.
open_mesh = simple.RefractaMeshVoxelizer(Input=simple.Plane())
open_mesh.UpdatePipeline()
show(open_mesh)

# A medium without medium arrays: the wavelet carries RTData only.
no_arrays = simple.RefractaRenderImage(Input=simple.Wavelet())
no_arrays.ImageSize = [16, 16]
no_arrays.UpdatePipeline()
no_arrays.ImageSize = [24, 24]               # re-executes: the pipeline says it once only
no_arrays.UpdatePipeline()

# The wrong input type: a polygonal sphere where a medium (vtkImageData) is needed.
wrong_type = simple.RefractaLighting(Input=simple.Sphere())
wrong_type.UpdatePipeline()
show(wrong_type)
print("END OF SCENE")
