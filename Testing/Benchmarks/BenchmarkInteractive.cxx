// BenchmarkInteractive: what one persistent vtkRefractaRenderPipeline saves against a fresh
// pipeline per frame, for the four interactions of a viewer:
//   camera move      the view pass only;
//   light move       the light passes and the view pass, on the medium already on the device;
//   material change  a transfer-function edit: the medium is mapped again, then everything;
//   full re-render   the medium marked modified: everything.
// The scene: a scalar blob field on N^3 voxels through vtkTransferFunctionMedium (opacity ->
// extinction, colour -> albedo, a refractive core n up to 1.1 so rays curve), a spot light, a
// W x H image; photon count and multiple scattering as the plan decides. Medians of --runs frames
// per interaction after one untimed frame (kernels compiled and cached); the fresh pipeline reuses
// the compiled kernels (process-wide cache), so its figure is the cost of the missing device and
// stage state, not of compilation. Per-stage medians of the persistent pipeline say where the time
// goes.
//
//   BenchmarkInteractive [--size N] [--photons P] [--width W] [--height H] [--runs R]
//                        [--csv FILE] [--profile] [--persistent-only] [--warm-start]
//                        [--transfers] [--fresh-scratch] [--general-kernel] [--cold-lattice]
//                        [--host-hand-off] [--only camera,light,material,full]
// Defaults are the target configuration: 128^3, 2^20 photons, 640 x 480, 5 runs.
// --profile times every OpenCL call of the persistent frames (vtkOpenCLKernelProfile): device_s is
// the median device time per frame (kernels and transfers), cl_host_s the host's wall time inside
// OpenCL calls (enqueues and blocking waits); persistent_s less cl_host_s is the host's own work.
// Each interaction's kernels and transfers are printed, longest first. --persistent-only skips the
// fresh pipelines (their columns read 0) where device time is scarce. --warm-start turns on the
// persistent pipeline's LatticeWarmStart (a light move iterates the lattice on from the last
// field); lattice_steps is the median of its steps per frame. --transfers first measures host <->
// device copies of one lighting array from pageable, pinned and pinned-staged memory. --only runs
// some of the interactions (camera, light, material, full). --fresh-scratch turns the photon
// tracer's ReuseScratchBuffers off (the persistent pipeline's default is on): its A/B.
// --general-kernel turns the view pass's LaneMarching off (the eight-lane kernel is the default on
// a CPU device): its A/B. --cold-lattice turns the lattice's CoarseStart off (every lattice step
// on the full grid): its A/B. --host-hand-off turns the pipeline's DeviceHandOff off (the lighting
// volume goes photon pass -> host -> lattice -> host -> view pass): its A/B.
#include "RefractaBenchmark.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkEffectPlan.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLKernelProfile.h"
#include "vtkPhotonTracer.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaViewPass.h"
#include "vtkSmartPointer.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkVolumeProperty.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace
{
struct Options
{
  int Size = 128;
  int Photons = 1 << 20;
  int Width = 640;
  int Height = 480;
  int Runs = 5;
  std::string Csv;
  bool Profile = false;
  bool PersistentOnly = false;
  bool WarmStart = false;
  bool Transfers = false;
  bool FreshScratch = false; // the tracer creates its scratch buffers every run (A/B)
  bool GeneralKernel = false; // the view pass's general kernel instead of the lanes (A/B)
  bool ColdLattice = false;   // the lattice without its coarse start (A/B)
  bool PlainWarmStart = false; // a warm start without its coarse correction (A/B)
  bool HostHandOff = false;   // the lighting volume handed on through the host (A/B)
  std::string Only; // comma-separated first words of the interactions to run (empty: all)
};

double Seconds(const std::function<bool()>& work)
{
  const auto start = std::chrono::steady_clock::now();
  if (!work())
  {
    std::cerr << "BenchmarkInteractive: a render failed\n";
    std::exit(1);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Host <-> device copy rates for one lighting array of the scene (N^3 RGB floats), the way the
// passes hand the lighting volume on today: from and to pageable host memory (a std::vector, what
// a vtkFloatArray holds); from and to pinned memory (a CL_MEM_ALLOC_HOST_PTR buffer, mapped); and
// pageable staged through the pinned buffer (a host copy plus the pinned transfer). Medians of
// `runs` copies, GB/s.
void MeasureTransfers(vtkOpenCLContext* context, int n, int runs)
{
  const size_t bytes = size_t(n) * n * n * 3 * sizeof(float);
  vtkOpenCLBuffer device = context->CreateBuffer(CL_MEM_READ_WRITE, bytes, nullptr, "transfer");
  vtkOpenCLBuffer pinned = context->CreateBuffer(
    CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, bytes, nullptr, "pinned staging");
  if (!device || !pinned)
  {
    std::cout << "  transfers: buffers of " << bytes << " bytes could not be created\n";
    return;
  }
  cl_int status = CL_SUCCESS;
  void* mapped = clEnqueueMapBuffer(context->GetQueue(), pinned.Get(), CL_TRUE,
    CL_MAP_READ | CL_MAP_WRITE, 0, bytes, 0, nullptr, nullptr, &status);
  if (status != CL_SUCCESS || !mapped)
  {
    std::cout << "  transfers: clEnqueueMapBuffer failed (" << status << ")\n";
    return;
  }
  std::vector<float> pageable(bytes / sizeof(float), 1.0f);
  // `staged`: through the pinned buffer, with a host copy to or from the pageable one (what a
  // pinned staging inside vtkOpenCLContext would cost).
  auto rate = [&](void* host, bool read, bool staged = false)
  {
    std::vector<double> rates;
    for (int r = 0; r < runs + 1; ++r) // the first copy is a warm-up
    {
      const double t = Seconds(
        [&]
        {
          if (read)
          {
            const bool done = context->ReadBuffer(device.Get(), bytes, staged ? mapped : host);
            return done && (!staged || std::memcpy(host, mapped, bytes));
          }
          return (!staged || std::memcpy(mapped, host, bytes)) &&
            context->WriteBuffer(device.Get(), bytes, staged ? mapped : host) && context->Finish();
        });
      if (r > 0)
      {
        rates.push_back(bytes / t * 1e-9);
      }
    }
    return refracta::bench::Median(rates);
  };
  std::cout << "  transfers of one lighting array (" << bytes / 1048576.0
            << " MiB), GB/s: pageable read " << rate(pageable.data(), true) << ", write "
            << rate(pageable.data(), false) << "; pinned read " << rate(mapped, true) << ", write "
            << rate(mapped, false) << "; pageable staged through pinned read "
            << rate(pageable.data(), true, true) << ", write " << rate(pageable.data(), false, true)
            << "\n";
  clEnqueueUnmapMemObject(context->GetQueue(), pinned.Get(), mapped, 0, nullptr, nullptr);
  context->Finish();
}

// A smooth blob: density 1 in the core falling to 0 at the box's edge, with some structure.
vtkSmartPointer<vtkImageData> BlobField(int n)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(1.0 / (n - 1), 1.0 / (n - 1), 1.0 / (n - 1));
  vtkNew<vtkFloatArray> density;
  density->SetName("density");
  density->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    const double x = p[0] - 0.5, y = p[1] - 0.5, z = p[2] - 0.5;
    const double r = std::sqrt(x * x + y * y + z * z);
    const double ripple = 0.08 * std::sin(14 * x) * std::sin(11 * y) * std::sin(9 * z);
    density->SetValue(id, static_cast<float>(std::max(0.0, 1.0 - 2.4 * r + ripple)));
  }
  image->GetPointData()->SetScalars(density);
  return image;
}

struct Scene
{
  vtkSmartPointer<vtkImageData> Field;
  vtkNew<vtkTransferFunctionMedium> Mapping;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkColorTransferFunction> Colour;
  vtkNew<vtkPiecewiseFunction> Index;
  vtkNew<vtkLight> Light;
  vtkNew<vtkCamera> Camera;

  explicit Scene(int n)
    : Field(BlobField(n))
  {
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(0.2, 0.02);
    opacity->AddPoint(1.0, 0.3);
    this->Colour->AddRGBPoint(0.0, 0.9, 0.9, 0.9);
    this->Colour->AddRGBPoint(1.0, 0.9, 0.7, 0.5);
    this->Property->SetScalarOpacity(opacity);
    this->Property->SetColor(this->Colour);
    this->Property->SetScalarOpacityUnitDistance(0.05);
    this->Index->AddPoint(0.0, 1.0);
    this->Index->AddPoint(1.0, 1.1);
    this->Mapping->SetInputData(this->Field);
    this->Mapping->SetVolumeProperty(this->Property);
    this->Mapping->SetRefractiveIndexFunction(this->Index);
    this->Mapping->Update();
    this->Light->SetLightTypeToSceneLight();
    this->Light->SetPositional(true);
    this->Light->SetConeAngle(30);
    this->Light->SetPosition(0.5, 2.5, 0.8);
    this->Light->SetFocalPoint(0.5, 0.5, 0.5);
    this->Light->SetIntensity(4.0);
    this->Camera->SetPosition(0.5, 0.8, 3.2);
    this->Camera->SetFocalPoint(0.5, 0.5, 0.5);
    this->Camera->SetViewUp(0, 1, 0);
    this->Camera->SetViewAngle(30);
  }

  vtkImageData* Medium() { return this->Mapping->GetOutput(); }
};

vtkSmartPointer<vtkRefractaRenderPipeline> MakePipeline(Scene& scene, const Options& o)
{
  auto pipeline = vtkSmartPointer<vtkRefractaRenderPipeline>::New();
  pipeline->SetMedium(scene.Medium());
  pipeline->AddLight(scene.Light);
  pipeline->SetCamera(scene.Camera);
  pipeline->GetPhotonTracer()->SetNumberOfPhotons(o.Photons);
  pipeline->GetPhotonTracer()->SetReuseScratchBuffers(!o.FreshScratch);
  pipeline->GetViewPass()->SetLaneMarching(!o.GeneralKernel);
  pipeline->GetLatticeSolver()->SetCoarseStart(!o.ColdLattice);
  pipeline->GetLatticeSolver()->SetCoarseWarmStart(!o.PlainWarmStart);
  pipeline->SetDeviceHandOff(!o.HostHandOff);
  return pipeline;
}

// The interactions: each changes the scene a little (and back and forth, so frames stay alike).
struct Interaction
{
  std::string Name;
  std::function<void(Scene&, int)> Change;
};

std::vector<Interaction> Interactions()
{
  return {
    { "camera move", [](Scene& s, int frame) { s.Camera->Azimuth(frame % 2 ? 2.0 : -2.0); } },
    { "light move",
      [](Scene& s, int frame) { s.Light->SetPosition(0.5 + (frame % 2 ? 0.1 : -0.1), 2.5, 0.8); } },
    { "material change",
      [](Scene& s, int frame)
      {
        s.Colour->RemoveAllPoints();
        s.Colour->AddRGBPoint(0.0, 0.9, 0.9, 0.9);
        s.Colour->AddRGBPoint(1.0, 0.9, frame % 2 ? 0.6 : 0.7, 0.5);
        s.Mapping->Update();
      } },
    { "full re-render", [](Scene& s, int) { s.Medium()->Modified(); } },
  };
}
}

