"""pvpython: the plugin loads, every Refracta proxy is created, and the proxies give what the
Refracta classes give when called directly.

- Every filter proxy (RefractaMeshVoxelizer, RefractaTransferFunctionMedium, RefractaLighting,
  RefractaRenderImage) is created and updated, and the "Refracta" representation type is offered
  for image data.
- The voxelizer proxy on a sphere gives the same medium as refracta.vtkMeshVoxelizer with the same
  mesh, material and grid: every array equal bit for bit (numpy array_equal on the raw floats),
  and the same grid.
- The transfer-function proxy on ParaView's wavelet gives the same medium as
  refracta.vtkTransferFunctionMedium with a vtkVolumeProperty holding the same functions, bit for
  bit; on a cell array (the wavelet through Point Data to Cell Data) too, on the grid of the
  cells' centres, announced before the filter runs.
- The lighting and render-image outputs carry the effect plan's summary and the stage times in
  their field data (what ParaView's Information panel shows).
"""
import numpy as np

import refracta
from paraview import servermanager
from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import vtkVolumeProperty

import refracta_pv_testing as rt

rt.load_plugin()
for name in ("RefractaMeshVoxelizer", "RefractaTransferFunctionMedium", "RefractaLighting",
             "RefractaRenderImage"):
    assert hasattr(simple, name), "the plugin must define the %s proxy" % name


def arrays(image):
    pd = image.GetPointData()
    return {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)) for i in range(pd.GetNumberOfArrays())}


def assert_same_image(a, b, what):
    assert a.GetDimensions() == b.GetDimensions(), what + ": dimensions differ"
    assert a.GetOrigin() == b.GetOrigin() and a.GetSpacing() == b.GetSpacing(), what + ": grid differs"
    aa, bb = arrays(a), arrays(b)
    assert sorted(aa) == sorted(bb), "%s: arrays %s vs %s" % (what, sorted(aa), sorted(bb))
    for name in aa:
        assert aa[name].dtype == bb[name].dtype, "%s: %s dtype differs" % (what, name)
        assert np.array_equal(aa[name], bb[name]), "%s: %s differs (max |d| %g)" % (
            what, name, np.abs(aa[name].astype(float) - bb[name]).max())
    print("%s: %d arrays, %d points, bitwise equal" % (what, len(aa), a.GetNumberOfPoints()))


# --- Voxelizer proxy vs vtkMeshVoxelizer ---
sphere, medium, image = rt.make_scene(simple, dims=24)
medium.UpdatePipeline()
proxy_medium = servermanager.Fetch(medium)
mesh = servermanager.Fetch(sphere)
direct = refracta.vtkMeshVoxelizer()
direct.AddInputData(mesh)
material = refracta.vtkMediumMaterial()
row = rt.GLASS
material.SetRefractiveIndex(row[0]); material.SetExtinction(*row[1:4]); material.SetAlbedo(*row[4:7])
material.SetAnisotropy(row[7]); material.SetEmission(*row[8:11])
direct.SetMaterial(0, material)
direct.SetDimensions(24, 24, 24)
direct.SetPadding(0.15)
direct.SetSmoothingWindow(5)
direct.Update()
assert proxy_medium.GetNumberOfPoints() == 24 ** 3
assert_same_image(proxy_medium, direct.GetOutput(), "RefractaMeshVoxelizer vs vtkMeshVoxelizer")
assert refracta.vtkMediumValidator().Validate(proxy_medium), "the proxy's medium must validate"

# --- Transfer-function proxy vs vtkTransferFunctionMedium ---
wavelet = simple.Wavelet(WholeExtent=[-6, 6, -6, 6, -6, 6])
colour = simple.GetColorTransferFunction("RTData")
colour.RGBPoints = [40.0, 0.2, 0.3, 0.9, 160.0, 0.9, 0.9, 0.9, 280.0, 0.95, 0.6, 0.2]
colour.Discretize = 0
opacity = simple.GetOpacityTransferFunction("RTData")
opacity.Points = [40.0, 0.0, 0.5, 0.0, 150.0, 0.1, 0.5, 0.0, 280.0, 0.7, 0.5, 0.0]
tf = simple.RefractaTransferFunctionMedium(Input=wavelet)
# Scalars left unset: made before the wavelet ran, the proxy's array name is empty, which means
# the input's active point scalars (RTData).
tf.ColorTransferFunction = colour
tf.ScalarOpacityFunction = opacity
tf.ScalarOpacityUnitDistance = 1.0
tf.Anisotropy = 0.4
tf.EmissionScale = 0.5
tf.UpdatePipeline()
proxy_tf = servermanager.Fetch(tf)
data = servermanager.Fetch(wavelet)
data.GetPointData().SetActiveScalars("RTData")
prop = vtkVolumeProperty()
prop.SetColor(colour.GetClientSideObject())      # the same function objects (built-in session)
prop.SetScalarOpacity(opacity.GetClientSideObject())
prop.SetScalarOpacityUnitDistance(1.0)
direct_tf = refracta.vtkTransferFunctionMedium()
direct_tf.SetInputData(data)
direct_tf.SetVolumeProperty(prop)
direct_tf.SetAnisotropy(0.4)
direct_tf.SetEmissionScale(0.5)
direct_tf.Update()
assert_same_image(proxy_tf, direct_tf.GetOutput(),
                  "RefractaTransferFunctionMedium vs vtkTransferFunctionMedium")

