// vtkRefractaRenderPipeline with a medium that carries exact dielectric interfaces
// (vtkMeshVoxelizer::EXACT_INTERFACES, its default): the pipeline adds them to the scene's
// surfaces by itself, so every pass meets the glass (photons refract at it, the plan keeps
// refraction on although grad n = 0 everywhere, the view pass shows it), exactly as if the caller
// had composed the surface set by hand; refraction forced off leaves them out; they follow the
// prop matrix; inconsistent interface arrays are an error that names them.
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkMediumMaterial.h"
#include "vtkMeshVoxelizer.h"
#include "vtkNew.h"
#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkRefractaDielectric.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSceneAnalysis.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTransform.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

namespace
{
const double BallRadius = 0.3;

// A clear glass ball (n = 1.5, radius 0.3, centred at the origin, a `resolution` x
// `resolution` / 2 sphere) in a fog of extinction `fog`, voxelized on 24^3 voxels with exact
// interfaces (the voxelizer's default).
vtkSmartPointer<vtkImageData> GlassBallMedium(int resolution = 48, double fog = 0.2)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(BallRadius);
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution / 2);
  sphere->Update();
  vtkNew<vtkMeshVoxelizer> voxelizer;
  voxelizer->AddInputData(sphere->GetOutput());
  vtkNew<vtkMediumMaterial> glass;
  glass->SetRefractiveIndex(1.5);
  voxelizer->SetMaterial(0, glass);
  vtkNew<vtkMediumMaterial> surrounding;
  surrounding->SetExtinction(fog, fog, fog);
  surrounding->SetAlbedo(0.9, 0.9, 0.9);
  voxelizer->SetSurroundingMaterial(surrounding);
  voxelizer->SetDimensions(24, 24, 24);
  voxelizer->SetBounds(-0.5, 0.5, -0.5, 0.5, -0.5, 0.5);
  voxelizer->Update();
  EXPECT_TRUE(voxelizer->GetWroteInterfaces());
  auto medium = vtkSmartPointer<vtkImageData>::New();
  medium->DeepCopy(voxelizer->GetOutput());
  return medium;
}

// A floor at y = -0.45 (inside the medium's box) of albedo `albedo` as the caller's surface set.
vtkSmartPointer<vtkRefractaSurfaceSet> Floor(double albedo = 0.8)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-0.6, -0.45, -0.6);
  plane->SetPoint1(0.6, -0.45, -0.6);
  plane->SetPoint2(-0.6, -0.45, 0.6);
  plane->Update();
  auto set = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  vtkNew<vtkRefractaSurfaceMaterial> material;
  material->SetAlbedo(albedo, albedo, albedo);
  set->AddSurface(plane->GetOutput(), material);
  return set;
}

vtkSmartPointer<vtkRefractaRenderPipeline> MakePipeline(
  vtkImageData* medium, vtkRefractaSurfaceSet* surfaces)
{
  auto pipeline = vtkSmartPointer<vtkRefractaRenderPipeline>::New();
  pipeline->SetMedium(medium);
  pipeline->SetSurfaces(surfaces);
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->SetPositional(false);
  sun->SetPosition(0.0, 3.0, 0.0);
  sun->SetFocalPoint(0.0, 0.0, 0.0);
  pipeline->AddLight(sun);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.0, 0.4, 2.0);
  camera->SetFocalPoint(0.0, -0.1, 0.0);
  pipeline->SetCamera(camera);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 14);
  pipeline->GetPhotonTracer()->SetSeed(3);
  return pipeline;
}

double FieldValue(vtkImageData* lighting, const char* name)
{
  vtkDataArray* a = lighting ? lighting->GetFieldData()->GetArray(name) : nullptr;
  double sum = 0.0;
  for (int c = 0; a && c < a->GetNumberOfComponents(); ++c)
  {
    sum += a->GetComponent(0, c);
  }
  return sum;
}
}

