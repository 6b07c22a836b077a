// vtkRefractaRenderPipeline with opaque surfaces: a clear glass ball over a floor needs the photon
// pass only because of the floor (the plan turns SurfaceLighting on and says why; without the
// floor no light pass runs); moving the floor re-runs the light passes and the view, never the
// plan's medium stage; removing the surfaces re-plans and drops the photon pass again.
// The direct light on surfaces by light rays (DirectSurfaceLightByRays): exact under an
// absorbing cube's shadow, the floor's flux unchanged under a glass ball (its caustic stays the
// photons'), and photons alone where the medium refracts. A lamp inside a closed box lights its
// inner faces only: the atlas keeps the two sides of a texel apart, by photons and by rays. Fog
// behind a wall stays dark: deposits and the view's lookups keep to their side of it.
#include "vtkCamera.h"
#include "vtkCubeSource.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <string>

namespace
{
// Channel c of a texel's irradiance on both sides together (the flux that arrived on it / area).
double BothSides(vtkDataArray* irradiance, vtkIdType texel, int c)
{
  return vtkRefractaLightingVolume::GetSurfaceSideValue(
           irradiance, texel, vtkRefractaLightingVolume::FRONT_SIDE, c, 3) +
    vtkRefractaLightingVolume::GetSurfaceSideValue(
      irradiance, texel, vtkRefractaLightingVolume::BACK_SIDE, c, 3);
}

// A clear glass ball (n up to 1.5, nothing absorbs or scatters) in a 24^3 unit box.
vtkSmartPointer<vtkImageData> GlassBall()
{
  const int n = 24;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  vtkNew<vtkFloatArray> idx;
  idx->SetName("RefractiveIndex");
  idx->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    const double r = std::sqrt(
      (p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5) + (p[2] - 0.5) * (p[2] - 0.5));
    idx->SetValue(id, static_cast<float>(1.0 + 0.25 * (1.0 - std::tanh((r - 0.3) / 0.05))));
  }
  image->GetPointData()->AddArray(idx);
  return image;
}
}

TEST(PipelineSurfaces, FloorTurnsOnPhotonsAndMovingItKeepsThePlan)
{
  vtkNew<vtkRefractaRenderPipeline> pipeline;
  pipeline->SetMedium(GlassBall());
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(0.5, 3.0, 0.5);
  sun->SetFocalPoint(0.5, 0.5, 0.5);
  pipeline->AddLight(sun);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.5, 1.5, 3.0);
  camera->SetFocalPoint(0.5, 0.3, 0.5);
  pipeline->SetCamera(camera);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 14);

  // Without surfaces nothing scatters: no light pass.
  ASSERT_TRUE(pipeline->Render(32, 24));
  EXPECT_FALSE(pipeline->GetEffectPlan()->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_FALSE(pipeline->GetEffectPlan()->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 0);

  // A floor below the ball: the plan turns surface lighting on and says so; the photon pass runs.
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-1, -0.2, -1);
  plane->SetPoint1(2, -0.2, -1);
  plane->SetPoint2(-1, -0.2, 2);
  plane->Update();
  vtkNew<vtkMatrix4x4> placement;
  vtkNew<vtkRefractaSurfaceSet> surfaces;
  surfaces->AddSurface(plane->GetOutput(), nullptr, placement);
  pipeline->SetSurfaces(surfaces);
  ASSERT_TRUE(pipeline->Render(32, 24));
  vtkEffectPlan* plan = pipeline->GetEffectPlan();
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_NE(std::string(plan->GetReason(vtkEffectPlan::SURFACE_LIGHTING)).find("1 surface(s)"),
    std::string::npos)
    << plan->GetReason(vtkEffectPlan::SURFACE_LIGHTING);
  EXPECT_NE(plan->GetSummary().find("SurfaceLighting on"), std::string::npos);
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 1);
  EXPECT_TRUE(pipeline->GetPhotonTracer()->GetUsedSurfaces());
  vtkDataArray* irradiance = pipeline->GetPhotonTracer()->GetOutput()->GetFieldData()->GetArray(
    vtkRefractaLightingVolume::SurfaceIrradianceName());
  ASSERT_NE(irradiance, nullptr);
  EXPECT_EQ(irradiance->GetNumberOfTuples(), surfaces->GetNumberOfTexels());
  const int plans = pipeline->GetNumberOfPlanRuns();
  const int media = pipeline->GetNumberOfMediumUpdates();

  // Nothing changed: nothing re-runs but the image is returned.
  ASSERT_TRUE(pipeline->Render(32, 24));
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 1);

  // Moving the floor: light passes again, same plan, same medium on the device.
  placement->SetElement(1, 3, -0.1);
  ASSERT_TRUE(pipeline->Render(32, 24));
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 2);
  EXPECT_EQ(pipeline->GetNumberOfPlanRuns(), plans);
  EXPECT_EQ(pipeline->GetNumberOfMediumUpdates(), media);
  EXPECT_TRUE(pipeline->GetPhotonTracer()->GetLastRunReusedMedium());
  EXPECT_FALSE(pipeline->GetPhotonTracer()->GetLastRunReusedSurfaces());

  // Removing the surfaces re-plans: no light pass is needed any more.
  surfaces->RemoveAllSurfaces();
  ASSERT_TRUE(pipeline->Render(32, 24));
  EXPECT_EQ(pipeline->GetNumberOfPlanRuns(), plans + 1);
  EXPECT_FALSE(pipeline->GetEffectPlan()->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), 2);
}

