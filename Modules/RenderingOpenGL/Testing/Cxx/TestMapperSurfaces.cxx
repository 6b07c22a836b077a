// vtkRefractiveVolumeMapper with surfaces (the renderer's opaque actors) and the renderer's
// background, in an offscreen vtkRenderWindow (run under xvfb-run).
//
// Medium: a glass ball lens, n = 1.5 inside radius R = 0.35 about the origin, on a 64^3 grid
// (spacing 1/63) with the index ramped linearly from 1.5 to 1 over w = 2 voxels about r = R (the
// smoothing a voxelized mesh gets). Expected images come from an independent trace of the SHARP
// sphere of radius R in double precision (Snell's law at entry and exit) done in this test:
// - ball lens over a plane actor 3 R behind the centre (beyond the focus at f = n R / (2 (n - 1))
//   = 1.5 R), its left half red, its right half blue (cell colours through the mapper's scalar
//   colouring): each pixel's colour class (red or blue) must be the one at the traced ray's hit
//   on the plane. Pixels in a rim band |b - R| < 0.05 (3 voxels: the ramp plus the trilinear
//   footprint; b the ray's distance from the centre) and pixels whose traced hit lies within
//   0.06 of the colour edge x = 0 (texel and pixel footprint) are not judged. Required: 95% of
//   the judged pixels inside the silhouette and 98% outside agree; inside, the halves are swapped
//   (a ball lens inverts).
// - the same with the ball as a voxelized sphere mesh (vtkMeshVoxelizer, exact interfaces, its
//   default): the mapper meets the glass exactly (the pipeline adds the medium's interfaces to
//   the actors' surfaces), so the rim band shrinks to about one pixel (0.012) and 99% of the
//   judged pixels inside the silhouette and outside must agree. In both, a pixel whose four
//   corners' traced rays land on different halves or off the plane is not judged (near the rim
//   one pixel spans both, and the refracted ray runs off the plane: the weaker internally
//   reflected leg then sets the colour).
// - moving the plane actor re-runs the light passes and rebuilds the surface set's BVH, but not
//   the medium stage, and the actor collection is not rebuilt.
// - ball lens over a vertical gradient background (red at the bottom, blue at the top of the
//   viewport), perspective camera: each pixel's colour must be the gradient at the viewport
//   position of its traced exit direction (the convention of vtkRefractaRendererBackground):
//   away from the rim band, 99% of the pixels within 8/255 and all within 20/255 (measured: 40
//   of 8032 above 8, worst 13, where b / R ~ 0.75 and the exit direction changes fastest); inside
//   the lens, the top shows the bottom colour.
// - no lights and a uniform grey background that illuminates (BackgroundIlluminates): the plane
//   actor's mean irradiance is 2 pi L (pi L per side) within 3%, and a new background re-lights.
#include "MapperTestUtilities.h"
#include "RenderingTestUtilities.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMediumMaterial.h"
#include "vtkMeshVoxelizer.h"
#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRefractaActorSurfaces.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaRendererBackground.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"
#include "vtkRefractiveVolumeMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSkybox.h"
#include "vtkSphereSource.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
const int Size = 96;
const int N = 64;
const double Radius = 0.35;
const double Ramp = 2.0 / (N - 1); // index ramp width, world units
const double IndexInside = 1.5;
const double PlaneZ = -3 * Radius;
const double RimBand = 0.05;

vtkSmartPointer<vtkImageData> BallLens()
{
  const double origin[3] = { -0.5, -0.5, -0.5 };
  auto medium = refracta_test::MakeGrid(N, N, N, 1.0 / (N - 1), origin);
  vtkFloatArray* n = refracta_test::AddConstant(medium, "RefractiveIndex", 1, 1.0);
  for (vtkIdType p = 0; p < medium->GetNumberOfPoints(); ++p)
  {
    double x[3];
    medium->GetPoint(p, x);
    const double r = vtkMath::Norm(x);
    const double f = std::min(std::max((Radius + 0.5 * Ramp - r) / Ramp, 0.0), 1.0);
    n->SetValue(p, static_cast<float>(1.0 + (IndexInside - 1.0) * f));
  }
  return medium;
}

