// vtkRefractaRenderPipeline: each stage re-runs only when something it reads changed (VTK
// modification times), progress is monotone and complete, an abort stops the render and the next
// render recovers, a bad medium is reported once, and the pipeline's image is the image of the
// passes wired by hand (photon tracer -> Lattice-Boltzmann lighting -> view pass) and of the
// lighting volume's hand-off through the host.
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkEffectPlan.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLDeviceArrays.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaViewPass.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
// Every error message `object` reports, in order (the observer lives as long as the object).
struct ErrorCollector : public vtkCommand
{
  static ErrorCollector* New() { return new ErrorCollector; }
  void Execute(vtkObject*, unsigned long, void* call) override
  {
    this->Messages.push_back(static_cast<const char*>(call));
  }
  std::vector<std::string> Messages;
};

ErrorCollector* CollectErrors(vtkObject* object)
{
  vtkNew<ErrorCollector> collector;
  object->AddObserver(vtkCommand::ErrorEvent, collector);
  return collector; // the object holds the observer
}

// A 24^3 fog (sigma_t 3, albedo 0.8) with a denser, slightly refractive ball in the middle.
vtkSmartPointer<vtkImageData> Fog()
{
  const int n = 24;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  auto add = [&](const char* name, int comps)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(image->GetNumberOfPoints());
    image->GetPointData()->AddArray(a);
    return a.GetPointer();
  };
  vtkFloatArray* ext = add("Extinction", 3);
  vtkFloatArray* alb = add("Albedo", 3);
  vtkFloatArray* idx = add("RefractiveIndex", 1);
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    const double r = std::sqrt(
      (p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5) + (p[2] - 0.5) * (p[2] - 0.5));
    const double ball = 0.5 * (1.0 - std::tanh((r - 0.25) / 0.05));
    for (int c = 0; c < 3; ++c)
    {
      ext->SetComponent(id, c, 3.0 + 6.0 * ball);
      alb->SetComponent(id, c, 0.8);
    }
    idx->SetValue(id, static_cast<float>(1.0 + 0.2 * ball));
  }
  return image;
}

// An Anisotropy array of `g` everywhere added to `medium`; the medium keeps it.
vtkFloatArray* AddAnisotropy(vtkImageData* medium, float g)
{
  vtkNew<vtkFloatArray> array;
  array->SetName("Anisotropy");
  array->SetNumberOfTuples(medium->GetNumberOfPoints());
  array->FillValue(g);
  medium->GetPointData()->AddArray(array);
  return array;
}

vtkSmartPointer<vtkLight> Sun()
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetLightTypeToSceneLight();
  light->SetPositional(false);
  light->SetPosition(0.5, 3.0, 0.8);
  light->SetFocalPoint(0.5, 0.5, 0.5);
  light->SetIntensity(2.0);
  return light;
}

vtkSmartPointer<vtkCamera> Front()
{
  auto camera = vtkSmartPointer<vtkCamera>::New();
  camera->SetPosition(0.5, 0.6, 3.0);
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  return camera;
}

struct Counts
{
  int Plan, Light, View, Medium;
};

Counts CountsOf(vtkRefractaRenderPipeline* p)
{
  return { p->GetNumberOfPlanRuns(), p->GetNumberOfLightPassRuns(), p->GetNumberOfViewPassRuns(),
    p->GetNumberOfMediumUpdates() };
}

void ExpectCounts(vtkRefractaRenderPipeline* p, Counts expected, const char* what)
{
  const Counts got = CountsOf(p);
  EXPECT_EQ(got.Plan, expected.Plan) << what;
  EXPECT_EQ(got.Light, expected.Light) << what;
  EXPECT_EQ(got.View, expected.View) << what;
  EXPECT_EQ(got.Medium, expected.Medium) << what;
}

