// vtkRefractiveVolumeMapper in an offscreen vtkRenderWindow (run under xvfb-run), composited with
// polydata actors, and vtkTransferFunctionMedium.
//
// Scene: a white background, an absorbing cube (sigma_t = (1, 2, 3), 16^3 grid, spacing 1/15, so
// the box is 16/15 deep) seen by a parallel camera along -z, a flat-shaded sphere inside the cube
// and a second one in front of it. Expected 8-bit pixels (VTK draws linear colour, no tone curve):
// - outside the box: the background, 255;
// - through the box only: 255 exp(-sigma 16/15);
// - on the inner sphere: 255 colour exp(-sigma l), l from the box top to the sphere's surface;
// - on the front sphere: its colour, untouched.
// Tolerance 3/255 (8-bit rounding of both the geometry pass and the blend), checked at pixel
// centres away from silhouettes. The cache is asserted by counting stage executions.
#include "MapperTestUtilities.h"
#include "RenderingTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkEffectPlan.h"
#include "vtkExecutive.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaViewPass.h"
#include "vtkRefractiveVolumeMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
const int Size = 96;
const double Sigma[3] = { 1.0, 2.0, 3.0 };
const double Top = 1.0 + 0.5 / 15; // box top in z
const double Depth = 16.0 / 15;

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window = refracta_test::SharedWindow(Size);
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRefractiveVolumeMapper> Mapper;
  vtkNew<vtkActor> Inner;
  vtkNew<vtkActor> Front;

  Scene()
  {
    this->Window->GetRenderers()->RemoveAllItems();
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(1, 1, 1);
    this->Volume->SetMapper(this->Mapper);
    this->Mapper->AutomaticExposureOff(); // these tests check radiometric compositing
    // The spheres are composited by depth (the rule for props that are not surfaces);
    // TestMapperSurfaces covers actors as surfaces.
    this->Mapper->ActorSurfacesOff();
    this->Renderer->AddVolume(this->Volume);
    AddSphere(this->Inner, 0.5, 0.5, 0.5, 0.25, 0.2, 0.8, 0.4);
    AddSphere(this->Front, 0.85, 0.85, 1.5, 0.1, 0.9, 0.3, 0.1);
    vtkCamera* camera = this->Renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetParallelScale(0.6);
    camera->SetFocalPoint(0.5, 0.5, 0.5);
    camera->SetPosition(0.5, 0.5, 4);
    camera->SetViewUp(0, 1, 0);
    camera->SetClippingRange(0.5, 8);
  }

  void AddSphere(
    vtkActor* actor, double x, double y, double z, double r, double cr, double cg, double cb)
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(x, y, z);
    sphere->SetRadius(r);
    sphere->SetThetaResolution(64);
    sphere->SetPhiResolution(64);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(cr, cg, cb);
    actor->GetProperty()->SetAmbient(1.0);
    actor->GetProperty()->SetDiffuse(0.0);
    actor->GetProperty()->SetSpecular(0.0);
    this->Renderer->AddActor(actor);
  }

  vtkSmartPointer<vtkImageData> Capture() { return refracta_test::Capture(this->Window); }
};

vtkSmartPointer<vtkImageData> AbsorbingCube()
{
  auto medium = refracta_test::MakeGrid(16, 16, 16, 1.0 / 15);
  refracta_test::AddConstant(medium, "Extinction", 3, Sigma[0], Sigma[1], Sigma[2]);
  return medium;
}

// World (x, y) of pixel (i, j) for the parallel camera above (scale 0.6 about (0.5, 0.5)).
void PixelXY(int i, int j, double& x, double& y)
{
  x = 0.5 + 0.6 * (2.0 * (i + 0.5) / Size - 1.0);
  y = 0.5 + 0.6 * (2.0 * (j + 0.5) / Size - 1.0);
}