// The same ball as a sharp glass sphere mesh (192 x 96), voxelized with exact interfaces on the
// same grid.
vtkSmartPointer<vtkImageData> ExactBallLens()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(Radius);
  sphere->SetThetaResolution(192);
  sphere->SetPhiResolution(96);
  sphere->Update();
  vtkNew<vtkMeshVoxelizer> voxelizer;
  voxelizer->AddInputData(sphere->GetOutput());
  vtkNew<vtkMediumMaterial> glass;
  glass->SetRefractiveIndex(IndexInside);
  voxelizer->SetMaterial(0, glass);
  voxelizer->SetDimensions(N, N, N);
  voxelizer->SetBounds(-0.5, 0.5, -0.5, 0.5, -0.5, 0.5);
  voxelizer->Update();
  auto medium = vtkSmartPointer<vtkImageData>::New();
  medium->ShallowCopy(voxelizer->GetOutput());
  return medium;
}

// Snell's law: the refracted unit direction of unit `d` at a surface with unit normal `normal`
// (facing the incoming ray), from index n1 to n2. Returns false on total internal reflection.
bool Refract(const double d[3], const double normal[3], double n1, double n2, double out[3])
{
  const double eta = n1 / n2, cosi = -vtkMath::Dot(d, normal);
  const double k = 1 - eta * eta * (1 - cosi * cosi);
  if (k < 0)
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    out[a] = eta * d[a] + (eta * cosi - std::sqrt(k)) * normal[a];
  }
  return true;
}

// The sharp sphere (radius R at the origin, index 1.5) acting on the ray o + t d (d unit):
// replaces (o, d) by the ray leaving the sphere; false where the ray misses it (unchanged).
bool TraceSharpSphere(double o[3], double d[3])
{
  const double b = vtkMath::Dot(o, d), c = vtkMath::Dot(o, o) - Radius * Radius;
  const double disc = b * b - c;
  if (disc <= 0)
  {
    return false;
  }
  const double t = -b - std::sqrt(disc);
  double p[3], normal[3], inside[3];
  for (int a = 0; a < 3; ++a)
  {
    p[a] = o[a] + t * d[a];
    normal[a] = p[a] / Radius;
  }
  Refract(d, normal, 1.0, IndexInside, inside);
  const double t2 = -2 * vtkMath::Dot(p, inside); // the chord through the sphere
  for (int a = 0; a < 3; ++a)
  {
    o[a] = p[a] + t2 * inside[a];
    normal[a] = -o[a] / Radius; // facing the ray inside
  }
  Refract(inside, normal, IndexInside, 1.0, d);
  return true;
}

struct Scene
{
  vtkSmartPointer<vtkRenderWindow> Window = refracta_test::SharedWindow(Size);
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRefractiveVolumeMapper> Mapper;

  explicit Scene(vtkImageData* medium = nullptr)
  {
    this->Window->GetRenderers()->RemoveAllItems();
    this->Window->AddRenderer(this->Renderer);
    this->Volume->SetMapper(this->Mapper);
    this->Mapper->SetInputData(medium ? medium : BallLens().GetPointer());
    this->Mapper->AutomaticExposureOff();
    this->Mapper->MultipleScatteringOff();
    this->Mapper->SetNumberOfPhotons(1 << 16);
    this->Renderer->AddVolume(this->Volume);
  }

  vtkSmartPointer<vtkImageData> Capture() { return refracta_test::Capture(this->Window); }
};

// A plane actor at z = PlaneZ, 3 x 3, left half red, right half blue (cell colours).
void AddSplitPlane(vtkRenderer* renderer, vtkActor* actor)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1.5, -1.5, PlaneZ);
  plane->SetPoint1(1.5, -1.5, PlaneZ);
  plane->SetPoint2(-1.5, 1.5, PlaneZ);
  plane->SetResolution(2, 1);
  plane->Update();
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetNumberOfComponents(3);
  colours->InsertNextTuple3(255, 0, 0);
  colours->InsertNextTuple3(0, 0, 255);
  plane->GetOutput()->GetCellData()->SetScalars(colours);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(plane->GetOutput());
  mapper->SetScalarModeToUseCellData();
  actor->SetMapper(mapper);
  renderer->AddActor(actor);
}

const unsigned char* Pixel(vtkImageData* image, int i, int j)
{
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  return rgb->GetPointer(3 * (i + Size * j));
}

void UseParallelCamera(vtkRenderer* renderer)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(0.5);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 0, 3);
  camera->SetViewUp(0, 1, 0);
  camera->SetClippingRange(0.5, 6);
}

void AddLightAlongView(vtkRenderer* renderer)
{
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(0, 0, 3);
  light->SetFocalPoint(0, 0, 0);
  light->SetIntensity(1.0);
  renderer->AutomaticLightCreationOff();
  renderer->RemoveAllLights();
  renderer->AddLight(light);
}