namespace
{
// An absorbing, non-scattering cube (sigma_t = (1, 2, 3) per unit, 24^3 voxels of 1/23: the box
// is 24/23 high) over a floor at y = -0.2 under a sun shining straight down (E = 1): the floor's
// direct irradiance is exp(-sigma 24/23) in the cube's shadow and 1 outside it.
struct ShadowScene
{
  vtkNew<vtkRefractaRenderPipeline> Pipeline;
  vtkNew<vtkRefractaSurfaceSet> Surfaces;
  vtkNew<vtkLight> Sun;
  vtkNew<vtkCamera> Camera;

  // `albedo`: the cube also scatters (then light rays serve its single scattering once no
  // surface is lit).
  explicit ShadowScene(double albedo = 0.0)
  {
    const int n = 24;
    auto cube = vtkSmartPointer<vtkImageData>::New();
    cube->SetDimensions(n, n, n);
    cube->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
    vtkNew<vtkFloatArray> extinction;
    extinction->SetName("Extinction");
    extinction->SetNumberOfComponents(3);
    extinction->SetNumberOfTuples(cube->GetNumberOfPoints());
    for (vtkIdType id = 0; id < cube->GetNumberOfPoints(); ++id)
    {
      extinction->SetTuple3(id, 1.0, 2.0, 3.0);
    }
    cube->GetPointData()->AddArray(extinction);
    if (albedo > 0)
    {
      vtkNew<vtkFloatArray> a;
      a->SetName("Albedo");
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(cube->GetNumberOfPoints());
      a->Fill(albedo);
      cube->GetPointData()->AddArray(a);
    }
    this->Pipeline->SetMedium(cube);
    this->Sun->SetLightTypeToSceneLight();
    this->Sun->SetPositional(false);
    this->Sun->SetPosition(0.5, 3.0, 0.5);
    this->Sun->SetFocalPoint(0.5, 0.5, 0.5);
    this->Pipeline->AddLight(this->Sun);
    this->Camera->SetPosition(0.5, 1.5, 3.0);
    this->Camera->SetFocalPoint(0.5, 0.3, 0.5);
    this->Pipeline->SetCamera(this->Camera);
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(-1, -0.2, -1);
    plane->SetPoint1(2, -0.2, -1);
    plane->SetPoint2(-1, -0.2, 2);
    plane->Update();
    this->Surfaces->AddSurface(plane->GetOutput());
    this->Surfaces->SetTexelSize(0.05);
    this->Pipeline->SetSurfaces(this->Surfaces);
  }

