"""Shared pieces of the ParaView plugin tests (run by pvpython / pvbatch from ctest).

The environment (ParaView/Testing/CMakeLists.txt) gives REFRACTA_PARAVIEW_PLUGIN (the built
RefractaPlugin.so), REFRACTA_BASELINE_DIR and REFRACTA_TEST_OUTPUT_DIR; the build tree's refracta
package is on PYTHONPATH.
"""
import os
import sys

PLUGIN = os.environ["REFRACTA_PARAVIEW_PLUGIN"]
BASELINES = os.environ.get("REFRACTA_BASELINE_DIR", ".")
OUTPUT = os.environ.get("REFRACTA_TEST_OUTPUT_DIR", ".")

# One glass sphere with a scattering, slightly absorbing interior: the scene every test shares.
SPHERE_RADIUS = 0.5
GLASS = [1.33, 3.0, 3.0, 3.0, 0.9, 0.8, 0.6, 0.3, 0.0, 0.0, 0.0]   # one Materials row
LIGHT = [0, -2.0, 1.5, 1.0, 0, 0, 0, 1.0, 1.0, 1.0, 4.0, 30.0]     # one Lights row: directional


def render_window_available(what_still_runs):
    """True when a render view can be made; otherwise print "no render window: <reason>" (ctest
    reports the test as skipped: refracta_test_needs_render_window) and return False. ParaView's
    VTK is an X11 build: without an X server its render views crash the process."""
    from refracta import vtkRefractaRenderWindowCheck
    if vtkRefractaRenderWindowCheck.CanOpen():
        return True
    print("no render window: %s; %s, the render-view checks do not"
          % (vtkRefractaRenderWindowCheck.GetReason(), what_still_runs))
    return False


def stop_without_render_window(what_ran):
    """Exit here (as skipped) when no render view can be made; `what_ran` passed already."""
    if not render_window_available("%s ran and passed" % what_ran):
        sys.exit(0)


def load_plugin(remote=False):
    """Load the plugin on the client (and on the server when `remote`); its proxies' functions
    join paraview.simple."""
    from paraview.simple import LoadPlugin
    LoadPlugin(PLUGIN, remote=False)
    if remote:
        LoadPlugin(PLUGIN, remote=True)


def make_scene(simple, dims=32):
    """Sphere -> Refracta Mesh Voxelizer -> Refracta Render Image (DRAFT, fixed seed)."""
    sphere = simple.Sphere(Radius=SPHERE_RADIUS, ThetaResolution=32, PhiResolution=32)
    medium = simple.RefractaMeshVoxelizer(Input=sphere)
    medium.Dimensions = [dims, dims, dims]
    medium.Padding = 0.15
    medium.SmoothingWindow = 5
    medium.Materials = GLASS
    image = simple.RefractaRenderImage(Input=medium)
    image.CameraPosition = [0, 0, 4]
    image.CameraViewAngle = 30
    image.ImageSize = [96, 96]
    image.Lights = LIGHT
    image.Quality = "Draft"
    image.Seed = 7
    image.NumberOfPhotons = 40000      # DRAFT's own count takes ~13 s on PoCL; enough for a baseline
    image.MultipleScattering = 0       # the photon pass only: seconds, not tens of seconds, on PoCL
    image.Exposure = 3.0
    image.ToneMapping = "Reinhard"
    return sphere, medium, image


def matches_baseline(image, name, threshold=15.0):
    """The RGB array of `image` (a fetched vtkImageData) against Testing/Baselines/<name>.png.

    vtkTesting's image comparison (as the C++ baseline tests use): the summed per-pixel error
    after its neighbourhood search must stay below `threshold`. REFRACTA_UPDATE_BASELINES=1
    writes the baseline instead.
    """
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkCommonExecutionModel import vtkTrivialProducer
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkTestingRendering import vtkTesting
    rgb = vtkImageData()
    rgb.CopyStructure(image)
    rgb.GetPointData().SetScalars(image.GetPointData().GetArray("RGB"))
    baseline = os.path.join(BASELINES, name + ".png")
    if os.environ.get("REFRACTA_UPDATE_BASELINES"):
        writer = vtkPNGWriter()
        writer.SetInputData(rgb)
        writer.SetFileName(baseline)
        writer.Write()
        print("wrote baseline", baseline)
        return True
    producer = vtkTrivialProducer()
    producer.SetOutput(rgb)
    testing = vtkTesting()
    for arg in ("-V", baseline, "-T", OUTPUT):
        testing.AddArgument(arg)
    result = testing.RegressionTest(producer, threshold)
    return result == vtkTesting.PASSED