vtkSmartPointer<vtkRefractaRenderPipeline> MakePipeline(
  vtkImageData* medium, vtkLight* light, vtkCamera* camera)
{
  auto pipeline = vtkSmartPointer<vtkRefractaRenderPipeline>::New();
  pipeline->SetMedium(medium);
  pipeline->AddLight(light);
  pipeline->SetCamera(camera);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 14);
  return pipeline;
}
}

TEST(RenderPipeline, StagesRerunOnlyWhatChanged)
{
  auto medium = Fog();
  auto light = Sun();
  auto camera = Front();
  auto pipeline = MakePipeline(medium, light, camera);
  ASSERT_TRUE(pipeline->Render(32, 32));
  ASSERT_TRUE(pipeline->GetEffectPlan()->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING));
  ExpectCounts(pipeline, { 1, 1, 1, 1 }, "first render");
  const int uploads = pipeline->GetViewPass()->GetNumberOfUploads();

  ASSERT_TRUE(pipeline->Render(32, 32));
  ExpectCounts(pipeline, { 1, 1, 1, 1 }, "nothing changed");
  EXPECT_FALSE(pipeline->GetStageRan(vtkRefractaRenderPipeline::VIEW));

  // What matters is the rays, not the camera's MTime or identity: a clipping range reset, or
  // a copy of the camera (vtkWindowToImageFilter renders with one), keeps the image.
  camera->SetClippingRange(0.01, 123.0);
  vtkNew<vtkCamera> copy;
  copy->DeepCopy(camera);
  pipeline->SetCamera(copy);
  ASSERT_TRUE(pipeline->Render(32, 32));
  ExpectCounts(pipeline, { 1, 1, 1, 1 }, "the same rays from another camera object");
  pipeline->SetCamera(camera);

  camera->Azimuth(10);
  ASSERT_TRUE(pipeline->Render(32, 32));
  ExpectCounts(pipeline, { 1, 1, 2, 1 }, "camera move: view only");
  EXPECT_EQ(pipeline->GetViewPass()->GetNumberOfUploads(), uploads);

  pipeline->GetViewPass()->SetStepSize(0.5);
  ASSERT_TRUE(pipeline->Render(32, 32));
  ExpectCounts(pipeline, { 1, 1, 3, 1 }, "view setting: view only");

  ASSERT_TRUE(pipeline->Render(40, 30));
  ExpectCounts(pipeline, { 1, 1, 4, 1 }, "image size: view only");

  light->SetPosition(1.5, 3.0, 0.5);
  ASSERT_TRUE(pipeline->Render(40, 30));
  ExpectCounts(pipeline, { 2, 2, 5, 1 }, "light move: light passes and view, same medium");
  EXPECT_EQ(pipeline->GetViewPass()->GetNumberOfUploads(), uploads + 1) << "lighting only";
  EXPECT_TRUE(pipeline->GetPhotonTracer()->GetLastRunReusedMedium())
    << "a light move neither re-uploads the medium nor rebuilds the octree";
  {
    // ... and the kept medium gives the image a fresh pipeline gives.
    auto fresh = MakePipeline(medium, light, camera);
    fresh->GetViewPass()->SetStepSize(0.5);
    ASSERT_TRUE(fresh->Render(40, 30));
    EXPECT_EQ(fresh->GetImage(), pipeline->GetImage());
  }

  pipeline->GetPhotonTracer()->SetNumberOfPhotons(1 << 13);
  ASSERT_TRUE(pipeline->Render(40, 30));
  ExpectCounts(pipeline, { 2, 3, 6, 1 }, "photon count: light passes and view");

  medium->Modified();
  ASSERT_TRUE(pipeline->Render(40, 30));
  ExpectCounts(pipeline, { 3, 4, 7, 2 }, "medium change: everything");
  EXPECT_FALSE(pipeline->GetPhotonTracer()->GetLastRunReusedMedium());

  pipeline->GetEffectPlan()->SetTolerance(0.02);
  ASSERT_TRUE(pipeline->Render(40, 30));
  ExpectCounts(pipeline, { 4, 5, 8, 3 }, "plan setting: everything");
}