  // The floor's texels: irradiance (RGB, both sides) and centroid (x, z), from the pipeline's
  // lighting.
  void Texels(std::vector<std::array<double, 5>>& texels)
  {
    vtkDataArray* irradiance = this->Pipeline->GetLighting()->GetFieldData()->GetArray(
      vtkRefractaLightingVolume::SurfaceIrradianceName());
    ASSERT_NE(irradiance, nullptr);
    const std::vector<int>& info = this->Surfaces->GetTriangleInfo();
    const std::vector<double>& tri = this->Surfaces->GetBVH()->GetTriangles();
    const double* origin = this->Surfaces->GetBVH()->GetFrameOrigin();
    texels.clear();
    for (size_t k = 0; 4 * k < info.size(); ++k)
    {
      const int first = info[4 * k], n = info[4 * k + 1];
      const double* v = &tri[9 * k];
      for (int t = 0; t < n * n; ++t)
      {
        double uv[8];
        vtkRefractaSurfaceSet::GetTexelSamplePoints(t, n, uv);
        std::array<double, 5> row;
        for (int c = 0; c < 3; ++c)
        {
          row[c] = BothSides(irradiance, first + t, c);
        }
        for (int a : { 0, 2 })
        {
          row[3 + a / 2] = origin[a] + v[a] + uv[0] * (v[3 + a] - v[a]) + uv[1] * (v[6 + a] - v[a]);
        }
        texels.push_back(row);
      }
    }
  }
};

// Whether the floor point (x, z) is in the cube's shadow (+1), out of it (-1), or within `m` of
// its edge (0).
int InShadow(double x, double z, double m)
{
  const double lo = -0.5 / 23, hi = 1.0 + 0.5 / 23;
  if (x > lo + m && x < hi - m && z > lo + m && z < hi - m)
  {
    return 1;
  }
  return (x < lo - m || x > hi + m || z < lo - m || z > hi + m) ? -1 : 0;
}
}

// Straight light: the photons leave the floor's direct light out and the light rays add it, so
// every texel is the analytic irradiance (to float rounding: nothing else lights a lone floor),
// where photons alone scatter around it.
TEST(PipelineSurfaces, DirectLightOnSurfacesIsExactByLightRays)
{
  ShadowScene scene;
  scene.Pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 16);
  ASSERT_TRUE(scene.Pipeline->Render(32, 24));
  EXPECT_TRUE(scene.Pipeline->GetDirectSurfaceLightByRays());
  EXPECT_TRUE(scene.Pipeline->GetLastDirectSurfaceLightByRays());
  EXPECT_TRUE(scene.Pipeline->GetPhotonTracer()->GetLastSkippedDirectSurfaceLight());
  std::vector<std::array<double, 5>> texels;
  scene.Texels(texels);
  const double sigma[3] = { 1, 2, 3 }, depth = 24.0 / 23;
  int shadowed = 0, lit = 0;
  double worst = 0;
  for (const auto& t : texels)
  {
    const int where = InShadow(t[3], t[4], 0.06);
    for (int c = 0; c < 3 && where != 0; ++c)
    {
      const double expected = where > 0 ? std::exp(-sigma[c] * depth) : 1.0;
      worst = std::max(worst, std::abs(t[c] - expected) / expected);
    }
    shadowed += where > 0;
    lit += where < 0;
  }
  std::cout << texels.size() << " texels, " << shadowed << " in the shadow, " << lit
            << " lit: worst relative error " << worst << "\n";
  EXPECT_GT(shadowed, 100);
  EXPECT_GT(lit, 1000);
  EXPECT_LT(worst, 1e-4);

  // Photons alone: the same means within their noise, texel by texel far from it.
  scene.Pipeline->DirectSurfaceLightByRaysOff();
  ASSERT_TRUE(scene.Pipeline->Render(32, 24));
  EXPECT_FALSE(scene.Pipeline->GetLastDirectSurfaceLightByRays());
  scene.Texels(texels);
  double litSum = 0, litSquares = 0;
  for (const auto& t : texels)
  {
    if (InShadow(t[3], t[4], 0.06) < 0)
    {
      litSum += t[1];
      litSquares += t[1] * t[1];
    }
  }
  const double mean = litSum / lit, spread = std::sqrt(litSquares / lit - mean * mean);
  std::cout << "photons alone, lit floor: mean " << mean << ", texel spread " << spread << "\n";
  EXPECT_NEAR(mean, 1.0, 0.02);
  EXPECT_GT(spread, 0.05); // what the light rays remove
}