int main(int argc, char* argv[])
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto next = [&]() -> std::string
    {
      if (i + 1 >= argc)
      {
        std::cerr << "BenchmarkInteractive: " << arg << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--size")
      o.Size = std::stoi(next());
    else if (arg == "--photons")
      o.Photons = std::stoi(next());
    else if (arg == "--width")
      o.Width = std::stoi(next());
    else if (arg == "--height")
      o.Height = std::stoi(next());
    else if (arg == "--runs")
      o.Runs = std::stoi(next());
    else if (arg == "--csv")
      o.Csv = next();
    else if (arg == "--profile")
      o.Profile = true;
    else if (arg == "--persistent-only")
      o.PersistentOnly = true;
    else if (arg == "--warm-start")
      o.WarmStart = true;
    else if (arg == "--transfers")
      o.Transfers = true;
    else if (arg == "--fresh-scratch")
      o.FreshScratch = true;
    else if (arg == "--general-kernel")
      o.GeneralKernel = true;
    else if (arg == "--cold-lattice")
      o.ColdLattice = true;
    else if (arg == "--plain-warm-start")
      o.PlainWarmStart = true;
    else if (arg == "--host-hand-off")
      o.HostHandOff = true;
    else if (arg == "--only")
    {
      o.Only = next();
      std::string rest = o.Only + ",";
      for (size_t comma; (comma = rest.find(',')) != std::string::npos; rest.erase(0, comma + 1))
      {
        const std::string key = rest.substr(0, comma);
        if (key != "camera" && key != "light" && key != "material" && key != "full")
        {
          std::cerr << "BenchmarkInteractive: --only " << o.Only << ": unknown interaction '" << key
                    << "' (valid: camera, light, material, full, comma-separated)\n";
          return 2;
        }
      }
    }
    else
    {
      std::cerr
        << "usage: BenchmarkInteractive [--size N] [--photons P] [--width W] "
           "[--height H] [--runs R] [--csv FILE] [--profile] [--persistent-only] "
           "[--warm-start] [--transfers] [--fresh-scratch] [--general-kernel] [--cold-lattice] "
           "[--host-hand-off] [--only camera,light,material,full]\n";
      return 2;
    }
  }
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::cerr << "BenchmarkInteractive: " << context->GetLastErrorMessage() << "\n";
    return 1;
  }
  std::cout << "BenchmarkInteractive: " << o.Size << "^3, " << o.Photons << " photons, " << o.Width
            << " x " << o.Height << ", " << o.Runs << " runs on " << context->GetDeviceName()
            << "\n";

  if (o.Transfers)
  {
    MeasureTransfers(context, o.Size, o.Runs);
  }
  context->SetProfileKernels(o.Profile);
  vtkOpenCLKernelProfile* profile = context->GetKernelProfile();
  Scene scene(o.Size);
  auto persistent = MakePipeline(scene, o);
  persistent->SetLatticeWarmStart(o.WarmStart);
  Seconds([&] { return persistent->Render(o.Width, o.Height); }); // compile, upload, light
  std::cout << "  plan: " << persistent->GetEffectPlan()->GetSummary() << "\n";

  using refracta::bench::Median;
  using refracta::bench::Table;
  Table table({ "interaction", "fresh_s", "persistent_s", "speedup", "plan_s", "lighting_s",
    "view_s", "frames_per_s", "device_s", "cl_host_s", "lattice_steps" });
  int frame = 0;
  for (const Interaction& interaction : Interactions())
  {
    const std::string key = interaction.Name.substr(0, interaction.Name.find(' '));
    if (!o.Only.empty() && ("," + o.Only + ",").find("," + key + ",") == std::string::npos)
    {
      continue;
    }
    std::vector<double> fresh, kept, device, clHost, steps,
      stage[vtkRefractaRenderPipeline::NUMBER_OF_STAGES];
    std::string kernels;
    for (int r = 0; r < o.Runs; ++r)
    {
      interaction.Change(scene, frame++);
      persistent->SetMedium(scene.Medium());
      profile->Reset();
      kept.push_back(Seconds([&] { return persistent->Render(o.Width, o.Height); }));
      profile->Collect();
      device.push_back(profile->GetTotalDeviceSeconds());
      clHost.push_back(profile->GetTotalHostSeconds());
      steps.push_back(persistent->GetStageRan(vtkRefractaRenderPipeline::LIGHTING)
          ? persistent->GetLatticeSolver()->GetIterations()
          : 0);
      kernels = profile->GetTable();
      for (int s = 0; s < vtkRefractaRenderPipeline::NUMBER_OF_STAGES; ++s)
      {
        stage[s].push_back(persistent->GetStageSeconds(s));
      }
      if (!o.PersistentOnly)
      {
        auto before = MakePipeline(scene, o); // the state a front end without the pipeline had
        fresh.push_back(Seconds([&] { return before->Render(o.Width, o.Height); }));
      }
    }
    const double f = Median(fresh), k = Median(kept);
    table.AddRow({ interaction.Name, Table::Format(f), Table::Format(k), Table::Format(f / k),
      Table::Format(Median(stage[0])), Table::Format(Median(stage[1])),
      Table::Format(Median(stage[2])), Table::Format(1.0 / k), Table::Format(Median(device)),
      Table::Format(Median(clHost)), Table::Format(Median(steps)) });
    if (o.Profile)
    {
      std::cout << "Kernels of the last persistent '" << interaction.Name << "' frame:\n"
                << kernels << "\n";
    }
  }
  table.Print("Interactive re-rendering: fresh pipeline per frame vs one persistent pipeline "
              "(medians, seconds)");
  if (!o.Csv.empty() && !table.WriteCsv(o.Csv))
  {
    std::cerr << "BenchmarkInteractive: cannot write " << o.Csv << "\n";
    return 1;
  }
  return 0;
}