// VTK_LIGHT_UNITS: a positional light of intensity I becomes the radiant intensity pi I d^2, d
// its distance to the medium's centre but at least the centre's distance to the nearest face
// (0.5 for the unit fog): a lamp at the centre went dark (pi I 1e-300; outside review).
TEST(RenderPipeline, VTKLightUnitsKeepALampAtTheCentreLit)
{
  for (double z : { 0.5, 0.6, 3.0 })
  {
    auto lamp = vtkSmartPointer<vtkLight>::New();
    lamp->SetLightTypeToSceneLight();
    lamp->SetPositional(true);
    lamp->SetConeAngle(180);
    lamp->SetPosition(0.5, 0.5, z);
    lamp->SetFocalPoint(0.5, 0.5, 0.0);
    lamp->SetIntensity(2.0);
    auto pipeline = MakePipeline(Fog(), lamp, Front());
    pipeline->SetLightUnits(vtkRefractaRenderPipeline::VTK_LIGHT_UNITS);
    ASSERT_TRUE(pipeline->Render(16, 16));
    vtkLightCollection* used = pipeline->GetPhotonTracer()->GetLights();
    ASSERT_EQ(used->GetNumberOfItems(), 1);
    used->InitTraversal();
    const double d = std::max(std::abs(z - 0.5), 0.5);
    EXPECT_NEAR(used->GetNextItem()->GetIntensity(), vtkMath::Pi() * 2.0 * d * d, 1e-9) << z;
    double mean = 0;
    for (float v : pipeline->GetImage())
    {
      mean += v / pipeline->GetImage().size();
    }
    EXPECT_GT(mean, 1e-3) << z;
  }
}

TEST(RenderPipeline, ProgressIsMonotoneAndStagesAreAnnounced)
{
  auto pipeline = MakePipeline(Fog(), Sun(), Front());
  std::vector<double> progress;
  std::vector<std::string> stages;
  vtkNew<vtkCallbackCommand> onProgress;
  onProgress->SetClientData(&progress);
  onProgress->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
    { static_cast<std::vector<double>*>(client)->push_back(*static_cast<double*>(call)); });
  vtkNew<vtkCallbackCommand> onStart;
  onStart->SetClientData(&stages);
  onStart->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
    { static_cast<std::vector<std::string>*>(client)->push_back(static_cast<const char*>(call)); });
  pipeline->AddObserver(vtkCommand::ProgressEvent, onProgress);
  pipeline->AddObserver(vtkCommand::StartEvent, onStart);
  ASSERT_TRUE(pipeline->Render(48, 48));
  ASSERT_GE(progress.size(), 4u);
  EXPECT_EQ(progress.front(), 0.0);
  EXPECT_DOUBLE_EQ(progress.back(), 1.0);
  for (size_t i = 1; i < progress.size(); ++i)
  {
    EXPECT_GE(progress[i], progress[i - 1]) << "at event " << i;
  }
  EXPECT_EQ(stages, (std::vector<std::string>{ "plan", "lighting", "view" }));
}

TEST(RenderPipeline, AbortStopsTheRenderAndTheNextRenderRecovers)
{
  auto medium = Fog();
  auto light = Sun();
  auto camera = Front();
  auto reference = MakePipeline(medium, light, camera);
  ASSERT_TRUE(reference->Render(32, 32));

  auto pipeline = MakePipeline(medium, light, camera);
  vtkNew<vtkCallbackCommand> abortAtStart;
  abortAtStart->SetClientData(pipeline.Get());
  abortAtStart->SetCallback(
    [](vtkObject*, unsigned long, void* client, void* call)
    {
      if (call && std::string(static_cast<const char*>(call)) == "lighting")
      {
        static_cast<vtkRefractaRenderPipeline*>(client)->AbortRender();
      }
    });
  const unsigned long tag = pipeline->AddObserver(vtkCommand::StartEvent, abortAtStart);
  EXPECT_FALSE(pipeline->Render(32, 32));
  EXPECT_TRUE(pipeline->GetLastRenderAborted());
  EXPECT_EQ(pipeline->GetNumberOfViewPassRuns(), 0);
  pipeline->RemoveObserver(tag);

  ASSERT_TRUE(pipeline->Render(32, 32));
  EXPECT_FALSE(pipeline->GetLastRenderAborted());
  EXPECT_EQ(pipeline->GetImage(), reference->GetImage()) << "same seed, same device: same image";
}