TEST(PipelineInterfaces, MediumInterfacesReachEveryPass)
{
  auto medium = GlassBallMedium();
  auto floor = Floor();
  auto pipeline = MakePipeline(medium, floor);
  ASSERT_TRUE(pipeline->Render(48, 32));

  // The passes saw the floor and the ball's interface, the caller's set is untouched.
  vtkRefractaSurfaceSet* scene = pipeline->GetSceneSurfaces();
  ASSERT_NE(scene, nullptr);
  EXPECT_NE(scene, floor.Get());
  EXPECT_EQ(floor->GetNumberOfSurfaces(), 1);
  EXPECT_EQ(scene->GetNumberOfSurfaces(), 2);
  EXPECT_EQ(scene->GetNumberOfNonEmptyDielectricSurfaces(), 1);
  EXPECT_EQ(pipeline->GetSceneAnalysis()->GetNumberOfInterfaceSurfaces(), 1);

  // grad n is 0 everywhere (the jump is in the interface), yet refraction stays on: the plan
  // says the interface is why, and keeps the index.
  EXPECT_EQ(pipeline->GetSceneAnalysis()->GetMaximumDisplacementInVoxels(), 0.0);
  vtkEffectPlan* plan = pipeline->GetEffectPlan();
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::REFRACTION));
  EXPECT_NE(
    std::string(plan->GetReason(vtkEffectPlan::REFRACTION)).find("dielectric"), std::string::npos)
    << plan->GetReason(vtkEffectPlan::REFRACTION);
  EXPECT_NE(pipeline->GetPlannedMedium()->GetPointData()->GetArray(
              vtkRefractaMedium::RefractiveIndexName()),
    nullptr);

  // Photons met the glass (how much of it reflects: PhotonsMeetTheBallWithFresnelWeights).
  vtkImageData* lighting = pipeline->GetLighting();
  EXPECT_GT(FieldValue(lighting, "EnergyInterfaceTransmitted"), 0.0);
  EXPECT_GT(FieldValue(lighting, "EnergyInterfaceReflected"), 0.0);

  // The same image as a caller who composed the set by hand, with a medium stripped of its
  // interface arrays (so that the pipeline adds nothing itself).
  const std::vector<float> image = pipeline->GetImage();
  auto bare = vtkSmartPointer<vtkImageData>::New();
  bare->DeepCopy(medium);
  for (const char* name : { vtkRefractaMedium::InterfacePointsName(),
         vtkRefractaMedium::InterfaceTrianglesName(), vtkRefractaMedium::InterfaceIndicesName() })
  {
    bare->GetFieldData()->RemoveArray(name);
  }
  auto byHand = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  byHand->CopySurfaces(floor);
  ASSERT_EQ(byHand->AddMediumInterfaces(medium), 1);
  auto manual = MakePipeline(bare, byHand);
  ASSERT_TRUE(manual->Render(48, 32));
  EXPECT_EQ(manual->GetSceneSurfaces(), byHand.Get());
  ASSERT_EQ(manual->GetImage().size(), image.size());
  EXPECT_TRUE(std::equal(image.begin(), image.end(), manual->GetImage().begin()));

  // Without the interfaces (the bare medium and only the floor) the ball is invisible: grad n = 0
  // and n is uniform inside it, so the image differs where the camera sees the ball.
  auto blind = MakePipeline(bare, floor);
  ASSERT_TRUE(blind->Render(48, 32));
  double difference = 0.0;
  for (size_t i = 0; i < image.size(); ++i)
  {
    difference = std::max(difference, double(std::abs(image[i] - blind->GetImage()[i])));
  }
  EXPECT_GT(difference, 0.05);
}

// A collimated beam from above on the ball in a clear medium over a black floor: the power the
// photons book as reflected and as transmitted at the interface, over all their events, against
// the Fresnel series of a sphere the test integrates itself: a ray of impact parameter b meets
// the surface at sin(i) = b, enters with 1 - R(i), and inside meets it again and again at the
// refracted angle, where the reflectance is R(i) again (Stokes), transmitting 1 - R and
// reflecting R each time. Measured with 2^18 photons: 0.1091 on a 96 x 48 sphere, 0.0998 on
// 192 x 96 (analytic 0.1010): coarse tessellations trap more grazing light by total internal
// reflection between their flat facets, so the test uses the fine one.
TEST(PipelineInterfaces, PhotonsMeetTheBallWithFresnelWeights)
{
  auto pipeline = MakePipeline(GlassBallMedium(192, 0.0), Floor(0.0));
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 16);
  ASSERT_TRUE(pipeline->UpdateLighting());
  vtkImageData* lighting = pipeline->GetLighting();
  const double reflected = FieldValue(lighting, "EnergyInterfaceReflected");
  const double transmitted = FieldValue(lighting, "EnergyInterfaceTransmitted");

  double expectedReflected = 0.0, expectedTransmitted = 0.0;
  const int rings = 100000;
  for (int k = 0; k < rings; ++k)
  {
    const double b = (k + 0.5) / rings, weight = 2.0 * b / rings; // uniform over the disk
    const double r = vtkRefractaDielectric::FresnelReflectance(std::sqrt(1.0 - b * b), 1.0, 1.5);
    expectedReflected += weight * r;
    double inside = weight * (1.0 - r);
    expectedTransmitted += inside;
    for (int bounce = 0; bounce < 60; ++bounce)
    {
      expectedTransmitted += inside * (1.0 - r);
      expectedReflected += inside * r;
      inside *= r;
    }
  }
  const double ratio = reflected / transmitted;
  const double expected = expectedReflected / expectedTransmitted;
  std::cout << "reflected / transmitted " << ratio << ", Fresnel series " << expected << "\n";
  // About 3300 reflection events at 2^16 photons: 1.7% standard error, 3 SE + 1% faceting.
  EXPECT_NEAR(ratio, expected, 0.06 * expected);
}