// Glass between the light and the floor: the light rays stop at it (its light is the photons'
// caustic), so the split must give the floor the photons' total flux, within their noise.
TEST(PipelineSurfaces, DirectLightByRaysKeepsTheFloorsFluxUnderGlass)
{
  ShadowScene scene;
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(0.5, 1.6, 0.5);
  ball->SetRadius(0.3);
  ball->SetThetaResolution(48);
  ball->SetPhiResolution(24);
  ball->Update();
  vtkNew<vtkRefractaSurfaceMaterial> glass;
  glass->SetKindToDielectric();
  glass->SetIndexInside(1.5);
  scene.Surfaces->AddSurface(ball->GetOutput(), glass);
  scene.Pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 18);
  double flux[2] = { 0, 0 };
  for (int split = 0; split <= 1; ++split)
  {
    scene.Pipeline->SetDirectSurfaceLightByRays(split != 0);
    ASSERT_TRUE(scene.Pipeline->Render(32, 24));
    EXPECT_EQ(scene.Pipeline->GetLastDirectSurfaceLightByRays(), split != 0);
    vtkDataArray* irradiance = scene.Pipeline->GetLighting()->GetFieldData()->GetArray(
      vtkRefractaLightingVolume::SurfaceIrradianceName());
    const std::vector<double>& areas = scene.Surfaces->GetTexelAreas();
    const std::vector<int>& info = scene.Surfaces->GetTriangleInfo();
    for (size_t k = 0; 4 * k < info.size(); ++k)
    {
      if (info[4 * k + 3] != 0)
      {
        continue; // glass texels hold nothing
      }
      for (int t = 0; t < info[4 * k + 1] * info[4 * k + 1]; ++t)
      {
        flux[split] += BothSides(irradiance, info[4 * k] + t, 0) * areas[info[4 * k] + t];
      }
    }
  }
  std::cout << "floor flux (red): photons " << flux[0] << ", rays + photons " << flux[1] << "\n";
  // Glass texels receive no light of either kind (they were given the fluence at the origin).
  vtkDataArray* irradiance = scene.Pipeline->GetLighting()->GetFieldData()->GetArray(
    vtkRefractaLightingVolume::SurfaceIrradianceName());
  const std::vector<int>& info = scene.Surfaces->GetTriangleInfo();
  double glassTexels = 0;
  for (size_t k = 0; 4 * k < info.size(); ++k)
  {
    for (int t = 0; info[4 * k + 3] != 0 && t < info[4 * k + 1] * info[4 * k + 1]; ++t)
    {
      glassTexels = std::max(glassTexels, std::abs(BothSides(irradiance, info[4 * k] + t, 0)));
    }
  }
  EXPECT_EQ(glassTexels, 0.0);
  EXPECT_GT(flux[0], 1.0);
  EXPECT_NEAR(flux[1] / flux[0], 1.0, 0.01);
}

// Curved photons (a refracting medium) do not fly along the light rays: photons carry it all.
TEST(PipelineSurfaces, RefractingMediumKeepsDirectLightWithThePhotons)
{
  ShadowScene scene;
  scene.Pipeline->SetMedium(GlassBall());
  scene.Pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 14);
  ASSERT_TRUE(scene.Pipeline->Render(32, 24));
  EXPECT_TRUE(scene.Pipeline->GetPhotonTracer()->GetUsedCurvedRays());
  EXPECT_FALSE(scene.Pipeline->GetPhotonTracer()->GetLastSkippedDirectSurfaceLight());
  EXPECT_FALSE(scene.Pipeline->GetLastDirectSurfaceLightByRays());
}