TEST(RenderPipeline, BadMediumIsReportedOnce)
{
  auto medium = Fog();
  vtkFloatArray::SafeDownCast(medium->GetPointData()->GetArray("Extinction"))
    ->SetComponent(7, 1, -1.0);
  auto pipeline = MakePipeline(medium, Sun(), Front());
  int errors = 0;
  std::string message;
  vtkNew<vtkCallbackCommand> onError;
  struct Sink
  {
    int* Count;
    std::string* Text;
  } sink{ &errors, &message };
  onError->SetClientData(&sink);
  onError->SetCallback(
    [](vtkObject*, unsigned long, void* client, void* call)
    {
      auto* s = static_cast<Sink*>(client);
      ++*s->Count;
      *s->Text = static_cast<const char*>(call);
    });
  pipeline->AddObserver(vtkCommand::ErrorEvent, onError);
  EXPECT_FALSE(pipeline->Render(16, 16));
  EXPECT_FALSE(pipeline->Render(16, 16));
  EXPECT_EQ(errors, 1) << "the same message is not repeated on every render";
  EXPECT_NE(message.find("Extinction"), std::string::npos) << message;
  EXPECT_NE(message.find("7"), std::string::npos) << "names the voxel: " << message;

  // A light of negative intensity: refused as the passes refuse it (the plan used to count it as
  // no light and skip the passes without a word), once; a valid light renders again.
  vtkFloatArray::SafeDownCast(medium->GetPointData()->GetArray("Extinction"))
    ->SetComponent(7, 1, 0.5);
  medium->Modified();
  auto negative = Sun();
  negative->SetIntensity(-5);
  pipeline->RemoveAllLights();
  pipeline->AddLight(negative);
  EXPECT_FALSE(pipeline->Render(16, 16));
  EXPECT_FALSE(pipeline->Render(16, 16));
  EXPECT_EQ(errors, 2);
  EXPECT_NE(message.find("Light 0"), std::string::npos) << message;
  EXPECT_NE(message.find("negative intensity"), std::string::npos) << message;
  negative->SetIntensity(5);
  EXPECT_TRUE(pipeline->Render(16, 16));
  EXPECT_EQ(errors, 2);
}

TEST(RenderPipeline, SameImageAsThePassesWiredByHand)
{
  auto medium = Fog();
  auto light = Sun();
  auto camera = Front();
  auto pipeline = MakePipeline(medium, light, camera);
  pipeline->GetEffectPlan()->SetTolerance(0.0);
  // The passes below are the photon tracer and the lattice alone; the refracting ball would make
  // the plan hand the first orders to photons (the split) by itself.
  pipeline->SetMultipleScatteringMethod(vtkEffectPlan::LATTICE_ONLY);
  // The passes below run one after the other; the automatic schedule interleaves them on a GPU.
  pipeline->SetMultipleScatteringSchedule(vtkRefractaRenderPipeline::SEQUENTIAL_SCHEDULE);
  ASSERT_TRUE(pipeline->Render(32, 32));
  ASSERT_FALSE(pipeline->GetLastScheduleInterleaved());

  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(medium);
  tracer->AddLight(light);
  tracer->SetNumberOfPhotons(1 << 14);
  vtkNew<vtkLatticeBoltzmannLighting> lattice;
  lattice->SetInputData(medium);
  lattice->SetLightingConnection(tracer->GetOutputPort());
  vtkNew<vtkRefractaImageRenderer> renderer;
  renderer->SetInputData(medium);
  renderer->SetLightingConnection(lattice->GetOutputPort());
  renderer->SetCamera(camera);
  renderer->SetImageSize(32, 32);
  renderer->Update();
  vtkDataArray* hdr = renderer->GetOutput()->GetPointData()->GetArray("HDR");
  ASSERT_NE(hdr, nullptr);
  const std::vector<float>& image = pipeline->GetImage();
  ASSERT_EQ(image.size(), static_cast<size_t>(4 * hdr->GetNumberOfTuples()));
  double maximum = 0, difference = 0;
  for (vtkIdType p = 0; p < hdr->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      maximum = std::max(maximum, std::abs(hdr->GetComponent(p, c)));
      difference = std::max(difference, std::abs(hdr->GetComponent(p, c) - image[4 * p + c]));
    }
  }
  EXPECT_GT(maximum, 0.0);
  EXPECT_LE(difference, 1e-5 * maximum);
}