TEST(PipelineInterfaces, RefractionForcedOffLeavesThemOut)
{
  auto floor = Floor();
  auto pipeline = MakePipeline(GlassBallMedium(), floor);
  pipeline->GetEffectPlan()->SetEffectMode(vtkEffectPlan::REFRACTION, vtkEffectPlan::FORCE_OFF);
  ASSERT_TRUE(pipeline->Render(24, 16));
  EXPECT_EQ(pipeline->GetSceneSurfaces(), floor.Get());
  EXPECT_FALSE(pipeline->GetEffectPlan()->IsEnabled(vtkEffectPlan::REFRACTION));
  EXPECT_EQ(pipeline->GetSceneAnalysis()->GetNumberOfInterfaceSurfaces(), 0);

  // Back to automatic: the interfaces return and the plan re-runs.
  const int plans = pipeline->GetNumberOfPlanRuns();
  pipeline->GetEffectPlan()->SetEffectMode(vtkEffectPlan::REFRACTION, vtkEffectPlan::AUTOMATIC);
  ASSERT_TRUE(pipeline->Render(24, 16));
  EXPECT_EQ(pipeline->GetNumberOfPlanRuns(), plans + 1);
  EXPECT_EQ(pipeline->GetSceneAnalysis()->GetNumberOfInterfaceSurfaces(), 1);
}

TEST(PipelineInterfaces, InterfacesFollowThePropMatrix)
{
  auto pipeline = MakePipeline(GlassBallMedium(), nullptr);
  vtkNew<vtkMatrix4x4> placement;
  placement->SetElement(0, 3, 10.0); // data -> world: 10 along x
  pipeline->SetPropMatrix(placement);
  vtkCamera* camera = pipeline->GetCamera();
  camera->SetPosition(10.0, 0.4, 2.0);
  camera->SetFocalPoint(10.0, -0.1, 0.0);
  ASSERT_TRUE(pipeline->Render(24, 16));
  vtkRefractaSurfaceSet* scene = pipeline->GetSceneSurfaces();
  ASSERT_NE(scene, nullptr);
  ASSERT_TRUE(scene->Build());
  double b[6];
  scene->GetBounds(b);
  EXPECT_NEAR(0.5 * (b[0] + b[1]), 10.0, 1e-6);
  EXPECT_NEAR(b[1] - b[0], 2 * BallRadius, 0.02);

  // Moving the prop moves them (the set holds the matrix by reference): lighting and view re-run.
  const int lights = pipeline->GetNumberOfLightPassRuns();
  placement->SetElement(1, 3, 0.05);
  ASSERT_TRUE(pipeline->Render(24, 16));
  EXPECT_EQ(pipeline->GetNumberOfLightPassRuns(), lights + 1);
  ASSERT_TRUE(scene->Build());
  scene->GetBounds(b);
  EXPECT_NEAR(0.5 * (b[2] + b[3]), 0.05, 1e-6);
}