// Where the parallel view ray at (x, y) meets the split plane's height after the sharp sphere.
void TracedPlaneHit(double x, double y, double hit[2])
{
  double o[3] = { x, y, 3 }, d[3] = { 0, 0, -1 };
  TraceSharpSphere(o, d);
  hit[0] = o[0] + (PlaneZ - o[2]) / d[2] * d[0];
  hit[1] = o[1] + (PlaneZ - o[2]) / d[2] * d[1];
}

// Whether the traced rays through the four corners of the pixel at (x, y) all land on the plane
// (3 x 3 about the axis) and all on its `left` (red) half or all on its right: near the rim the
// exit direction turns so fast that one pixel spans both halves or runs off the plane, and its
// colour is then a matter of where in it the ray went (or of the weaker reflected legs).
bool FootprintSeesOneColour(double x, double y, bool left)
{
  const double h = 0.5 / Size; // half a pixel (the view is 1 wide)
  for (double dx : { -h, h })
  {
    for (double dy : { -h, h })
    {
      double hit[2];
      TracedPlaneHit(x + dx, y + dy, hit);
      if (std::abs(hit[0]) > 1.5 || std::abs(hit[1]) > 1.5 || (hit[0] < 0) != left)
      {
        return false;
      }
    }
  }
  return true;
}

// Renders the ball lens `medium` over the split plane and judges every pixel against the
// sharp-sphere trace, away from a rim band of half-width `rimBand` (world units); the share of
// judged pixels that agree inside and outside the silhouette must reach `inside` and `outside`.
void ExpectInvertedPlane(vtkImageData* medium, double rimBand, double inside, double outside)
{
  Scene scene(medium);
  vtkNew<vtkActor> plane;
  AddSplitPlane(scene.Renderer, plane);
  UseParallelCamera(scene.Renderer);
  AddLightAlongView(scene.Renderer);
  scene.Mapper->SetExposure(4.0);
  vtkSmartPointer<vtkImageData> image = scene.Capture();
  ASSERT_EQ(scene.Mapper->GetActorSurfaceCollector()->GetNumberOfActors(), 1);

  int judged[2] = { 0, 0 }, agreed[2] = { 0, 0 }, dark = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      const double x = (2.0 * (i + 0.5) / Size - 1.0) * 0.5,
                   y = (2.0 * (j + 0.5) / Size - 1.0) * 0.5;
      const double b = std::hypot(x, y);
      double hit[2];
      TracedPlaneHit(x, y, hit);
      const double hitX = hit[0];
      if (std::abs(b - Radius) < rimBand || std::abs(hitX) < 0.06 ||
        !FootprintSeesOneColour(x, y, hitX < 0))
      {
        continue;
      }
      const unsigned char* rgb = Pixel(image, i, j);
      if (rgb[0] + rgb[2] < 12)
      {
        ++dark;
        continue;
      }
      const int in = b < Radius ? 1 : 0;
      ++judged[in];
      agreed[in] += (rgb[0] > rgb[2]) == (hitX < 0);
    }
  }
  std::cout << "inside the silhouette " << agreed[1] << " of " << judged[1]
            << " pixels agree with the sharp-sphere trace, outside " << agreed[0] << " of "
            << judged[0] << "; " << dark << " dark pixels\n";
  EXPECT_GT(judged[1], 300);
  EXPECT_GE(agreed[1], inside * judged[1]);
  EXPECT_GE(agreed[0], outside * judged[0]);
  EXPECT_LT(dark, Size * Size / 10);
  // Inverted: right of the centre inside the lens shows the red (left) half, and vice versa.
  const unsigned char* right = Pixel(image, Size / 2 + 14, Size / 2);
  const unsigned char* left = Pixel(image, Size / 2 - 15, Size / 2);
  EXPECT_GT(right[0], right[2] + 20);
  EXPECT_GT(left[2], left[0] + 20);
  // Outside the lens the plane is seen directly: blue on the right.
  const unsigned char* outsidePixel = Pixel(image, Size - 4, Size / 2);
  EXPECT_GT(outsidePixel[2], outsidePixel[0] + 20);
}
}

TEST(MapperSurfaces, BallLensInvertsAPlaneActor)
{
  ExpectInvertedPlane(BallLens(), RimBand, 0.95, 0.98);
}