// Checks the composited pixels against the analytic answer; returns the number checked.
int CheckComposite(vtkImageData* image, const double sigma[3], bool front = true)
{
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  EXPECT_NE(rgb, nullptr);
  const double innerColour[3] = { 0.2, 0.8, 0.4 }, frontColour[3] = { 0.9, 0.3, 0.1 };
  const double h = 1.2 / Size; // pixel size in world units
  const double lo = -0.5 / 15, hi = Top;
  int checked = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      double x, y;
      PixelXY(i, j, x, y);
      const double rInner = std::hypot(x - 0.5, y - 0.5);
      double rFront = std::hypot(x - 0.85, y - 0.85);
      const bool inBox = x > lo + 2 * h && x < hi - 2 * h && y > lo + 2 * h && y < hi - 2 * h;
      const bool outBox = x < lo - 2 * h || x > hi + 2 * h || y < lo - 2 * h || y > hi + 2 * h;
      double expected[3];
      if (!front)
      {
        rFront = 1.0;
      }
      if (rFront < 0.1 - 2 * h)
      {
        std::copy(frontColour, frontColour + 3, expected);
      }
      else if (rFront < 0.1 + 2 * h || std::abs(rInner - 0.25) < 2 * h || (!inBox && !outBox))
      {
        continue; // silhouettes and box edges: rasterisation decides
      }
      else if (outBox)
      {
        expected[0] = expected[1] = expected[2] = 1.0;
      }
      else if (rInner < 0.25)
      {
        const double l = Top - (0.5 + std::sqrt(0.0625 - rInner * rInner));
        for (int c = 0; c < 3; ++c)
        {
          expected[c] = innerColour[c] * std::exp(-sigma[c] * l);
        }
      }
      else
      {
        for (int c = 0; c < 3; ++c)
        {
          expected[c] = std::exp(-sigma[c] * Depth);
        }
      }
      for (int c = 0; c < 3; ++c)
      {
        const double got = rgb->GetValue(3 * (i + Size * j) + c);
        EXPECT_NEAR(got, 255.0 * expected[c], 3.0) << "pixel " << i << "," << j << " channel " << c;
      }
      ++checked;
    }
  }
  return checked;
}
}

TEST(RefractiveVolumeMapper, CompositesWithGeometryByDepth)
{
  Scene scene;
  scene.Mapper->SetInputData(AbsorbingCube());
  vtkSmartPointer<vtkImageData> image = scene.Capture();
  EXPECT_GT(CheckComposite(image, Sigma), Size * Size / 2);
  EXPECT_TRUE(refracta_test::MatchesBaseline(image, "MapperCompositing"));
}

// The absorbing cube with a glowing top corner (x, y < 0.2): the automatic exposure is then
// far from 1 (set by the corner), while the rest of the cube only dims the background.
static vtkSmartPointer<vtkImageData> CubeWithAGlowingCorner()
{
  auto medium = AbsorbingCube();
  vtkFloatArray* emission = refracta_test::AddConstant(medium, "Emission", 3, 0.0);
  int dims[3];
  medium->GetDimensions(dims);
  for (int k = 0; k < 3; ++k)
  {
    for (int j = 0; j < 3; ++j)
    {
      for (int i = 0; i < 3; ++i)
      {
        const vtkIdType p = i + dims[0] * (j + static_cast<vtkIdType>(dims[1]) * (dims[2] - 1 - k));
        emission->SetTuple3(p, 40.0, 40.0, 40.0);
      }
    }
  }
  return medium;
}

// Automatic exposure scales the scene's light, not VTK's background: with a glowing corner in
// the absorbing cube (exposure far from 1), the white background seen through the rest of the
// cube is still 255 exp(-sigma depth), as VTK's background dimmed by the medium, within 3/255.
TEST(RefractiveVolumeMapper, AutomaticExposureLeavesTheBackgroundAsVTKDrawsIt)
{
  Scene scene;
  scene.Mapper->SetInputData(CubeWithAGlowingCorner());
  scene.Mapper->AutomaticExposureOn();
  scene.Inner->VisibilityOff();
  scene.Front->VisibilityOff();
  vtkSmartPointer<vtkImageData> image = scene.Capture();
  const double exposure = scene.Mapper->GetLastExposure();
  std::cout << "automatic exposure " << exposure << "\n";
  EXPECT_GT(std::abs(exposure - 1.0), 0.5) << "the test needs an exposure far from 1";
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  const double h = 1.2 / Size;
  int checked = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      double x, y;
      PixelXY(i, j, x, y);
      const double lo = -0.5 / 15 + 2 * h, hi = Top - 2 * h;
      if (x < lo || x > hi || y < lo || y > hi || (x < 0.35 && y < 0.35))
      {
        continue; // outside the box, its edges, or near the glowing corner
      }
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(rgb->GetValue(3 * (i + Size * j) + c), 255.0 * std::exp(-Sigma[c] * Depth), 3.0)
          << "pixel " << i << "," << j << " channel " << c;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, Size * Size / 3);
}

