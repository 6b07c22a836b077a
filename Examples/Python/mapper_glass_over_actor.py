"""A voxelized glass ball over an ordinary VTK floor actor, in a vtkRenderWindow.

    PYTHONPATH=build/lib/python3.11/dist-packages xvfb-run -a /usr/bin/python3 \
        Examples/Python/mapper_glass_over_actor.py [--out mapper_glass.png] [--size 400]

The ball (n = 1.5) is the only thing in the medium; the floor is a plain vtkPlaneSource actor
with VTK's default material, lit by a spot light from above. vtkRefractiveVolumeMapper takes the
actor as a surface of its light and view passes: the ball focuses the spot into a caustic on the
floor, ringed by its shadow, both well outside the ball's own screen footprint, and the floor is
seen bent through the ball. ShadeActorsEverywhere (off by default: VTK's own shading away from
the medium) lets the whole floor show the light passes' shading, so the caustic shows and there is
no seam at the medium's outline; the renderer's uniform background seen through the ball stays
VTK's colour whatever the automatic exposure.

Smoke check: the caustic under the ball is much brighter than the lit floor beside the shadow,
which is darker than both; the background around and through the medium is VTK's own.
"""
import argparse
import sys

import refracta
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL render window)
from vtkmodules.vtkFiltersSources import vtkPlaneSource, vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkLight, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow, vtkVolume, vtkWindowToImageFilter)

parser = argparse.ArgumentParser()
parser.add_argument("--out", default="mapper_glass.png")
parser.add_argument("--size", type=int, default=400, help="image width (height 3/4 of it)")
args = parser.parse_args()
if not refracta.vtkRefractaRenderWindowCheck.CanOpen():      # an X11 VTK would abort instead
    sys.exit("no render window: " + refracta.vtkRefractaRenderWindowCheck.GetReason())

glass = refracta.vtkMediumMaterial(); glass.SetRefractiveIndex(1.5)
ball = vtkSphereSource(); ball.SetRadius(0.3); ball.SetCenter(0, 0, 0.8)
ball.SetThetaResolution(48); ball.SetPhiResolution(48)
medium = refracta.vtkMeshVoxelizer()                 # the ball alone, in a box just around it
medium.AddInputConnection(ball.GetOutputPort()); medium.SetMaterial(0, glass)
medium.SetDimensions(40, 40, 40); medium.SetBounds(-0.4, 0.4, -0.4, 0.4, 0.4, 1.2)
mapper = refracta.vtkRefractiveVolumeMapper(); mapper.SetInputConnection(medium.GetOutputPort())
mapper.ShadeActorsEverywhereOn()    # the actors lit by the light passes everywhere, not only under the ball
volume = vtkVolume(); volume.SetMapper(mapper)

floor = vtkPlaneSource(); floor.SetOrigin(-2, -2, 0); floor.SetPoint1(2, -2, 0); floor.SetPoint2(-2, 2, 0)
floor_mapper = vtkPolyDataMapper(); floor_mapper.SetInputConnection(floor.GetOutputPort())
floor_actor = vtkActor(); floor_actor.SetMapper(floor_mapper)   # an ordinary VTK actor

renderer = vtkRenderer(); renderer.SetBackground(0.1, 0.1, 0.15)
renderer.AddActor(floor_actor); renderer.AddVolume(volume)
spot = vtkLight(); spot.SetLightTypeToSceneLight(); spot.SetPositional(True); spot.SetConeAngle(20)
spot.SetPosition(0, 0, 3); spot.SetFocalPoint(0, 0, 0); renderer.AddLight(spot)
camera = renderer.GetActiveCamera()
camera.SetPosition(0, -3, 2); camera.SetFocalPoint(0, 0, 0.3); camera.SetViewUp(0, 0, 1)
width, height = args.size, args.size * 3 // 4
window = vtkRenderWindow(); window.SetOffScreenRendering(1); window.SetSize(width, height)
window.AddRenderer(renderer); window.Render()
grab = vtkWindowToImageFilter(); grab.SetInput(window); grab.Update()
writer = vtkPNGWriter(); writer.SetInputConnection(grab.GetOutputPort())
writer.SetFileName(args.out); writer.Write()
print(mapper.GetPipeline().GetEffectPlan().GetSummary(), "| exposure %.3f" % mapper.GetLastExposure())

rgb = grab.GetOutput().GetPointData().GetScalars()


def grey_at(x, y, z, r=2):
    """Mean grey over (2r + 1)^2 pixels around the pixel of world point (x, y, z)."""
    renderer.SetWorldPoint(x, y, z, 1.0); renderer.WorldToDisplay()
    i, j = (int(v) for v in renderer.GetDisplayPoint()[:2])
    values = [sum(rgb.GetTuple3(a + width * b)) / 3.0
              for b in range(j - r, j + r + 1) for a in range(i - r, i + r + 1)]
    return sum(values) / len(values)


caustic, shadow, lit = grey_at(0, 0, 0), grey_at(0.3, 0, 0), grey_at(0.75, 0, 0)
# Background around the medium, and through its clear corner above the ball (in the medium's
# box, past the ball's top at z = 1.1; the ray goes on over the floor's far edge).
around = sum(rgb.GetTuple3(5 + width * (height - 5))) / 3.0    # the top left corner
through = grey_at(0.0, 0.0, 1.16, r=0)
print("caustic %.0f, shadow ring %.0f, lit floor %.0f, background %.1f around the medium, "
      "%.1f through it (0..255)" % (caustic, shadow, lit, around, through))
assert caustic > 1.3 * lit and shadow < 0.6 * lit, "the caustic and the shadow show on the floor"
assert abs(through - around) <= 1.0, "VTK's background seen through clear medium is VTK's"