TEST(MapperSurfaces, ExactGlassBallInvertsAPlaneActorAsTheSharpTrace)
{
  ExpectInvertedPlane(ExactBallLens(), 0.012, 0.99, 0.99);
}

TEST(MapperSurfaces, MovingAnActorRelightsWithoutRebuildingTheMedium)
{
  Scene scene;
  vtkNew<vtkActor> plane;
  AddSplitPlane(scene.Renderer, plane);
  // And a plain actor (no scalars) out of view: the set's own mapping of its colours creates
  // its mapper's default lookup table, which used to count as a change on the next render.
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(5, 5, -1);
  ball->SetRadius(0.1);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> plain;
  plain->SetMapper(ballMapper);
  scene.Renderer->AddActor(plain);
  UseParallelCamera(scene.Renderer);
  AddLightAlongView(scene.Renderer);
  scene.Window->Render();
  vtkRefractaActorSurfaces* actors = scene.Mapper->GetActorSurfaceCollector();
  const int lightRuns = scene.Mapper->GetNumberOfLightPassRuns();
  const int mediumBuilds = scene.Mapper->GetNumberOfMediumBuilds();
  const int setBuilds = actors->GetSurfaces()->GetNumberOfBuilds();
  const int rebuilds = actors->GetNumberOfRebuilds();
  EXPECT_EQ(lightRuns, 1);
  EXPECT_EQ(rebuilds, 1);

  scene.Window->Render(); // nothing changed: nothing re-runs
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), lightRuns);
  EXPECT_EQ(actors->GetNumberOfRebuilds(), rebuilds);

  plane->SetPosition(0.1, 0.0, -0.05);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), lightRuns + 1) << "a moved actor re-lights";
  EXPECT_EQ(scene.Mapper->GetNumberOfMediumBuilds(), mediumBuilds) << "but keeps the medium";
  EXPECT_EQ(actors->GetSurfaces()->GetNumberOfBuilds(), setBuilds + 1);
  EXPECT_EQ(actors->GetNumberOfRebuilds(), rebuilds) << "same actors: the set is not rebuilt";

  scene.Renderer->GetActiveCamera()->Azimuth(5);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), lightRuns + 1) << "a camera move only views";

  // Translucent: no longer a surface (the scene then has none, which re-plans).
  plane->GetProperty()->SetOpacity(0.5);
  plain->GetProperty()->SetOpacity(0.5);
  scene.Window->Render();
  EXPECT_EQ(actors->GetNumberOfActors(), 0);
  EXPECT_EQ(scene.Mapper->GetPipeline()->GetSurfaces(), nullptr);
}

TEST(MapperSurfaces, BentRaysSeeTheRenderersGradientBackground)
{
  Scene scene;
  scene.Renderer->GradientBackgroundOn();
  scene.Renderer->SetBackground(1, 0, 0);  // bottom
  scene.Renderer->SetBackground2(0, 0, 1); // top
  scene.Renderer->AutomaticLightCreationOff();
  scene.Renderer->RemoveAllLights();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 0, 2.5);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  camera->SetClippingRange(0.5, 6);
  vtkSmartPointer<vtkImageData> image = scene.Capture();
  EXPECT_EQ(scene.Mapper->GetBackgroundConverter()->GetLastSource(),
    vtkRefractaRendererBackground::GRADIENT);

  const double t = std::tan(vtkMath::RadiansFromDegrees(15.0));
  int judged = 0, worst = 0, over = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int i = 0; i < Size; ++i)
    {
      const double sx = 2.0 * (i + 0.5) / Size - 1.0, sy = 2.0 * (j + 0.5) / Size - 1.0;
      double o[3] = { 0, 0, 2.5 }, d[3] = { sx * t, sy * t, -1 };
      vtkMath::Normalize(d);
      const double b =
        std::sqrt(std::max(vtkMath::Dot(o, o) - std::pow(vtkMath::Dot(o, d), 2), 0.0));
      if (std::abs(b - Radius) < RimBand)
      {
        continue;
      }
      TraceSharpSphere(o, d);
      // The viewport height at which this camera sees direction d (clamped), and the gradient.
      const double y =
        d[2] < 0 ? std::min(std::max(d[1] / (-d[2] * t), -1.0), 1.0) : (d[1] > 0 ? 1.0 : -1.0);
      const double f = 0.5 * (y + 1.0);
      const unsigned char* rgb = Pixel(image, i, j);
      const int error =
        std::max(std::abs(rgb[0] - 255.0 * (1 - f)), std::abs(rgb[2] - 255.0 * f)) + 0.5;
      worst = std::max(worst, error);
      over += error > 8;
      ++judged;
    }
  }
  std::cout << judged << " pixels judged, " << over << " off by more than 8 / 255, worst " << worst
            << " / 255\n";
  EXPECT_GT(judged, Size * Size / 2);
  EXPECT_LE(over, judged / 100);
  EXPECT_LE(worst, 20);
  // Inverted: above the centre, inside the lens, the bottom colour (red) dominates.
  const unsigned char* top = Pixel(image, Size / 2, Size / 2 + 12);
  EXPECT_GT(top[0], top[2] + 40);
}