// The whole scene rotated by 40 degrees about (1, 2, 3) and moved by (10, -5, 3): the prop
// matrix carries the medium and its interfaces, the floor's matrix the floor, and the camera and
// light move alike. In the medium's frame nothing changed, so the image must be the same up to
// photon noise: the sun's photons cover the rotated floor's larger axis-aligned bounds, so they
// land elsewhere (pixels differ by noise, not bias). Measured at 2^16 photons: 16 x 16-pixel
// blocks within 1.8% (8 x 8 blocks: 8%, shrinking as 1 / sqrt(photons)); without the rotation
// the images are identical.
TEST(PipelineInterfaces, RotatedAndMovedSceneRendersTheSameImage)
{
  auto medium = GlassBallMedium();
  auto straight = MakePipeline(medium, Floor());
  straight->GetPhotonTracer()->SetNumberOfPhotons(1 << 16);
  ASSERT_TRUE(straight->Render(48, 32));

  vtkNew<vtkTransform> placement;
  placement->Translate(10.0, -5.0, 3.0);
  placement->RotateWXYZ(40.0, 1.0, 2.0, 3.0);
  vtkNew<vtkMatrix4x4> matrix;
  matrix->DeepCopy(placement->GetMatrix());
  auto floor = vtkSmartPointer<vtkRefractaSurfaceSet>::New();
  vtkNew<vtkRefractaSurfaceMaterial> floorMaterial;
  floor->AddSurface(Floor()->GetSurface(0), floorMaterial, matrix);
  auto moved = MakePipeline(medium, floor);
  moved->GetPhotonTracer()->SetNumberOfPhotons(1 << 16);
  moved->SetPropMatrix(matrix);
  vtkCamera* camera = moved->GetCamera();
  double p[3], f[3], up[3] = { 0, 1, 0 };
  camera->GetPosition(p);
  camera->GetFocalPoint(f);
  placement->TransformPoint(p, p);
  placement->TransformPoint(f, f);
  placement->TransformVector(up, up);
  camera->SetPosition(p);
  camera->SetFocalPoint(f);
  camera->SetViewUp(up);
  vtkLight* sun = vtkLight::SafeDownCast(moved->GetLights()->GetItemAsObject(0));
  ASSERT_NE(sun, nullptr);
  sun->GetPosition(p);
  sun->GetFocalPoint(f);
  placement->TransformPoint(p, p);
  placement->TransformPoint(f, f);
  sun->SetPosition(p);
  sun->SetFocalPoint(f);
  ASSERT_TRUE(moved->Render(48, 32));

  const std::vector<float>& a = straight->GetImage();
  const std::vector<float>& b = moved->GetImage();
  ASSERT_EQ(a.size(), b.size());
  // 16 x 16-pixel blocks, RGB summed.
  const int B = 16;
  double worst = 0.0;
  for (int bj = 0; bj < 32; bj += B)
  {
    for (int bi = 0; bi < 48; bi += B)
    {
      double sa = 0.0, sb = 0.0;
      for (int j = bj; j < bj + B; ++j)
      {
        for (int i = bi; i < bi + B; ++i)
        {
          for (int c = 0; c < 3; ++c)
          {
            sa += a[4 * (i + 48 * j) + c];
            sb += b[4 * (i + 48 * j) + c];
          }
        }
      }
      worst = std::max(worst, std::abs(sa - sb) / std::max(sa, 1e-3));
    }
  }
  std::cout << "rotated scene: largest 16 x 16 block difference " << worst << "\n";
  EXPECT_LT(worst, 0.05);
}

TEST(PipelineInterfaces, InconsistentInterfaceArraysAreAnErrorThatNamesThem)
{
  auto medium = GlassBallMedium();
  // Indices with the wrong number of components.
  vtkNew<vtkFloatArray> wrong;
  wrong->SetName(vtkRefractaMedium::InterfaceIndicesName());
  wrong->SetNumberOfComponents(3);
  wrong->SetNumberOfTuples(1);
  medium->GetFieldData()->RemoveArray(vtkRefractaMedium::InterfaceIndicesName());
  medium->GetFieldData()->AddArray(wrong);
  auto pipeline = MakePipeline(medium, Floor());
  std::string message;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetClientData(&message);
  onError->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
    { *static_cast<std::string*>(client) = static_cast<const char*>(call); });
  pipeline->AddObserver(vtkCommand::ErrorEvent, onError);
  EXPECT_FALSE(pipeline->Render(16, 16));
  EXPECT_NE(message.find(vtkRefractaMedium::InterfaceTrianglesName()), std::string::npos)
    << message;
  EXPECT_TRUE(pipeline->GetImage().empty());
}