// The same for a background that is not one colour (a gradient): through the cube VTK's own
// gradient, captured without the volume, times exp(-sigma l), l the ray's path through the box,
// within 3/255 (8-bit rounding; with a perspective camera also the gradient baked into a
// 512 x 256 map, vtkRefractaRendererBackground). A perspective camera sees it through the view
// pass's background part; a parallel one, whose rays share one direction, through VTK's own
// drawing of the pixel. The uniform-colour rule alone left this background exposed (0.12x
// here), and a parallel camera showed the viewport centre's colour across the cube.
static void CheckGradientThroughTheCube(bool parallel)
{
  Scene scene;
  scene.Renderer->GradientBackgroundOn();
  scene.Renderer->SetBackground(0.1, 0.3, 0.9);  // bottom
  scene.Renderer->SetBackground2(1.0, 0.9, 0.6); // top
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetParallelProjection(parallel);
  camera->SetViewAngle(30);
  scene.Mapper->SetInputData(CubeWithAGlowingCorner());
  scene.Mapper->AutomaticExposureOn();
  scene.Inner->VisibilityOff();
  scene.Front->VisibilityOff();
  scene.Volume->VisibilityOff();
  vtkSmartPointer<vtkImageData> gradient = scene.Capture();
  scene.Volume->VisibilityOn();
  vtkSmartPointer<vtkImageData> image = scene.Capture();
  const double exposure = scene.Mapper->GetLastExposure();
  std::cout << (parallel ? "parallel" : "perspective") << ": automatic exposure " << exposure
            << "\n";
  EXPECT_GT(std::abs(exposure - 1.0), 0.5) << "the test needs an exposure far from 1";
  auto* before = vtkUnsignedCharArray::SafeDownCast(gradient->GetPointData()->GetScalars());
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  const double lo = -0.5 / 15, hi = Top, eyeZ = 4.0;
  const double tanHalf = parallel ? 0.0 : std::tan(vtkMath::RadiansFromDegrees(15.0));
  int checked = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      // The pixel's ray (from (ox, oy, eyeZ) along (dx, dy, -1)) enters through the top face and
      // leaves through the bottom one, away from the side faces and the glowing corner.
      double ox = 0.5, oy = 0.5;
      if (parallel)
      {
        PixelXY(i, j, ox, oy);
      }
      const double dx = tanHalf * (2.0 * (i + 0.5) / Size - 1.0);
      const double dy = tanHalf * (2.0 * (j + 0.5) / Size - 1.0);
      bool inside = true;
      for (double z : { hi, lo })
      {
        const double x = ox + dx * (eyeZ - z), y = oy + dy * (eyeZ - z);
        inside = inside && x > lo + 0.03 && x < hi - 0.03 && y > lo + 0.03 && y < hi - 0.03 &&
          !(x < 0.35 && y < 0.35);
      }
      if (!inside)
      {
        continue;
      }
      const double l = Depth * std::sqrt(1.0 + dx * dx + dy * dy);
      for (int c = 0; c < 3; ++c)
      {
        const vtkIdType v = 3 * (i + Size * j) + c;
        EXPECT_NEAR(rgb->GetValue(v), before->GetValue(v) * std::exp(-Sigma[c] * l), 3.0)
          << "pixel " << i << "," << j << " channel " << c;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, Size * Size / 6);
}