TEST(MapperSurfaces, BackgroundIlluminatesLightsTheActors)
{
  // No lights, a uniform grey background: the plane actor behind the lens is lit only when the
  // background illuminates. A uniform sky of radiance L gives an unoccluded plane pi L on each
  // side (the atlas holds the sum, 2 pi L); the clear lens in front bends the sky but keeps it
  // uniform.
  Scene scene;
  vtkNew<vtkActor> plane;
  AddSplitPlane(scene.Renderer, plane);
  UseParallelCamera(scene.Renderer);
  scene.Renderer->AutomaticLightCreationOff();
  scene.Renderer->RemoveAllLights();
  scene.Renderer->SetBackground(0.5, 0.5, 0.5);
  scene.Mapper->SetNumberOfPhotons(1 << 15); // the mean over the plane needs few
  EXPECT_FALSE(scene.Mapper->GetBackgroundIlluminates());
  scene.Window->Render();
  const int runs = scene.Mapper->GetNumberOfLightPassRuns();
  scene.Mapper->BackgroundIlluminatesOn();
  EXPECT_TRUE(scene.Mapper->GetPipeline()->GetBackgroundIlluminates());
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), runs + 1);
  EXPECT_TRUE(scene.Mapper->GetPipeline()->GetPhotonTracer()->GetUsedEnvironment());
  vtkImageData* lighting = scene.Mapper->GetPipeline()->GetLighting();
  ASSERT_NE(lighting, nullptr);
  vtkDataArray* e =
    lighting->GetFieldData()->GetArray(vtkRefractaLightingVolume::SurfaceIrradianceName());
  ASSERT_NE(e, nullptr);
  vtkRefractaSurfaceSet* set = scene.Mapper->GetActorSurfaceCollector()->GetSurfaces();
  // Each side of the floor sees a hemisphere of the uniform sky: E = pi L on each.
  const double radiance = scene.Mapper->GetPipeline()->GetViewPass()->GetBackgroundColor()[0];
  for (int side = 0; side < vtkRefractaLightingVolume::NUMBER_OF_SURFACE_SIDES; ++side)
  {
    double flux = 0, area = 0;
    for (vtkIdType t = 0; t < e->GetNumberOfTuples(); ++t)
    {
      flux +=
        vtkRefractaLightingVolume::GetSurfaceSideValue(e, t, side, 0, 3) * set->GetTexelAreas()[t];
      area += set->GetTexelAreas()[t];
    }
    std::cout << "mean irradiance on side " << side << ": " << flux / area << " = "
              << flux / area / (vtkMath::Pi() * radiance) << " x pi L (L = " << radiance << ")"
              << std::endl;
    EXPECT_NEAR(flux / area / (vtkMath::Pi() * radiance), 1.0, 0.03) << "side " << side;
  }
  scene.Renderer->SetBackground(0.25, 0.25, 0.25);
  scene.Window->Render();
  EXPECT_EQ(scene.Mapper->GetNumberOfLightPassRuns(), runs + 2) << "a new sky re-lights";
}