// The lattice the solver runs is the plan's: D3Q18 for a strongly forward-scattering medium
// (mean |g| >= vtkEffectPlan::D3Q18Anisotropy), D3Q6 once the medium is nearly isotropic or where
// the device cannot hold D3Q18's state (a simulated 2 MiB allocation limit: 24^3 voxels need
// 3.0 MB per D3Q18 state, 1.0 MB per D3Q6 one); a forced lattice is the solver's whatever the
// medium.
TEST(RenderPipeline, LatticeIsThePlansChoice)
{
  auto medium = Fog();
  vtkFloatArray* g = AddAnisotropy(medium, 0.8f);
  auto pipeline = MakePipeline(medium, Sun(), Front());
  pipeline->SetMultipleScatteringMethod(vtkEffectPlan::LATTICE_ONLY);
  EXPECT_EQ(pipeline->GetLattice(), vtkEffectPlan::AUTOMATIC_LATTICE);
  ASSERT_TRUE(pipeline->Render(16, 16));
  EXPECT_EQ(pipeline->GetLatticeSolver()->GetLattice(), 18);
  // The solver's own setting does not outlast the next render: the plan's lattice runs.
  pipeline->GetLatticeSolver()->SetLattice(6);
  ASSERT_TRUE(pipeline->Render(16, 16));
  EXPECT_EQ(pipeline->GetLatticeSolver()->GetLattice(), 18);

  g->FillValue(0.3f);
  medium->Modified();
  ASSERT_TRUE(pipeline->Render(16, 16));
  EXPECT_EQ(pipeline->GetLatticeSolver()->GetLattice(), 6);
  pipeline->SetLattice(18);
  ASSERT_TRUE(pipeline->Render(16, 16));
  EXPECT_EQ(pipeline->GetLatticeSolver()->GetLattice(), 18);

  vtkNew<vtkOpenCLContext> small;
  ASSERT_TRUE(small->Initialize());
  small->SetSimulatedMaximumAllocationBytes(2 << 20);
  g->FillValue(0.8f);
  medium->Modified();
  pipeline->SetContext(small);
  pipeline->SetLattice(vtkEffectPlan::AUTOMATIC_LATTICE);
  ASSERT_TRUE(pipeline->Render(16, 16));
  EXPECT_EQ(pipeline->GetLatticeSolver()->GetLattice(), 6);
  EXPECT_NE(std::string(pipeline->GetEffectPlan()->GetMultipleScatteringMethodReason())
              .find("does not fit the device"),
    std::string::npos)
    << pipeline->GetEffectPlan()->GetMultipleScatteringMethodReason();
}