TEST(RefractiveVolumeMapper, AutomaticExposureLeavesAGradientBackgroundAsVTKDrawsIt)
{
  CheckGradientThroughTheCube(false);
  CheckGradientThroughTheCube(true);
}

// Opaque geometry behind the medium (an actor the mapper composites by depth) shows through it
// dimmed, with nothing of the background (white here) added: a ray that leaves the box before
// its depth limit ends at that geometry. Both view kernels (the eight-lane one applies to this
// emission-absorption medium). The old kernels added T x background: +88/255 in red.
TEST(RefractiveVolumeMapper, GeometryBehindTheMediumShowsNoBackground)
{
  Scene scene;
  scene.Mapper->SetInputData(AbsorbingCube());
  scene.Inner->VisibilityOff();
  scene.Front->VisibilityOff();
  vtkNew<vtkActor> behind;
  scene.AddSphere(behind, 0.25, 0.75, -0.6, 0.15, 0.9, 0.9, 0.2);
  const double colour[3] = { 0.9, 0.9, 0.2 }, h = 1.2 / Size;
  for (bool lanes : { true, false })
  {
    scene.Mapper->GetViewPass()->SetLaneMarching(lanes);
    vtkSmartPointer<vtkImageData> image = scene.Capture();
    auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
    int checked = 0;
    for (int j = 0; j < Size; ++j)
    {
      for (int i = 0; i < Size; ++i)
      {
        double x, y;
        PixelXY(i, j, x, y);
        if (std::hypot(x - 0.25, y - 0.75) > 0.15 - 2 * h)
        {
          continue;
        }
        for (int c = 0; c < 3; ++c)
        {
          EXPECT_NEAR(rgb->GetValue(3 * (i + Size * j) + c),
            255.0 * colour[c] * std::exp(-Sigma[c] * Depth), 3.0)
            << (lanes ? "lanes" : "general") << " pixel " << i << "," << j << " channel " << c;
        }
        ++checked;
      }
    }
    EXPECT_GT(checked, 200);
  }
}

// vtkCamera::SetWindowCenter (what vtkRenderLargeImage and vtkWindowToImageFilter's scale tile
// with) shifts the medium exactly as it shifts VTK's actors: every pixel of the shifted view is
// the pixel (Size / 4, -Size / 8) away in the centred one, within 3/255, for both projections.
// The ray frame ignored it before: the medium stayed while the actors moved.
TEST(RefractiveVolumeMapper, WindowCenterShiftsTheMediumWithTheActors)
{
  for (bool parallel : { true, false })
  {
    Scene scene;
    scene.Mapper->SetInputData(AbsorbingCube());
    vtkCamera* camera = scene.Renderer->GetActiveCamera();
    camera->SetParallelProjection(parallel);
    camera->SetViewAngle(30);
    vtkSmartPointer<vtkImageData> centred = scene.Capture();
    camera->SetWindowCenter(0.5, -0.25);
    vtkSmartPointer<vtkImageData> shifted = scene.Capture();
    camera->SetWindowCenter(0, 0);
    auto* a = vtkUnsignedCharArray::SafeDownCast(centred->GetPointData()->GetScalars());
    auto* b = vtkUnsignedCharArray::SafeDownCast(shifted->GetPointData()->GetScalars());
    const int di = Size / 4, dj = -Size / 8;
    int compared = 0, differing = 0;
    for (int j = std::max(0, -dj); j < Size - std::max(0, dj); ++j)
    {
      for (int i = 0; i + di < Size; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          const int got = b->GetValue(3 * (i + Size * j) + c);
          const int want = a->GetValue(3 * (i + di + Size * (j + dj)) + c);
          differing += std::abs(got - want) > 3;
        }
        ++compared;
      }
    }
    std::cout << (parallel ? "parallel" : "perspective") << ": " << differing << " of "
              << 3 * compared << " channels differ by more than 3\n";
    EXPECT_GT(compared, Size * Size / 2);
    EXPECT_EQ(differing, 0);
  }
}