// The renderer's equirectangular environment texture reaches the view pass as the very image the
// user gave (no copy, no resampling: full resolution), so a procedural checkerboard
// (vtkRefractaEnvironmentMap::MakeChecker) stays procedural behind the mapper too, and so does a
// large image environment.
TEST(MapperSurfaces, EnvironmentTextureReachesTheViewPassUnchanged)
{
  const double color1[3] = { 0.9, 0.9, 0.9 }, color2[3] = { 0.1, 0.1, 0.1 };
  vtkSmartPointer<vtkImageData> checker =
    vtkRefractaEnvironmentMap::MakeChecker(24, 12, color1, color2);
  vtkNew<vtkImageData> large;
  large->SetDimensions(4096, 2048, 1);
  large->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (vtkImageData* image : { checker.Get(), static_cast<vtkImageData*>(large) })
  {
    vtkNew<vtkTexture> texture;
    texture->SetInputData(image);
    vtkNew<vtkRenderer> renderer;
    renderer->UseImageBasedLightingOn();
    renderer->SetEnvironmentTexture(texture);
    vtkNew<vtkCamera> camera;
    vtkNew<vtkRefractaViewPass> pass;
    vtkNew<vtkRefractaRendererBackground> background;
    background->Apply(renderer, camera, pass);
    EXPECT_EQ(background->GetLastSource(), vtkRefractaRendererBackground::ENVIRONMENT_TEXTURE);
    EXPECT_EQ(pass->GetEnvironmentMap(), image);
  }
  int squares[2];
  double c1[3], c2[3];
  EXPECT_TRUE(vtkRefractaEnvironmentMap::GetChecker(checker, squares, c1, c2));
}

// An opaque block (extinction 60 per unit over 0.6: optical depth 36) floats above a floor actor
// under a light straight down, seen obliquely so that its shadow on the floor lies outside the
// block's screen footprint. With ShadeActorsEverywhere (default) the floor is shaded by the light
// passes wherever it is drawn: the shadow shows (the floor's pixels there are dark) and the lit
// floor matches VTK's own diffuse shading on both sides of the footprint's outline (directional
// light in VTK units: E rho / pi = I rho cos theta). Off: VTK's shading stays outside the
// footprint, and the shadow is not shown.
TEST(MapperSurfaces, TheMediumsShadowOnAnActorShowsOutsideItsFootprint)
{
  const double origin[3] = { -0.3, -0.3, 0.9 };
  auto block = refracta_test::MakeGrid(13, 13, 13, 0.05, origin);
  refracta_test::AddConstant(block, "Extinction", 3, 60.0, 60.0, 60.0);
  Scene scene(block);
  vtkNew<vtkPlaneSource> floor;
  floor->SetOrigin(-2, -2, 0);
  floor->SetPoint1(2, -2, 0);
  floor->SetPoint2(-2, 2, 0);
  vtkNew<vtkPolyDataMapper> floorMapper;
  floorMapper->SetInputConnection(floor->GetOutputPort());
  vtkNew<vtkActor> floorActor;
  floorActor->SetMapper(floorMapper);
  floorActor->GetProperty()->SetDiffuseColor(0.8, 0.8, 0.8);
  floorActor->GetProperty()->SetAmbient(0.0);
  floorActor->GetProperty()->SetSpecular(0.0);
  scene.Renderer->AddActor(floorActor);
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(0, 0, 5);
  light->SetFocalPoint(0, 0, 0);
  light->SetIntensity(0.9);
  scene.Renderer->AutomaticLightCreationOff();
  scene.Renderer->RemoveAllLights();
  scene.Renderer->AddLight(light);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->ParallelProjectionOn();
  camera->SetParallelScale(1.2);
  camera->SetFocalPoint(0, 0, 0.6);
  camera->SetPosition(0, -4, 4.6); // looking down at 45 degrees from -y
  camera->SetViewUp(0, 1, 1);
  camera->SetClippingRange(0.5, 12);
  scene.Mapper->SetNumberOfPhotons(1 << 18);

  // The floor points' pixels (0, 0, 0): in the shadow; (0.9, 0, 0) and (-0.9, 0, 0): lit.
  auto pixelOf = [&](double x, double y, double z)
  {
    scene.Renderer->SetWorldPoint(x, y, z, 1.0);
    scene.Renderer->WorldToDisplay();
    const double* d = scene.Renderer->GetDisplayPoint();
    return std::make_pair(static_cast<int>(d[0]), static_cast<int>(d[1]));
  };
  auto grey = [&](vtkImageData* image, std::pair<int, int> at)
  {
    // The mean over 5 x 5 pixels (photon noise).
    double sum = 0;
    for (int dj = -2; dj <= 2; ++dj)
    {
      for (int di = -2; di <= 2; ++di)
      {
        sum += Pixel(image, at.first + di, at.second + dj)[1];
      }
    }
    return sum / 25.0;
  };
  for (bool everywhere : { true, false })
  {
    scene.Mapper->SetShadeActorsEverywhere(everywhere);
    vtkSmartPointer<vtkImageData> image = scene.Capture();
    const auto shadow = pixelOf(0, 0, 0), left = pixelOf(-0.9, 0, 0), right = pixelOf(0.9, 0, 0);
    ASSERT_GT(shadow.second, 8);
    ASSERT_LT(shadow.second, Size - 8);
    // The block's footprint: the shadow's pixel sees the floor, not the block.
    const auto blockLow = pixelOf(0, -0.3, 0.9);
    ASSERT_GT(blockLow.second, shadow.second + 4) << "the block is drawn above the shadow";
    const double lit = 0.5 * (grey(image, left) + grey(image, right));
    const double dark = grey(image, shadow);
    const double vtkShading = 255 * 0.9 * 0.8; // I rho cos(0)
    std::cout << (everywhere ? "everywhere" : "where covered") << ": shadow " << dark
              << ", lit floor " << lit << " (VTK's shading " << vtkShading << ")\n";
    EXPECT_NEAR(lit, vtkShading, 0.08 * vtkShading) << "the lit floor as VTK shades it";
    if (everywhere)
    {
      EXPECT_LT(dark, 0.05 * lit) << "the shadow shows outside the medium's footprint";
    }
    else
    {
      EXPECT_GT(dark, 0.9 * lit) << "VTK's own shading outside the footprint";
    }
  }
}