// Where the split would not give the photons' light it is not made: a volume placed with a
// scale (the passes assume a rigid placement), an extended light (a fixed quadrature would band
// its penumbra). And a stage that lights no surface (the floor removed, light rays serve the
// scattering cube) neither adds direct light nor fails on the last photon run's flag.
TEST(PipelineSurfaces, DirectLightByRaysOnlyWhereItMatchesThePhotons)
{
  ShadowScene scene(0.5);
  scene.Pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 14);
  ASSERT_TRUE(scene.Pipeline->Render(32, 24));
  EXPECT_TRUE(scene.Pipeline->GetLastDirectSurfaceLightByRays());

  vtkNew<vtkMatrix4x4> scaled;
  scaled->SetElement(0, 0, 2.0);
  scene.Pipeline->SetPropMatrix(scaled);
  ASSERT_TRUE(scene.Pipeline->Render(32, 24));
  EXPECT_FALSE(scene.Pipeline->GetLastDirectSurfaceLightByRays());
  scene.Pipeline->SetPropMatrix(nullptr);

  scene.Pipeline->GetPhotonTracer()->SetDirectionalLightAngularRadius(2.0);
  ASSERT_TRUE(scene.Pipeline->Render(32, 24));
  EXPECT_FALSE(scene.Pipeline->GetLastDirectSurfaceLightByRays());
  scene.Pipeline->GetPhotonTracer()->SetDirectionalLightAngularRadius(0.0);
  ASSERT_TRUE(scene.Pipeline->Render(32, 24));
  EXPECT_TRUE(scene.Pipeline->GetLastDirectSurfaceLightByRays());

  scene.Surfaces->RemoveAllSurfaces();
  ASSERT_TRUE(scene.Pipeline->Render(32, 24));
  EXPECT_FALSE(scene.Pipeline->GetEffectPlan()->IsEnabled(vtkEffectPlan::SURFACE_LIGHTING));
  EXPECT_FALSE(scene.Pipeline->GetLastDirectSurfaceLightByRays());
}

// A lamp inside a closed grey box (around a clear medium): the inner faces are lit, the outer
// faces get no light at all, by photons alone or with the direct light by rays; seen from
// outside the box is black, seen from inside its walls are lit. With one irradiance for both
// sides (before the atlas kept them apart) the outside glowed as bright as the inside.
TEST(PipelineSurfaces, LampInsideAClosedBoxLightsOnlyItsInnerFaces)
{
  const int n = 8;
  auto clear = vtkSmartPointer<vtkImageData>::New();
  clear->SetDimensions(n, n, n);
  clear->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  vtkNew<vtkFloatArray> index;
  index->SetName("RefractiveIndex");
  index->SetNumberOfTuples(clear->GetNumberOfPoints());
  index->Fill(1.0);
  clear->GetPointData()->AddArray(index);
  vtkNew<vtkRefractaRenderPipeline> pipeline;
  pipeline->SetMedium(clear);
  vtkNew<vtkLight> lamp;
  lamp->SetLightTypeToSceneLight();
  lamp->SetPositional(true);
  lamp->SetConeAngle(180.0);
  lamp->SetPosition(0.5, 0.5, 0.5);
  lamp->SetFocalPoint(0.5, 0.0, 0.5);
  pipeline->AddLight(lamp);
  vtkNew<vtkCubeSource> box;
  box->SetBounds(-0.5, 1.5, -0.5, 1.5, -0.5, 1.5);
  box->Update();
  vtkNew<vtkRefractaSurfaceMaterial> grey;
  grey->SetAlbedo(0.5, 0.5, 0.5);
  vtkNew<vtkRefractaSurfaceSet> surfaces;
  surfaces->AddSurface(box->GetOutput(), grey);
  surfaces->SetTexelSize(0.25);
  pipeline->SetSurfaces(surfaces);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 16);
  vtkNew<vtkCamera> camera;
  pipeline->SetCamera(camera);
  for (bool rays : { true, false })
  {
    pipeline->SetDirectSurfaceLightByRays(rays);
    camera->SetPosition(0.5, 0.8, 6.0); // outside, the whole box in view
    camera->SetFocalPoint(0.5, 0.5, 0.5);
    ASSERT_TRUE(pipeline->Render(48, 48));
    EXPECT_EQ(pipeline->GetLastDirectSurfaceLightByRays(), rays);
    vtkDataArray* e = pipeline->GetLighting()->GetFieldData()->GetArray(
      vtkRefractaLightingVolume::SurfaceIrradianceName());
    ASSERT_NE(e, nullptr);
    ASSERT_EQ(e->GetNumberOfComponents(), 6);
    // Each texel's outer side (where the face's winding normal points away from the lamp, or not)
    // has no light; its inner side sees the lamp.
    const std::vector<int>& info = surfaces->GetTriangleInfo();
    const std::vector<double>& tri = surfaces->GetBVH()->GetTriangles();
    const double* origin = surfaces->GetBVH()->GetFrameOrigin();
    double outer = 0, innerLeast = 1e300;
    for (size_t k = 0; 4 * k < info.size(); ++k)
    {
      const double* v = &tri[9 * k];
      double a[3], b[3], normal[3], toFace[3];
      for (int c = 0; c < 3; ++c)
      {
        a[c] = v[3 + c] - v[c];
        b[c] = v[6 + c] - v[c];
        toFace[c] = origin[c] + (v[c] + v[3 + c] + v[6 + c]) / 3 - 0.5;
      }
      normal[0] = a[1] * b[2] - a[2] * b[1];
      normal[1] = a[2] * b[0] - a[0] * b[2];
      normal[2] = a[0] * b[1] - a[1] * b[0];
      const double facing = normal[0] * toFace[0] + normal[1] * toFace[1] + normal[2] * toFace[2];
      const int outerSide =
        facing > 0 ? vtkRefractaLightingVolume::FRONT_SIDE : vtkRefractaLightingVolume::BACK_SIDE;
      for (int t = 0; t < info[4 * k + 1] * info[4 * k + 1]; ++t)
      {
        for (int c = 0; c < 3; ++c)
        {
          outer = std::max(outer,
            vtkRefractaLightingVolume::GetSurfaceSideValue(e, info[4 * k] + t, outerSide, c, 3));
          innerLeast = std::min(innerLeast,
            vtkRefractaLightingVolume::GetSurfaceSideValue(
              e, info[4 * k] + t, 1 - outerSide, c, 3));
        }
      }
    }
    EXPECT_EQ(outer, 0.0) << (rays ? "rays" : "photons") << ": light on the outer faces";
    EXPECT_GT(innerLeast, 0.0) << (rays ? "rays" : "photons") << ": an inner texel left dark";
    // From outside: the box covers the middle of the image, and it is black.
    const std::vector<float>& outside = pipeline->GetImage();
    float brightest = 0;
    for (size_t p = 0; p < outside.size(); p += 4)
    {
      brightest = std::max({ brightest, outside[p], outside[p + 1], outside[p + 2] });
    }
    EXPECT_EQ(brightest, 0.0f) << (rays ? "rays" : "photons") << ": the box glows outside";
    EXPECT_EQ(outside[4 * (24 * 48 + 24) + 3], 1.0f) << "the middle pixel sees the opaque box";
    // From inside, looking at the far wall: lit.
    camera->SetPosition(0.5, 0.5, 1.3);
    camera->SetFocalPoint(0.5, 0.5, -0.5);
    ASSERT_TRUE(pipeline->Render(16, 16));
    const std::vector<float>& inside = pipeline->GetImage();
    double sum = 0;
    for (size_t p = 0; p < inside.size(); p += 4)
    {
      sum += inside[p];
    }
    EXPECT_GT(sum / (inside.size() / 4), 0.0) << (rays ? "rays" : "photons");
    std::cout << (rays ? "rays + photons" : "photons alone") << ": outer faces' largest irradiance "
              << outer << ", inner faces' least " << innerLeast << ", brightest pixel outside "
              << brightest << ", mean red inside " << sum / (inside.size() / 4) << "\n";
  }
}