// Channels of `a` and `b` (RGB captures of one size) that differ by more than 3/255.
int DifferingChannels(vtkImageData* a, vtkImageData* b)
{
  auto* x = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  auto* y = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetScalars());
  EXPECT_EQ(x->GetNumberOfValues(), y->GetNumberOfValues());
  int differing = 0;
  for (vtkIdType v = 0; v < std::min(x->GetNumberOfValues(), y->GetNumberOfValues()); ++v)
  {
    differing += std::abs(int(x->GetValue(v)) - int(y->GetValue(v))) > 3;
  }
  return differing;
}

// The image depends on the current view only, not on what was drawn before: with nothing but
// the medium in the renderer the depth buffer stays all background, and the pixels' kinds
// (covered by the medium or clear) were kept from the first view: moving the camera into the
// cube left the old footprint's outside clear (the white background undimmed), switching the
// projection lost the edge pixels, and vtkWindowToImageFilter's tiles (SetScale) reused the first
// tile's footprint: black seams. Each view must equal the same view drawn by a new mapper.
TEST(RefractiveVolumeMapper, TheImageDependsOnlyOnTheCurrentView)
{
  auto cube = AbsorbingCube();
  auto setView = [](vtkCamera* camera, int view)
  {
    camera->SetParallelProjection(view == 2);
    camera->SetViewAngle(30);
    camera->SetPosition(0.5, 0.5, view == 1 ? 0.45 : 5.0);
    camera->SetFocalPoint(0.45, 0.5, -1.0);
    camera->SetClippingRange(0.01, 8);
  };
  auto sceneWithCube = [&](Scene& scene)
  {
    scene.Inner->VisibilityOff();
    scene.Front->VisibilityOff();
    scene.Mapper->SetInputData(cube);
  };
  // 0: outside, perspective; 1: inside the cube; 2: outside, parallel.
  for (int view : { 1, 2 })
  {
    Scene moved;
    sceneWithCube(moved);
    setView(moved.Renderer->GetActiveCamera(), 0);
    moved.Capture();
    setView(moved.Renderer->GetActiveCamera(), view);
    vtkSmartPointer<vtkImageData> after = moved.Capture();
    Scene fresh;
    sceneWithCube(fresh);
    setView(fresh.Renderer->GetActiveCamera(), view);
    EXPECT_EQ(DifferingChannels(after, fresh.Capture()), 0) << "view " << view;
  }

  // Four tiles of a half-size window against the full-size window.
  Scene tiled;
  sceneWithCube(tiled);
  setView(tiled.Renderer->GetActiveCamera(), 0);
  vtkSmartPointer<vtkImageData> direct = tiled.Capture();
  tiled.Window->SetSize(Size / 2, Size / 2);
  vtkNew<vtkWindowToImageFilter> tiles;
  tiles->SetInput(tiled.Window);
  tiles->SetScale(2);
  tiles->SetInputBufferTypeToRGB();
  tiles->ReadFrontBufferOff();
  tiles->Update();
  tiled.Window->SetSize(Size, Size);
  EXPECT_EQ(DifferingChannels(tiles->GetOutput(), direct), 0);
}

// Translucent geometry is drawn by VTK before the volume and covered where the medium is: the
// mapper says so once (not on every render) and again after it was gone and came back.
TEST(RefractiveVolumeMapper, TranslucentGeometryIsNamedOnce)
{
  Scene scene;
  scene.Mapper->SetInputData(AbsorbingCube());
  vtkNew<vtkTest::ErrorObserver> warnings;
  scene.Mapper->AddObserver(vtkCommand::WarningEvent, warnings);
  scene.Capture();
  EXPECT_FALSE(warnings->GetWarning()) << warnings->GetWarningMessage();
  scene.Front->GetProperty()->SetOpacity(0.5);
  scene.Capture();
  ASSERT_TRUE(warnings->GetWarning());
  EXPECT_NE(warnings->GetWarningMessage().find("translucent geometry"), std::string::npos)
    << warnings->GetWarningMessage();
  EXPECT_NE(warnings->GetWarningMessage().find("Actor"), std::string::npos); // vtkOpenGLActor
  warnings->Clear();
  scene.Capture();
  EXPECT_FALSE(warnings->GetWarning());
  scene.Front->GetProperty()->SetOpacity(1.0);
  scene.Capture();
  scene.Front->GetProperty()->SetOpacity(0.5);
  scene.Capture();
  EXPECT_TRUE(warnings->GetWarning());
}