// A clear glass ball (voxelized with exact interfaces: Fresnel-split legs) over a uniform
// background shows nothing but that background: the scene's light left after taking out the
// background's part is float round-off. Automatic exposure must stay 1 (metering the round-off
// gave 6e7, the ball drawn as speckle) and the ball's centre is the background.
TEST(MapperSurfaces, AClearGlassBallMetersNoExposure)
{
  Scene scene(ExactBallLens());
  UseParallelCamera(scene.Renderer);
  AddLightAlongView(scene.Renderer);
  scene.Renderer->SetBackground(0.1, 0.1, 0.15);
  scene.Mapper->AutomaticExposureOn();
  vtkSmartPointer<vtkImageData> image = scene.Capture();
  EXPECT_EQ(scene.Mapper->GetLastExposure(), 1.0);
  const unsigned char* centre = Pixel(image, Size / 2, Size / 2);
  EXPECT_NEAR(centre[0], 25.5, 1.5);
  EXPECT_NEAR(centre[2], 38.25, 1.5);
}

// A textured actor's surface takes its texture (sampled at its texture coordinates, vtkTexture's
// Repeat and Interpolate), and a new texture image rebuilds the actor set.
TEST(MapperSurfaces, ATexturedActorTakesItsTexture)
{
  Scene scene;
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1.5, -1.5, PlaneZ);
  plane->SetPoint1(1.5, -1.5, PlaneZ);
  plane->SetPoint2(-1.5, 1.5, PlaneZ);
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 1, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* pixels = static_cast<unsigned char*>(image->GetScalarPointer());
  const unsigned char values[6] = { 255, 0, 0, 0, 0, 255 }; // red | blue
  std::copy(values, values + 6, pixels);
  vtkNew<vtkTexture> texture;
  texture->SetInputData(image);
  texture->RepeatOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->SetTexture(texture);
  scene.Renderer->AddActor(actor);
  UseParallelCamera(scene.Renderer);
  AddLightAlongView(scene.Renderer);
  scene.Window->Render();
  vtkRefractaActorSurfaces* actors = scene.Mapper->GetActorSurfaceCollector();
  ASSERT_EQ(actors->GetNumberOfActors(), 1);
  vtkRefractaSurfaceMaterial* material = actors->GetSurfaces()->GetMaterial(0);
  EXPECT_EQ(material->GetTexture(), image.GetPointer());
  EXPECT_FALSE(material->GetTextureRepeat());
  double rgb[3];
  ASSERT_TRUE(material->EvaluateTexture(0.25, 0.5, rgb));
  EXPECT_EQ(rgb[0], 1.0);
  ASSERT_TRUE(material->EvaluateTexture(0.75, 0.5, rgb));
  EXPECT_EQ(rgb[2], 1.0);
  const int rebuilds = actors->GetNumberOfRebuilds();
  scene.Window->Render();
  EXPECT_EQ(actors->GetNumberOfRebuilds(), rebuilds) << "nothing changed";
  pixels[0] = 0;
  image->Modified();
  scene.Window->Render();
  EXPECT_EQ(actors->GetNumberOfRebuilds(), rebuilds + 1) << "a new texture image";
}