# A cell array: the medium lies on the cells' centres (12^3 for the 13^3 wavelet), announced
# before it runs, and equals vtkTransferFunctionMedium's on the same cells.
cell_wavelet = simple.PointDatatoCellData(Input=wavelet)
cell_tf = simple.RefractaTransferFunctionMedium(Input=cell_wavelet)
cell_tf.Scalars = ["CELLS", "RTData"]
cell_tf.ColorTransferFunction = colour
cell_tf.ScalarOpacityFunction = opacity
cell_tf.ScalarOpacityUnitDistance = 1.0
cell_tf.UpdatePipeline()
assert list(cell_tf.GetDataInformation().GetExtent()) == [-6, 5, -6, 5, -6, 5], \
    cell_tf.GetDataInformation().GetExtent()
proxy_cells = servermanager.Fetch(cell_tf)
cell_data = servermanager.Fetch(cell_wavelet)
direct_cells = refracta.vtkTransferFunctionMedium()
direct_cells.SetInputData(cell_data)
direct_cells.SetInputArrayToProcess(0, 0, 0, 1, "RTData")  # FIELD_ASSOCIATION_CELLS
direct_cells.SetVolumeProperty(prop)
direct_cells.SetAnisotropy(0.0)
direct_cells.SetEmissionScale(0.0)
direct_cells.Update()
assert direct_cells.GetOutput().GetDimensions() == (12, 12, 12)
assert_same_image(proxy_cells, direct_cells.GetOutput(),
                  "RefractaTransferFunctionMedium on cell data vs vtkTransferFunctionMedium")

# --- Lighting and render image: outputs and their field data ---
lighting = simple.RefractaLighting(Input=medium)
lighting.Lights = rt.LIGHT
lighting.Quality = "Draft"
lighting.NumberOfPhotons = 20000
lighting.MultipleScattering = 0                  # the lattice takes ~25 s on PoCL here
lighting.UpdatePipeline()
lit = servermanager.Fetch(lighting)
names = [lit.GetPointData().GetArrayName(i) for i in range(lit.GetPointData().GetNumberOfArrays())]
print("RefractaLighting arrays:", names)
assert lit.GetNumberOfPoints() == 24 ** 3 and "Radiance" in names, "a lighting volume on the grid"
assert "MultipleScattering" not in names, "MultipleScattering = 0 must switch the lattice off"
radiance = vtk_to_numpy(lit.GetPointData().GetArray("Radiance"))
assert np.isfinite(radiance).all() and radiance.max() > 0, "the lit sphere scatters light"
summary = lit.GetFieldData().GetAbstractArray("PlanSummary").GetValue(0)
print("RefractaLighting plan:", summary, "| lighting %.3f s" %
      lit.GetFieldData().GetArray("LightingSeconds").GetValue(0))
assert "SingleScattering on" in summary and "MultipleScattering off" in summary
assert lit.GetFieldData().GetArray("LightingSeconds").GetValue(0) > 0

# Multiple scattering (issue 14): the method is a proxy property; this scene has a lit surface,
# so the plan has photons carry every order whatever is asked (no lattice: seconds on PoCL), and
# records it.
lighting.MultipleScattering = 1
lighting.MultipleScatteringMethod = "Lattice"
lighting.UpdatePipeline()
lit = servermanager.Fetch(lighting)
assert lit.GetPointData().GetArray("MultipleScattering") is not None, "photons carry S_ms"
method = lit.GetFieldData().GetAbstractArray("PlanMultipleScatteringMethod")
print("RefractaLighting multiple scattering:", method.GetValue(0), "|", method.GetValue(1))
assert method.GetValue(0) == "photons"
lighting.ScatteringOrders = 3
assert lighting.ScatteringOrders == 3
# The lattice: the plan's choice by default, or forced (the pipeline's setting, which the
# filter's PrintSelf reads back).
assert "Lattice: 0\n" in str(lighting.GetClientSideObject()), "Auto: the plan chooses"
lighting.Lattice = "D3Q18"
lighting.UpdatePipeline()
assert "Lattice: 18\n" in str(lighting.GetClientSideObject()), "D3Q18 reaches the pipeline"
lighting.Lattice = "Auto"
lighting.MultipleScattering = 0

image.UpdatePipeline()
picture = servermanager.Fetch(image)
assert picture.GetDimensions() == (96, 96, 1)
for field in ("PlanSummary", "PlanSeconds", "LightingSeconds", "ViewSeconds"):
    assert picture.GetFieldData().GetAbstractArray(field) is not None, field + " in field data"
info = image.GetDataInformation().DataInformation.GetFieldDataInformation()
assert info.GetArrayInformation("PlanSummary") is not None, "the Information panel sees the plan"

# The glass knobs reach the passes (built-in session: the proxies' own objects, whose PrintSelf
# reads the values back from the photon tracer and the view pass).
lighting.VolumeCausticSubdivision = 2
lighting.UpdatePipeline()
assert "VolumeCausticSubdivision: 2" in str(lighting.GetClientSideObject()), "reaches the tracer"
image.VolumeCausticSubdivision = 1
image.GlassSupersampling = 5
image.UpdatePipeline()
printed = str(image.GetClientSideObject())
assert "VolumeCausticSubdivision: 1" in printed and "GlassSupersampling: 5" in printed, printed

# --- The representation type, offered for image data ---
view = simple.CreateRenderView()
display = simple.Show(medium, view)
assert "Refracta" in display.GetProperty("Representation").Available, "Refracta representation"
print("representation types:", display.GetProperty("Representation").Available)
display.Representation = "Refracta"
display.RefractaGlassSupersampling = 2
display.RefractaVolumeCausticSubdivision = 3
printed = str(display.GetClientSideObject().GetActiveRepresentation())
assert "RefractaGlassSupersampling: 2" in printed, "reaches the mapper's view pass"
assert "RefractaVolumeCausticSubdivision: 3" in printed, "reaches the mapper's photon tracer"
print("OK")