// A volume in a transparent renderer (layer 1 over layer 0) shows the layers below through the
// medium, dimmed: its own background (magenta here) is never drawn by VTK and must not show.
TEST(RefractiveVolumeMapper, ATransparentLayerShowsTheLayersBelow)
{
  Scene scene;
  scene.Mapper->SetInputData(AbsorbingCube());
  scene.Inner->VisibilityOff();
  scene.Front->VisibilityOff();
  vtkNew<vtkRenderer> below;
  below->SetBackground(0.2, 0.6, 0.9);
  below->SetActiveCamera(scene.Renderer->GetActiveCamera());
  below->SetLayer(0);
  scene.Renderer->SetLayer(1);
  scene.Renderer->SetBackground(1, 0, 1);
  scene.Window->SetNumberOfLayers(2);
  scene.Window->AddRenderer(below);
  vtkSmartPointer<vtkImageData> image = scene.Capture();
  scene.Window->RemoveRenderer(below);
  scene.Window->SetNumberOfLayers(1);
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  const double background[3] = { 0.2, 0.6, 0.9 }, h = 1.2 / Size;
  const double lo = -0.5 / 15 + 2 * h, hi = Top - 2 * h;
  int checked = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      double x, y;
      PixelXY(i, j, x, y);
      const bool inside = x > lo && x < hi && y > lo && y < hi;
      const bool outside = x < lo - 4 * h || x > hi + 4 * h || y < lo - 4 * h || y > hi + 4 * h;
      for (int c = 0; c < 3 && (inside || outside); ++c)
      {
        const double expected = 255.0 * background[c] * (inside ? std::exp(-Sigma[c] * Depth) : 1);
        EXPECT_NEAR(rgb->GetValue(3 * (i + Size * j) + c), expected, 3.0)
          << "pixel " << i << "," << j << " channel " << c;
      }
      checked += inside;
    }
  }
  EXPECT_GT(checked, Size * Size / 3);
}

TEST(RefractiveVolumeMapper, CacheRunsOnlyWhatChanged)
{
  Scene scene;
  auto medium = AbsorbingCube();
  // A synthetic lighting volume, supplied instead of the light passes.
  vtkNew<vtkImageData> lighting;
  lighting->CopyStructure(medium);
  refracta_test::AddConstant(
    lighting, vtkRefractaLightingVolume::MultipleScatteringName(), 3, 0.5, 0.5, 0.5);
  scene.Mapper->SetInputData(medium);
  scene.Mapper->SetLightingData(lighting);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), 1);
  EXPECT_EQ(scene.Mapper->GetNumberOfViewPassRuns(), 1);
  const int uploads = scene.Mapper->GetViewPass()->GetNumberOfUploads();
  EXPECT_EQ(uploads, 2); // medium + lighting

  // Nothing changed: the image is drawn again without running anything.
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfViewPassRuns(), 1);

  // Camera move: the view pass only.
  scene.Renderer->GetActiveCamera()->Azimuth(10);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfViewPassRuns(), 2);
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), 1);
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), 0);
  EXPECT_EQ(scene.Mapper->GetViewPass()->GetNumberOfUploads(), uploads);

  // Geometry moves (depth buffer changes): the view pass again, nothing else.
  scene.Inner->SetPosition(0.05, 0, 0);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfViewPassRuns(), 3);
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), 1);

  // Empty-space skipping is a view knob: switching it re-runs the view pass only (no medium
  // build, no upload).
  EXPECT_TRUE(scene.Mapper->GetEmptySpaceSkipping());
  scene.Mapper->EmptySpaceSkippingOff();
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfViewPassRuns(), 4);
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), 1);
  EXPECT_EQ(scene.Mapper->GetViewPass()->GetNumberOfUploads(), uploads);
  scene.Mapper->EmptySpaceSkippingOn();
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfViewPassRuns(), 5);

  // The medium changes: everything.
  medium->Modified();
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), 2);
  EXPECT_EQ(scene.Mapper->GetNumberOfViewPassRuns(), 6);
  EXPECT_EQ(scene.Mapper->GetViewPass()->GetNumberOfUploads(), uploads + 2);
}