// A vtkSkybox is a vtkActor with an opaque quad, but it is the background: neither a surface
// the passes light (an outside review saw it drawn as a grey quad at the medium's back face)
// nor foreign geometry; the plane beside it is taken.
TEST(MapperSurfaces, ASkyboxIsTheBackgroundNotASurface)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkSkybox> sky;
  const double white[3] = { 1, 1, 1 }, black[3] = { 0, 0, 0 };
  vtkNew<vtkTexture> texture;
  texture->SetInputData(vtkRefractaEnvironmentMap::MakeChecker(8, 4, white, black));
  sky->SetTexture(texture);
  sky->SetProjectionToSphere();
  renderer->AddActor(sky);
  vtkNew<vtkPlaneSource> plane;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  mapper->Update();
  vtkNew<vtkActor> floor;
  floor->SetMapper(mapper);
  renderer->AddActor(floor);
  vtkNew<vtkRefractaActorSurfaces> actors;
  actors->Update(renderer, nullptr);
  EXPECT_EQ(actors->GetNumberOfActors(), 1);
  EXPECT_EQ(actors->GetNumberOfForeignProps(), 0);
}

// An actor drawn as wireframe or points (a cage around a volume) is VTK's drawing, composited by
// depth, not a surface: taken as one it hid the whole medium inside it (outside review).
TEST(MapperSurfaces, WireframeAndPointsActorsAreNotSurfaces)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkPlaneSource> plane;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkActor> cage;
  cage->SetMapper(mapper);
  renderer->AddActor(cage);
  vtkNew<vtkRefractaActorSurfaces> actors;
  for (int representation : { VTK_WIREFRAME, VTK_POINTS, VTK_SURFACE })
  {
    cage->GetProperty()->SetRepresentation(representation);
    actors->Update(renderer, nullptr);
    const bool surface = representation == VTK_SURFACE;
    EXPECT_EQ(actors->GetNumberOfActors(), surface ? 1 : 0) << representation;
    EXPECT_EQ(actors->GetNumberOfForeignProps(), surface ? 0 : 1) << representation;
  }
}

// A visible vtkSkybox (Sphere projection) is what VTK draws behind everything: its texture is
// what bent rays see, about its floor plane's normal and FloorRight, before the renderer's
// environment texture (before session 23 a skybox without image-based lighting was not seen).
TEST(MapperSurfaces, BentRaysSeeTheSkybox)
{
  const double white[3] = { 1, 1, 1 }, black[3] = { 0, 0, 0 };
  vtkSmartPointer<vtkImageData> skyImage =
    vtkRefractaEnvironmentMap::MakeChecker(8, 4, white, black);
  vtkSmartPointer<vtkImageData> other = vtkRefractaEnvironmentMap::MakeChecker(4, 2, black, white);
  vtkNew<vtkTexture> skyTexture, environment;
  skyTexture->SetInputData(skyImage);
  environment->SetInputData(other);
  vtkNew<vtkRenderer> renderer;
  renderer->UseImageBasedLightingOn();
  renderer->SetEnvironmentTexture(environment);
  vtkNew<vtkSkybox> sky;
  sky->SetTexture(skyTexture);
  sky->SetProjectionToSphere();
  sky->SetFloorPlane(0, 0, 1, 0);
  sky->SetFloorRight(0, 1, 0);
  renderer->AddActor(sky);
  vtkNew<vtkCamera> camera;
  vtkNew<vtkRefractaViewPass> pass;
  vtkNew<vtkRefractaRendererBackground> background;
  background->Apply(renderer, camera, pass);
  EXPECT_EQ(background->GetLastSource(), vtkRefractaRendererBackground::SKYBOX);
  EXPECT_EQ(pass->GetEnvironmentMap(), skyImage.Get());
  EXPECT_EQ(pass->GetEnvironmentUp()[2], 1.0);
  EXPECT_EQ(pass->GetEnvironmentRight()[1], 1.0);
  // Hidden, or with a projection that is not converted: the environment texture again.
  sky->VisibilityOff();
  background->Apply(renderer, camera, pass);
  EXPECT_EQ(background->GetLastSource(), vtkRefractaRendererBackground::ENVIRONMENT_TEXTURE);
  EXPECT_EQ(pass->GetEnvironmentMap(), other.Get());
  sky->VisibilityOn();
  sky->SetProjectionToCube();
  background->Apply(renderer, camera, pass);
  EXPECT_NE(background->GetLastSource(), vtkRefractaRendererBackground::SKYBOX);
  EXPECT_NE(pass->GetEnvironmentMap(), skyImage.Get());
}