TEST(PipelineSurfaces, FogBehindAWallStaysDark)
{
  // A fog box [0, 1]^3 (24^3, sigma_t 3, albedo 0.9: multiple scattering by analog photons) split
  // by an opaque wall reaching beyond it, the lamp on one side, the camera on the other: nothing
  // there is lit, so the image is black. Two walls between voxel centres: at x = 0.53 the voxel
  // of centre 0.5217 spans the wall (the view's trilinear lookups read it from the dark side:
  // before session 26 the image's largest value was 0.058 against 6.1 seen from the lit side); at
  // x = 0.51 the voxel of centre 0.5217, on the dark side, held the deposits of the lit sliver of
  // its cell (0.076). And an oblique wall, normal (1, 1, 1) through the box's centre.
  const int n = 24;
  auto fog = vtkSmartPointer<vtkImageData>::New();
  fog->SetDimensions(n, n, n);
  fog->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  auto add = [&](const char* name, int components, double value)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(components);
    a->SetNumberOfTuples(fog->GetNumberOfPoints());
    a->Fill(value);
    fog->GetPointData()->AddArray(a);
  };
  add("RefractiveIndex", 1, 1.0);
  add("Extinction", 3, 3.0);
  add("Albedo", 3, 0.9);
  vtkNew<vtkRefractaRenderPipeline> pipeline;
  pipeline->SetMedium(fog);
  vtkNew<vtkLight> lamp;
  lamp->SetLightTypeToSceneLight();
  lamp->SetPositional(true);
  lamp->SetConeAngle(180.0);
  lamp->SetIntensity(4.0);
  pipeline->AddLight(lamp);
  vtkNew<vtkRefractaSurfaceMaterial> grey;
  grey->SetAlbedo(0.8, 0.8, 0.8);
  vtkNew<vtkRefractaSurfaceSet> surfaces;
  surfaces->SetTexelSize(0.5);
  pipeline->SetSurfaces(surfaces);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 17);
  vtkNew<vtkCamera> camera;
  camera->SetViewAngle(20);
  pipeline->SetCamera(camera);
  // The image's mean and largest value seen from `eye` towards `centre`.
  auto meanAndLargest = [&](const double eye[3], const double centre[3], double& mean)
  {
    camera->SetPosition(eye);
    camera->SetFocalPoint(centre);
    camera->SetViewUp(0, 0, 1);
    camera->OrthogonalizeViewUp();
    EXPECT_TRUE(pipeline->Render(40, 40));
    const std::vector<float>& image = pipeline->GetImage();
    double largest = 0;
    mean = 0;
    for (size_t p = 0; p < image.size(); p += 4)
    {
      for (int c = 0; c < 3; ++c)
      {
        largest = std::max(largest, static_cast<double>(image[p + c]));
        mean += image[p + c] / (0.75 * image.size());
      }
    }
    return largest;
  };
  const double third = 1.0 / std::sqrt(3.0);
  struct Wall
  {
    double Normal[3]; // towards the dark side
    double Centre[3];
  };
  for (const Wall& wall :
    { Wall{ { 1, 0, 0 }, { 0.53, 0.5, 0.5 } }, Wall{ { 1, 0, 0 }, { 0.51, 0.5, 0.5 } },
      Wall{ { third, third, third }, { 0.5, 0.5, 0.5 } } })
  {
    // A square of side 11 about the centre, normal to Normal.
    double u[3], v[3];
    const double z[3] = { 0, 0, 1 };
    vtkMath::Cross(z, wall.Normal, u);
    vtkMath::Normalize(u);
    if (!(vtkMath::Norm(u) > 0.5))
    {
      u[0] = 1;
      u[1] = u[2] = 0;
    }
    vtkMath::Cross(wall.Normal, u, v);
    double corner[3], p1[3], p2[3], lampAt[3], lit[3], dark[3];
    for (int a = 0; a < 3; ++a)
    {
      corner[a] = wall.Centre[a] - 5.5 * (u[a] + v[a]);
      p1[a] = corner[a] + 11 * u[a];
      p2[a] = corner[a] + 11 * v[a];
      lampAt[a] = wall.Centre[a] - 0.28 * wall.Normal[a];
      lit[a] = wall.Centre[a] - 2.5 * wall.Normal[a];
      dark[a] = wall.Centre[a] + 2.5 * wall.Normal[a];
    }
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(corner);
    plane->SetPoint1(p1);
    plane->SetPoint2(p2);
    plane->SetResolution(8, 8);
    plane->Update();
    surfaces->RemoveAllSurfaces();
    surfaces->AddSurface(plane->GetOutput(), grey);
    lamp->SetPosition(lampAt);
    lamp->SetFocalPoint(lampAt[0], lampAt[1] - 1, lampAt[2]);
    double litMean = 0, darkMean = 0;
    meanAndLargest(lit, wall.Centre, litMean);
    const double largest = meanAndLargest(dark, wall.Centre, darkMean);
    std::cout << "wall through (" << wall.Centre[0] << ", " << wall.Centre[1] << ", "
              << wall.Centre[2] << "), normal x " << wall.Normal[0]
              << ": seen from the lit side, mean " << litMean << "; from the dark side, largest "
              << largest << "\n";
    EXPECT_GT(litMean, 1.0);
    // Photons stop at the wall in float: a sliver of a step may round past it (1e-6 of the lit
    // side's light at most in the deposits).
    EXPECT_LT(largest, 1e-5 * litMean)
      << "light behind the wall through x = " << wall.Centre[0] << ", normal x " << wall.Normal[0];
  }
}