// The lighting volume handed on on the device (photon pass -> lattice -> view pass, no upload of
// what was just read back) gives the image of the hand-off through the host, to the bit, for the
// lattice's two sources (S1 alone; the first-collision split, whose photon S_ms is added on the
// device), and a light move replaces the copies rather than adding to them.
TEST(RenderPipeline, DeviceHandOffGivesTheImageOfTheHostHandOff)
{
  auto medium = Fog();
  // Forward scattering: the lattice's source is spread around its direction (which an isotropic
  // phase function would ignore); g = 0.6 runs D3Q18 (the plan's lattice).
  AddAnisotropy(medium, 0.6f);
  auto camera = Front();
  vtkOpenCLDeviceArrays* copies = vtkOpenCLContext::GetDefault()->GetDeviceArrays();
  for (const bool split : { true, false })
  {
    SCOPED_TRACE(split ? "first-collision split" : "lattice only");
    auto light = Sun();
    auto device = MakePipeline(medium, light, camera);
    auto host = MakePipeline(medium, light, camera);
    host->SetDeviceHandOff(false);
    for (vtkRefractaRenderPipeline* p : { device.GetPointer(), host.GetPointer() })
    {
      p->SetMultipleScatteringSchedule(vtkRefractaRenderPipeline::SEQUENTIAL_SCHEDULE);
      if (!split)
      {
        p->SetMultipleScatteringMethod(vtkEffectPlan::LATTICE_ONLY);
      }
    }
    int held = -1;
    for (int frame = 0; frame < 2; ++frame)
    {
      if (frame == 1)
      {
        light->SetPosition(1.5, 2.5, 0.5); // a light move: the light passes run again
      }
      const long long hits = copies->GetNumberOfHits();
      ASSERT_TRUE(host->Render(24, 20));
      EXPECT_EQ(host->GetViewPass()->GetLastLightingArraysShared(), 0);
      EXPECT_EQ(copies->GetNumberOfHits(), hits) << "the host hand-off takes no device copy";
      ASSERT_TRUE(device->Render(24, 20));
      EXPECT_EQ(device->GetPhotonTracer()->GetUsedScatteringOrders() > 0, split);
      // The view pass's arrays (Radiance, its direction, S_ms and, from the lattice alone, S_ms's
      // direction: the split's is merged with the photons' on the host), the lattice's source and
      // its direction, and with the split the photons' S_ms added to the lattice's.
      EXPECT_EQ(device->GetViewPass()->GetLastLightingArraysShared(), split ? 3 : 4);
      EXPECT_EQ(copies->GetNumberOfHits() - hits, 6);
      EXPECT_EQ(device->GetImage(), host->GetImage()) << "frame " << frame;
      vtkDataArray* a = device->GetLighting()->GetPointData()->GetArray("MultipleScattering");
      vtkDataArray* b = host->GetLighting()->GetPointData()->GetArray("MultipleScattering");
      ASSERT_TRUE(a && b);
      double largest = 0, difference = 0;
      for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
      {
        largest = std::max(largest, a->GetComponent(i / 3, i % 3));
        difference = std::max(
          difference, std::abs(a->GetComponent(i / 3, i % 3) - b->GetComponent(i / 3, i % 3)));
      }
      EXPECT_GT(largest, 0.0);
      EXPECT_EQ(difference, 0.0);
      if (held >= 0)
      {
        EXPECT_EQ(copies->GetNumberOfArrays(), held) << "a light move replaces the copies";
      }
      held = copies->GetNumberOfArrays();
    }
    // Radiance and its direction, S_ms; from the lattice alone also S_ms's direction, with the
    // split the photons' S_ms and the lattice's source and its direction.
    EXPECT_EQ(held, split ? 6 : 4);
  }
}