TEST(RefractiveVolumeMapper, ScalarInputThroughTransferFunctions)
{
  // A scalar field whose opacity function gives a = 1 - exp(-sigma d) per unit distance d: the
  // same extinction as AbsorbingCube's red channel, grey.
  auto scalars = refracta_test::MakeGrid(16, 16, 16, 1.0 / 15);
  vtkFloatArray* density = refracta_test::AddConstant(scalars, "density", 1, 7.0);
  scalars->GetPointData()->SetScalars(density);
  const double unit = 0.5;
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0);
  opacity->AddPoint(10, 10 * (1 - std::exp(-2.0 * unit)) / 7.0); // a(7) = 1 - exp(-2 d)
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(0, 0, 0, 0);
  colour->AddRGBPoint(10, 1, 0.5, 0.25);
  vtkNew<vtkPiecewiseFunction> index;
  index->AddPoint(0, 1.0);
  index->AddPoint(10, 1.4);

  vtkNew<vtkVolumeProperty> property;
  property->SetScalarOpacity(opacity);
  property->SetColor(colour);
  property->SetScalarOpacityUnitDistance(unit);

  vtkNew<vtkTransferFunctionMedium> mapping;
  mapping->SetInputData(scalars);
  mapping->SetVolumeProperty(property);
  mapping->SetRefractiveIndexFunction(index);
  mapping->SetAnisotropy(0.3);
  mapping->SetEmissionScale(2.0);
  mapping->Update();
  vtkPointData* pd = mapping->GetOutput()->GetPointData();
  double e[3], a[3];
  pd->GetArray("Extinction")->GetTuple(100, e);
  pd->GetArray("Albedo")->GetTuple(100, a);
  EXPECT_NEAR(e[0], 2.0, 1e-5);
  EXPECT_NEAR(e[2], 2.0, 1e-5);
  EXPECT_NEAR(a[0], 0.7, 1e-6);
  EXPECT_NEAR(a[1], 0.35, 1e-6);
  EXPECT_NEAR(pd->GetArray("RefractiveIndex")->GetTuple1(5), 1.28, 1e-6);
  EXPECT_NEAR(pd->GetArray("Anisotropy")->GetTuple1(5), 0.3, 1e-6);
  EXPECT_NEAR(pd->GetArray("Emission")->GetComponent(5, 1), 2.0 * 0.35 * 2.0, 1e-5);

  // Through the mapper: same transmittance as the medium with sigma = 2 (the index is constant,
  // so rays stay straight; no emission in the mapper's default).
  Scene scene;
  scene.Renderer->RemoveActor(scene.Front);
  // No lights: the albedo (from the colour function) has nothing to scatter; pure absorption.
  scene.Renderer->AutomaticLightCreationOff();
  scene.Renderer->RemoveAllLights();
  scene.Volume->SetProperty(property);
  scene.Mapper->SetInputData(scalars);
  vtkSmartPointer<vtkImageData> image = scene.Capture();
  const double grey[3] = { 2.0, 2.0, 2.0 };
  EXPECT_GT(CheckComposite(image, grey, false), Size * Size / 2);
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), 1);
  // Editing a transfer function re-runs the medium stage.
  opacity->AddPoint(5, 0.1);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), 2);

  // Bad input: three dependent components (VTK defines 2 or 4).
  vtkNew<vtkTest::ErrorObserver> errors;
  vtkNew<vtkImageData> threeComponents;
  threeComponents->SetDimensions(4, 4, 4);
  threeComponents->GetPointData()->SetScalars(
    refracta_test::AddConstant(threeComponents, "v", 3, 1.0, 2.0));
  property->IndependentComponentsOff();
  mapping->AddObserver(vtkCommand::ErrorEvent, errors);
  mapping->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  mapping->SetInputData(threeComponents);
  mapping->Update();
  EXPECT_NE(errors->GetErrorMessage().find("components"), std::string::npos);
  EXPECT_EQ(mapping->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(RefractiveVolumeMapper, LightPassesRunOnlyWhenLightsChange)
{
  // A scattering fog lit by a scene light: the photon tracer runs for the light, not for the
  // camera.
  Scene scene;
  scene.Renderer->RemoveActor(scene.Front);
  scene.Renderer->SetBackground(0, 0, 0);
  auto fog = refracta_test::MakeGrid(20, 20, 20, 1.0 / 19);
  refracta_test::AddConstant(fog, "Extinction", 3, 2.0, 2.0, 2.0);
  refracta_test::AddConstant(fog, "Albedo", 3, 0.8, 0.8, 0.8);
  scene.Mapper->SetInputData(fog);
  scene.Mapper->SetNumberOfPhotons(1 << 14);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(3, 0.5, 0.5);
  light->SetFocalPoint(0.5, 0.5, 0.5);
  light->SetIntensity(2.0);
  scene.Renderer->RemoveAllLights();
  scene.Renderer->AddLight(light);
  scene.Renderer->AutomaticLightCreationOff();

  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), 1);
  ASSERT_NE(scene.Mapper->GetLighting(), nullptr);
  EXPECT_NE(scene.Mapper->GetLighting()->GetPointData()->GetArray(
              vtkRefractaLightingVolume::RadianceName()),
    nullptr);
  EXPECT_NE(scene.Mapper->GetLighting()->GetPointData()->GetArray(
              vtkRefractaLightingVolume::MultipleScatteringName()),
    nullptr);
  // The fog is lit: the medium's radiance shows (the background is black).
  vtkSmartPointer<vtkImageData> lit = scene.Capture();
  double sum = 0;
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(lit->GetPointData()->GetScalars());
  for (vtkIdType i = 0; i < rgb->GetNumberOfValues(); ++i)
  {
    sum += rgb->GetValue(i);
  }
  EXPECT_GT(sum, 0.0);
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), 1);
  const int views = scene.Mapper->GetNumberOfViewPassRuns();

  scene.Renderer->GetActiveCamera()->Elevation(15);
  scene.Renderer->GetActiveCamera()->OrthogonalizeViewUp();
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), 1) << "a camera move must not re-light";
  EXPECT_EQ(scene.Mapper->GetNumberOfViewPassRuns(), views + 1);

  light->SetIntensity(4.0);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), 2) << "a light change re-lights";
  EXPECT_EQ(scene.Mapper->GetNumberOfViewPassRuns(), views + 2);
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), 1);
  light->SetIntensity(2.0);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), 3);

  // A quality preset sets the plan, the photon count and the view step, and re-lights.
  scene.Mapper->SetQuality(vtkEffectPlan::DRAFT);
  EXPECT_EQ(scene.Mapper->GetEffectPlan()->GetQuality(), vtkEffectPlan::DRAFT);
  EXPECT_EQ(scene.Mapper->GetNumberOfPhotons(),
    scene.Mapper->GetEffectPlan()->GetRecommendedNumberOfPhotons());
  EXPECT_EQ(scene.Mapper->GetStepSize(), scene.Mapper->GetEffectPlan()->GetRecommendedViewStep());
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), 4);
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), 2); // the plan's tolerance changed
  vtkNew<vtkTest::ErrorObserver> errors;
  scene.Mapper->GetEffectPlan()->AddObserver(vtkCommand::ErrorEvent, errors);
  scene.Mapper->SetQuality(7); // unknown: an error, nothing changes
  EXPECT_TRUE(errors->GetError());
  EXPECT_EQ(scene.Mapper->GetEffectPlan()->GetQuality(), vtkEffectPlan::DRAFT);
}