TEST(RenderPipeline, MissingInputsAreErrorsThatNameThem)
{
  vtkNew<vtkRefractaRenderPipeline> pipeline;
  std::vector<std::string>& messages = CollectErrors(pipeline)->Messages;
  EXPECT_FALSE(pipeline->Render(16, 16));
  pipeline->SetMedium(Fog());
  EXPECT_FALSE(pipeline->Render(16, 16));
  pipeline->SetCamera(Front());
  EXPECT_FALSE(pipeline->Render(0, 16));
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_NE(messages[0].find("SetMedium"), std::string::npos) << messages[0];
  EXPECT_NE(messages[1].find("SetCamera"), std::string::npos) << messages[1];
  EXPECT_NE(messages[2].find("0 x 16"), std::string::npos) << messages[2];
  EXPECT_TRUE(pipeline->GetImage().empty());
  EXPECT_TRUE(pipeline->Render(16, 16)) << "usable once the inputs are there";
}

// A camera or a prop matrix that cannot make view rays or place the medium is an error naming
// what is wrong, not a black or NaN image (a vtkVolume scaled by zero on one axis, a camera whose
// position was computed from NaN).
TEST(RenderPipeline, UnusableCameraAndPropMatrixAreErrors)
{
  vtkNew<vtkRefractaRenderPipeline> pipeline;
  std::vector<std::string>& messages = CollectErrors(pipeline)->Messages;
  pipeline->SetMedium(Fog());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto fails = [&](const char* expected)
  {
    messages.clear();
    EXPECT_FALSE(pipeline->Render(16, 16)) << expected;
    ASSERT_EQ(messages.size(), 1u) << expected;
    EXPECT_NE(messages[0].find(expected), std::string::npos) << messages[0];
    EXPECT_TRUE(pipeline->GetImage().empty());
  };
  vtkSmartPointer<vtkCamera> camera = Front();
  pipeline->SetCamera(camera);
  camera->SetPosition(nan, 0, 0);
  fails("must be finite");
  camera = Front();
  pipeline->SetCamera(camera);
  camera->SetViewUp(camera->GetDirectionOfProjection());
  fails("view up");
  pipeline->SetCamera(Front());
  EXPECT_TRUE(pipeline->Render(16, 16));

  vtkNew<vtkMatrix4x4> squashed;
  squashed->SetElement(1, 1, 0.0);
  pipeline->SetPropMatrix(squashed);
  fails("singular");
  squashed->SetElement(1, 1, 1.0);
  squashed->SetElement(0, 3, nan);
  fails("not finite");
  squashed->SetElement(0, 3, 0.5);
  EXPECT_TRUE(pipeline->Render(16, 16)) << "a translated medium renders";
}

// The front end's settings refuse what would render nothing: a NaN step size or exposure (which
// vtkSetClampMacro lets through) and an image size outside 1 to 16384 pixels are errors, seen by
// an observer on the renderer, that keep the previous value.
TEST(RenderPipeline, ImageRendererRefusesUnusableSettings)
{
  vtkNew<vtkRefractaImageRenderer> renderer;
  std::vector<std::string>& messages = CollectErrors(renderer)->Messages;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  renderer->SetStepSize(0.5);
  renderer->SetStepSize(nan);
  EXPECT_EQ(renderer->GetStepSize(), 0.5);
  renderer->SetExposure(nan);
  EXPECT_EQ(renderer->GetExposure(), 1.0);
  renderer->SetImageSize(64, 48);
  renderer->SetImageSize(0, 48);
  renderer->SetImageSize(100000, 100000);
  EXPECT_EQ(renderer->GetImageSize()[0], 64);
  EXPECT_EQ(renderer->GetImageSize()[1], 48);
  ASSERT_EQ(messages.size(), 4u);
  EXPECT_NE(messages[0].find("SetStepSize(nan)"), std::string::npos) << messages[0];
  EXPECT_NE(messages[1].find("SetExposure(nan)"), std::string::npos) << messages[1];
  EXPECT_NE(messages[2].find("1 to 16384"), std::string::npos) << messages[2];
  renderer->SetStepSize(-1); // finite values are clamped, as vtkSetClampMacro does
  EXPECT_EQ(renderer->GetStepSize(), 0.01);
  EXPECT_EQ(messages.size(), 4u);
}
