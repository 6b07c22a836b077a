#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkMediumValidator.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLMemoryPlan.h"
#include "vtkRefractaHostThreads.h"
#include "vtkRefractaSettings.h"

#include "photon_tallies.cl" // the layout of the tallies and counters, shared with the kernels

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkPhotonTracer);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, PrimaryTolerance, 0.0, 1e30);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, SecondaryTolerance, 0.0, 1e30);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, SecondaryStepLimit, 1e-3, 1e6);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, MinimumStep, 1e-3, 1e6);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, MaximumStep, 1e-3, 1e6);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, FixedStep, 1e-3, 1e6);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, ExtinctionStepLimit, 0.0, 1e30);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, RouletteThreshold, 0.0, 1.0);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, VolumeCausticPiecesPerFineVoxel, 0.0, 1e30);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, MaximumTurn, 1e-3, 2.0);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, StepTolerance, 0.0, 1.0);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, SmoothingBias, 0.0, 1e30);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, LightRadius, 0.0, 1e30);
vtkRefractaCxxSetClampMacro(vtkPhotonTracer, DirectionalLightAngularRadius, 0.0, 45.0);
vtkRefractaCxxSetVector3Macro(vtkPhotonTracer, BackgroundColor);
vtkRefractaCxxSetVector3Macro(vtkPhotonTracer, EnvironmentUp);
vtkRefractaCxxSetVector3Macro(vtkPhotonTracer, EnvironmentRight);

using namespace vtkPhotonTracerDetail;

namespace
{
// Progress at the end of each stage, in proportion to the work measured for 2^20 photons in a
// curved, scattering 96^3 to 128^3 medium on the 2-core CPU (octree and gradient ~1%, generation
// ~1%, marching ~97%, resolve and smoothing ~1%).
constexpr double ProgressGenerated = 0.02;
constexpr double ProgressMarched = 0.99;
// Automatic photon batches: each launch is sized to take about TargetBatchSeconds.
constexpr double TargetBatchSeconds = 0.05;
constexpr size_t MinimumBatch = 1024;
constexpr size_t MaximumBatch = size_t(1) << 20;
// Curved steps are halved at most this often by the step control (StepTolerance).
constexpr int MaximumHalvings = 6;

}

//------------------------------------------------------------------------------
vtkPhotonTracer::vtkPhotonTracer()
{
  vtkRefractaHostThreads::UseThreadedBackend();
  this->Lights = vtkSmartPointer<vtkLightCollection>::New();
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

vtkPhotonTracer::~vtkPhotonTracer() = default;

//------------------------------------------------------------------------------
void vtkPhotonTracer::AddLight(vtkLight* light)
{
  if (light)
  {
    this->Lights->AddItem(light);
    this->Modified();
  }
}

void vtkPhotonTracer::RemoveAllLights()
{
  this->Lights->RemoveAllItems();
  this->Modified();
}

void vtkPhotonTracer::SetLights(vtkLightCollection* lights)
{
  this->Lights = lights ? vtkSmartPointer<vtkLightCollection>(lights)
                        : vtkSmartPointer<vtkLightCollection>::New();
  this->Modified();
}

vtkLightCollection* vtkPhotonTracer::GetLights()
{
  return this->Lights;
}

void vtkPhotonTracer::SetContext(vtkOpenCLContext* context)
{
  if (this->Context != context)
  {
    this->Context = context;
    this->Modified();
  }
}

vtkOpenCLContext* vtkPhotonTracer::GetContext()
{
  return this->Context ? this->Context.Get() : vtkOpenCLContext::GetDefault();
}

vtkMTimeType vtkPhotonTracer::GetMTime()
{
  // A light changed after being added must re-run the pass.
  vtkMTimeType t = this->Superclass::GetMTime();
  vtkLight* light;
  vtkCollectionSimpleIterator it;
  for (this->Lights->InitTraversal(it); (light = this->Lights->GetNextLight(it));)
  {
    t = std::max(t, light->GetMTime());
  }
  if (this->MediumToWorld)
  {
    t = std::max(t, this->MediumToWorld->GetMTime());
  }
  if (this->BackgroundIlluminates && this->EnvironmentMap)
  {
    t = std::max(t, this->EnvironmentMap->GetMTime());
  }
  return this->Surfaces ? std::max(t, this->Surfaces->GetMTime()) : t;
}

int vtkPhotonTracer::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::ReportProgress(Internals& run, double progress)
{
  run.Progress = std::max(run.Progress, std::min(progress, 1.0));
  this->UpdateProgress(run.Progress);
  run.Aborted = run.Aborted || this->GetAbortExecute();
  return !run.Aborted;
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::InitializeDevice(Internals& run)
{
  const Medium& m = run.M;
  run.Context = this->GetContext();
  vtkOpenCLContext* ctx = run.Context;
  if (!ctx->Initialize())
  {
    vtkErrorMacro("No OpenCL device for the photon pass: " << ctx->GetLastErrorMessage());
    return false;
  }
  this->UsedCurvedRays = m.Curved;
  this->UsedExtinction = m.Attenuates;
  this->UsedDeposit = m.Scatters;
  this->UsedNodePlaneCuts = m.NodeCuts;
  this->UsedOctree = m.Curved && this->AdaptiveStepping;
  this->ComputedGradient = m.Curved && !m.HasGradient;

  run.Alloc = Allocator{ ctx, this };
  if (this->ReuseScratchBuffers)
  {
    if (!this->Scratch)
    {
      this->Scratch = std::make_unique<ScratchPool>();
    }
    run.Alloc.Pool = this->Scratch.get();
  }
  return true;
}

//------------------------------------------------------------------------------
// Stage 2: generation.
bool vtkPhotonTracer::GeneratePhotons(Internals& run)
{
  Medium& m = run.M;
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  const size_t photons = run.Photons;
  vtkOpenCLBuffer& pos = run.Pos;
  vtkOpenCLBuffer& dirs = run.Dirs;
  vtkOpenCLBuffer& power = run.Power;
  const std::vector<LightSetup>& lights = run.Lights;
  const auto start = Clock::now();
  // The device works in units of the total power sent towards the box (`unit`), so that one
  // compiled program serves every light set up. Every sum (a voxel's deposits, a tally, a
  // direction sum weighted by three channels) is then bounded by 1, plus roulette boosts; 16
  // leaves room for both. The host multiplies the results back by `unit`.
  run.Unit = run.TotalBound > 0 ? run.TotalBound : 1.0;
  run.Scale = vtkOpenCLContext::ChooseFixedPointScale(16.0) / run.Unit;
  const double unit = run.Unit;
  const double deviceScale = vtkOpenCLContext::ChooseFixedPointScale(16.0);
  std::ostringstream scaleLiteral;
  scaleLiteral << "0x1p" << std::ilogb(deviceScale) << "f";
  std::ostringstream options;
  options << "-DREFRACTA_FIXED_SCALE=" << scaleLiteral.str() << " -DREFRACTA_REFRACT=" << m.Curved
          << " -DREFRACTA_ADAPTIVE=" << this->AdaptiveStepping
          << " -DREFRACTA_EXTINCTION=" << m.Attenuates << " -DREFRACTA_DEPOSIT=" << m.Scatters
          << " -DREFRACTA_NODE_CUTS=" << m.NodeCuts
          << " -DREFRACTA_GREY_EXTINCTION=" << (m.ExtinctionChannels == 1)
          << " -DREFRACTA_GREY_ALBEDO=" << (m.AlbedoChannels == 1)
          << " -DREFRACTA_MIN_STEP=" << vtkOpenCLContext::FloatLiteral(this->MinimumStep)
          << " -DREFRACTA_MAX_STEP=" << vtkOpenCLContext::FloatLiteral(this->MaximumStep)
          << " -DREFRACTA_CAP_STEP="
          << vtkOpenCLContext::FloatLiteral(std::min(this->SecondaryStepLimit, this->MaximumStep))
          << " -DREFRACTA_FIXED_STEP=" << vtkOpenCLContext::FloatLiteral(this->FixedStep)
          << " -DREFRACTA_MAX_STEPS=" << this->MaximumNumberOfSteps
          << " -DREFRACTA_MAX_INTERFACES=" << this->MaximumNumberOfInterfaceEvents
          << " -DREFRACTA_EXT_STEP_LIMIT="
          << vtkOpenCLContext::FloatLiteral(this->ExtinctionStepLimit)
          << " -DREFRACTA_ROULETTE=" << vtkOpenCLContext::FloatLiteral(this->RouletteThreshold)
          << " -DREFRACTA_MAX_TURN=" << vtkOpenCLContext::FloatLiteral(this->MaximumTurn)
          << " -DREFRACTA_STEP_TOLERANCE=" << vtkOpenCLContext::FloatLiteral(this->StepTolerance)
          << " -DREFRACTA_MAX_HALVINGS=" << (this->StepTolerance > 0 ? MaximumHalvings : 0);
  const bool interfaces = run.Surfaces && run.Surfaces->GetNumberOfDielectricTriangles() > 0;
  // The analog events (run.Analog, decided with the memory plan) live in the surfaces' event loop,
  // which with an empty set (no BVH nodes) is the plain march with scattering added.
  options << " -DREFRACTA_SURFACES=" << (run.Surfaces || run.Analog ? 1 : 0)
          << " -DREFRACTA_INTERFACES=" << (interfaces ? 1 : 0);
  run.Caustic = interfaces ? this->CausticSubdivision : 1;
  while (run.Caustic > 1 &&
    run.Surfaces->GetNumberOfTexels() * run.Caustic * run.Caustic >
      this->MaximumNumberOfCausticTexels)
  {
    --run.Caustic; // the fine texels must fit their budget
  }
  this->LastCausticSubdivision = run.Caustic;
  options << " -DREFRACTA_CAUSTIC_SUBDIVISION=" << run.Caustic;
  options << " -DREFRACTA_ANALOG=" << (run.Analog ? 1 : 0)
          << " -DREFRACTA_SIDED_DEPOSITS=" << (run.Cuts && m.Scatters ? 1 : 0);
  // Direct surface light left to straight light rays: only where they give what the photons
  // would: photons that fly straight (the rays cut voxels at node planes as the photons do,
  // LR_NODE_CUTS), from delta lights the rays sample exactly (not the sky,
  // whose photons the rays do not carry, nor extended lights, whose penumbra a fixed quadrature
  // would band), onto Lambertian triangles.
  const bool sky =
    std::any_of(lights.begin(), lights.end(), [](const LightSetup& l) { return l.Environment; });
  const bool extended =
    std::any_of(lights.begin(), lights.end(), [](const LightSetup& l) { return l.Extent > 0.0; });
  const bool lambertian = run.Surfaces &&
    run.Surfaces->GetNumberOfTriangles() > run.Surfaces->GetNumberOfDielectricTriangles();
  this->LastSkippedDirectSurfaceLight =
    this->SkipDirectSurfaceLight && lambertian && !m.Curved && !sky && !extended;
  options << " -DREFRACTA_SKIP_DIRECT=" << (this->LastSkippedDirectSurfaceLight ? 1 : 0);
  this->UsesVolumeCaustic(run); // a run-time choice of the kernels (their last arguments)
  if (run.SplitOrders > 0)
  {
    options << " -DREFRACTA_ANALOG_ORDERS=" << run.SplitOrders;
  }
  if (run.Lobes > 1)
  {
    options << " -DREFRACTA_LOBES=" << run.Lobes;
  }
  run.Trace = ctx->GetProgram(
    { "refracta_atomics.cl", "refracta_common.cl", "photon_tallies.cl", "refracta_surfaces.cl",
      "photon_trace.cl", "photon_surfaces.cl", "photon_march.cl", "photon_generate.cl",
      "photon_environment.cl" },
    options.str(), this);
  cl_program trace = run.Trace;
  if (!trace)
  {
    return false;
  }
  pos = alloc.Make(CL_MEM_READ_WRITE, photons * sizeof(cl_float4), nullptr, "photon positions");
  dirs = alloc.Make(CL_MEM_READ_WRITE, photons * sizeof(cl_float4), nullptr, "photon directions");
  power = alloc.Make(CL_MEM_READ_WRITE, photons * sizeof(cl_float4), nullptr, "photon powers");
  if (!pos || !dirs || !power || !ctx->ZeroBuffer(power.Get(), photons * sizeof(cl_float4), this))
  {
    return false;
  }
  vtkOpenCLKernel generate = ctx->CreateKernel(trace, "photon_generate", this);
  if (!generate)
  {
    return false;
  }
  // Each light's two lattice rotations, and every slot's random stream.
  uint64_t seedState = 0x5eedULL ^ (static_cast<uint64_t>(this->Seed) << 17);
  std::vector<std::array<cl_uint, 2>> rotations;
  for (size_t l = 0; l < lights.size(); ++l)
  {
    rotations.push_back({ SplitMix(seedState), SplitMix(seedState) });
  }
  if (!this->Streams)
  {
    this->Streams = std::make_unique<PhotonStreams>();
  }
  const std::vector<cl_uint>& streams =
    this->Streams->Update(photons, lights, rotations, this->CoherentPhotonOrder, run.VolumeCaustic);
  // Made empty and written (not copied at creation): a scratch buffer, kept with the others.
  run.Streams = alloc.Make(CL_MEM_READ_ONLY, photons * sizeof(cl_uint), nullptr, "photon streams");
  if (!run.Streams ||
    !ctx->WriteBuffer(run.Streams.Get(), photons * sizeof(cl_uint), streams.data(), this))
  {
    return false;
  }
  cl_uint offset = 0;
  for (const auto& ls : lights)
  {
    const cl_uint count = ls.Photons;
    const cl_uint r1 = rotations[&ls - lights.data()][0];
    const cl_uint r2 = rotations[&ls - lights.data()][1];
    if (count == 0)
    {
      continue;
    }
    if (ls.Environment) // the sky (vtkPhotonTracerEnvironment.cxx)
    {
      if (!this->GenerateEnvironmentPhotons(run, &ls - lights.data(), offset, r1, r2))
      {
        return false;
      }
      offset += count;
      continue;
    }
    const cl_int positional = ls.Positional ? 1 : 0;
    const cl_float4 params =
      Float4(1.0 - ls.OneMinusCos, ls.Exponent, ls.Measure / count, ls.OneMinusCos);
    if (!ctx->Check(
          vtkOpenCLSetKernelArgs(generate.Get(), pos.Get(), dirs.Get(), power.Get(),
            run.Streams.Get(), offset, count, positional, Float4(ls.Origin), Float4(ls.Axis),
            Float4(ls.Basis1), Float4(ls.Basis2), Float4(ls.SpotAxis, ls.SpotCos), params,
            Float4(ls.Colour[0] / unit, ls.Colour[1] / unit, ls.Colour[2] / unit),
            Float4(run.EmitLo), Float4(run.EmitHi), r1, r2, static_cast<cl_float>(ls.Extent),
            static_cast<cl_float>(ls.Lead),
            static_cast<cl_float>(run.LightLobes[&ls - lights.data()])),
          "clSetKernelArg(photon_generate)", this) ||
      !Run1D(ctx, generate.Get(), count, "photon_generate", this))
    {
      return false;
    }
    offset += count;
  }
  if (!ctx->Finish(this))
  {
    return false;
  }
  this->GenerationSeconds = Seconds(start);
  return this->ReportProgress(run, ProgressGenerated);
}

//------------------------------------------------------------------------------
// Stage 3: marching.
bool vtkPhotonTracer::MarchPhotons(Internals& run)
{
  Medium& m = run.M;
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  const size_t voxels = m.Voxels;
  const cl_int4 dims = Int4(m.Dims);
  const cl_float4 spacing = Float4(m.Spacing);
  const size_t photons = run.Photons;
  const double scale = run.Scale;
  cl_program trace = run.Trace;
  vtkOpenCLBuffer& nBuffer = run.NBuffer;
  vtkOpenCLBuffer& gradBuffer = run.GradBuffer;
  vtkOpenCLBuffer& octree = run.Octree;
  vtkOpenCLBuffer& pos = run.Pos;
  vtkOpenCLBuffer& dirs = run.Dirs;
  vtkOpenCLBuffer& power = run.Power;
  vtkOpenCLBuffer& extBuffer = run.ExtBuffer;
  vtkOpenCLBuffer& albBuffer = run.AlbBuffer;
  vtkOpenCLBuffer& deposits = run.Deposits;
  vtkOpenCLBuffer& tallies = run.Tallies;
  vtkOpenCLBuffer& counters = run.Counters;
  const auto start = Clock::now();
  // Six per voxel (RGB power, then the direction sums): one cache line per deposit; with S1 in
  // lobes a block of them for all of S1, then one per lobe.
  const size_t accumulators = m.Scatters ? voxels * 6 * run.DepositBlocks() : 1;
  if (!run.ReusedMedium)
  {
    std::vector<float> grey;
    extBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
      (m.Attenuates ? voxels * m.ExtinctionChannels : 1) * sizeof(float),
      DeviceChannels(m.Extinction, m.ExtinctionChannels, grey).data(), "Extinction");
    albBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
      (m.Scatters ? voxels * m.AlbedoChannels : 1) * sizeof(float),
      DeviceChannels(m.Albedo, m.AlbedoChannels, grey).data(), "Albedo");
  }
  deposits = alloc.Make(CL_MEM_READ_WRITE, accumulators * sizeof(cl_long), nullptr,
    "radiance and direction accumulators");
  tallies = alloc.Make(CL_MEM_READ_WRITE, PHOTON_TALLY_COUNT * sizeof(cl_long), nullptr, "tallies");
  counters =
    alloc.Make(CL_MEM_READ_WRITE, PHOTON_COUNTER_COUNT * sizeof(cl_long), nullptr, "counters");
  const cl_uint photonCount = static_cast<cl_uint>(photons);
  const cl_uint seed = this->Seed;
  // Both march kernels take the common arguments, the index of the launch's first photon (set
  // again for every launch, at firstPhotonArg), their own, the surfaces' and the volume
  // caustic's, each group appended where the one before ended. Returns the index of the volume
  // caustic's first argument, 0 on failure.
  cl_uint firstPhotonArg = 0;
  auto setMarchArguments = [&](cl_kernel kernel, const char* what, const auto&... own) -> cl_uint
  {
    cl_uint next = 0;
    const cl_uint firstPhoton = 0;
    const bool set =
      ctx->Check(vtkOpenCLAppendKernelArgs(kernel, next, pos.Get(), dirs.Get(), power.Get(),
                   run.Streams.Get(), photonCount, nBuffer.Get(), gradBuffer.Get(), extBuffer.Get(),
                   albBuffer.Get(), octree.Get(), dims, spacing, deposits.Get(), tallies.Get(),
                   counters.Get(), seed),
        what, this) &&
      (firstPhotonArg = next,
        ctx->Check(vtkOpenCLAppendKernelArgs(kernel, next, firstPhoton, own...), what, this)) &&
      this->SetSurfaceArguments(run, kernel, next);
    return set ? next : 0;
  };
  vtkOpenCLKernel march = ctx->CreateKernel(trace, "photon_march", this);
  cl_uint marchCausticArg = 0;
  if (!extBuffer || !albBuffer || !deposits || !tallies || !counters || !march ||
    !this->UploadSurfaces(run) || !this->UploadAnalogScattering(run) ||
    (marchCausticArg = setMarchArguments(march.Get(), "clSetKernelArg(photon_march)")) == 0 ||
    !ctx->ZeroBuffer(deposits.Get(), accumulators * sizeof(cl_long), this) ||
    !ctx->ZeroBuffer(tallies.Get(), PHOTON_TALLY_COUNT * sizeof(cl_long), this) ||
    !ctx->ZeroBuffer(counters.Get(), PHOTON_COUNTER_COUNT * sizeof(cl_long), this))
  {
    return false;
  }
  // Launches of `kernel` over photons [first, first + count), at most `chunk` each.
  const size_t chunk = size_t(1) << 16;
  auto runMarch = [&](cl_kernel kernel, const char* name, size_t first, size_t count)
  {
    for (size_t sub = first; sub < first + count; sub += chunk)
    {
      const cl_uint firstPhoton = static_cast<cl_uint>(sub);
      if (!ctx->Check(vtkOpenCLSetKernelArgsFrom(kernel, firstPhotonArg, firstPhoton),
            "clSetKernelArg(first photon)", this) ||
        !Run1D(ctx, kernel, std::min(chunk, first + count - sub), name, this))
      {
        return false;
      }
    }
    return true;
  };
  this->NumberOfChunks = 0;
  this->NumberOfBatches = 0;
  if (this->StepsPerChunk > 0)
  {
    // Chunked march (photon_march_chunk): all photons advance k steps per launch; the callback
    // (e.g. the Lattice-Boltzmann diffusion of what is already deposited) is enqueued between
    // launches.
    vtkOpenCLKernel marchChunk = ctx->CreateKernel(trace, "photon_march_chunk", this);
    vtkOpenCLBuffer state = alloc.Make(CL_MEM_READ_WRITE,
      photons * PHOTON_STATE_FLOAT4S * sizeof(cl_float4), nullptr, "photon state");
    vtkOpenCLBuffer status =
      alloc.Make(CL_MEM_READ_WRITE, photons * sizeof(cl_uint4), nullptr, "photon status");
    vtkOpenCLBuffer active = alloc.Make(CL_MEM_READ_WRITE, sizeof(cl_int), nullptr, "active");
    const cl_uint k = static_cast<cl_uint>(this->StepsPerChunk);
    cl_uint causticArg = 0;
    if (!marchChunk || !state || !status || !active ||
      (causticArg = setMarchArguments(marchChunk.Get(), "clSetKernelArg(photon_march_chunk)",
         state.Get(), status.Get(), k, active.Get())) == 0 ||
      !this->SetVolumeCausticArguments(run, marchChunk.Get(), causticArg, 0) ||
      !ctx->ZeroBuffer(status.Get(), photons * sizeof(cl_uint4), this))
    {
      return false;
    }
    const double radianceFactor = 1.0 / (scale * m.Spacing[0] * m.Spacing[1] * m.Spacing[2]);
    // Curved rays stop at MaximumNumberOfSteps; straight ones cross at most the grid's diagonal
    // in voxel edges. The bound only guards against a hang.
    const size_t bound = static_cast<size_t>(this->MaximumNumberOfSteps) + 4 +
      static_cast<size_t>(2 * (m.Dims[0] + m.Dims[1] + m.Dims[2]) *
        std::max({ m.Spacing[0], m.Spacing[1], m.Spacing[2] }) /
        std::min({ m.Spacing[0], m.Spacing[1], m.Spacing[2] }));
    int stillActive = 1;
    for (size_t launch = 0; stillActive > 0 && launch * k <= bound; ++launch)
    {
      if (!ctx->ZeroBuffer(active.Get(), sizeof(cl_int), this))
      {
        return false;
      }
      if (!runMarch(marchChunk.Get(), "photon_march_chunk", 0, photons))
      {
        return false;
      }
      cl_int count = 0;
      if (!ctx->ReadBuffer(active.Get(), sizeof(cl_int), &count, this))
      {
        return false;
      }
      stillActive = count;
      ++this->NumberOfChunks;
      if (this->Callback &&
        (!this->SumLobeDeposits(run) ||
          !this->Callback(deposits.Get(), radianceFactor, 1.0 / scale, count)))
      {
        vtkErrorMacro("The chunk callback failed after chunk " << this->NumberOfChunks << ".");
        return false;
      }
      if (!this->ReportProgress(run,
            ProgressGenerated +
              (ProgressMarched - ProgressGenerated) * (1.0 - double(count) / photons)))
      {
        return false;
      }
    }
  }
  // Unchunked march: photons in batches of whole work-groups, each launch waited for, so that
  // progress is reported and an abort is seen between them. The deposits are fixed-point sums and
  // every photon's random stream depends on its index only, so the batches do not change the
  // result. PhotonBatchSize 0 sizes each batch from the rate measured so far to take about
  // TargetBatchSeconds (at most doubling from one batch to the next).
  auto launchMarch = [&](size_t first, size_t count)
  { return runMarch(march.Get(), "photon_march", first, count); };
  if (this->StepsPerChunk == 0 &&
    (!this->PlaceVolumeCausticBricks(run, launchMarch, march.Get(), marchCausticArg) ||
      !this->ReportProgress(run, ProgressGenerated)))
  {
    return false;
  }
  const size_t group = 64; // Run1D's work-group size: batches must be whole groups
  const bool automatic = this->PhotonBatchSize <= 0;
  size_t batch = automatic ? MinimumBatch : std::max<size_t>(this->PhotonBatchSize, 1);
  batch = (batch + group - 1) / group * group;
  for (size_t first = 0; this->StepsPerChunk == 0 && first < photons;)
  {
    const size_t count = std::min(batch, photons - first);
    const auto launchStart = Clock::now();
    if (!launchMarch(first, count) || !ctx->Finish(this))
    {
      return false;
    }
    first += count;
    ++this->NumberOfBatches;
    if (!this->ReportProgress(
          run, ProgressGenerated + (ProgressMarched - ProgressGenerated) * double(first) / photons))
    {
      return false;
    }
    if (automatic)
    {
      const double seconds = std::max(Seconds(launchStart), 1e-6);
      const double wanted = static_cast<double>(count) * TargetBatchSeconds / seconds;
      batch = static_cast<size_t>(std::min({ wanted, 2.0 * count, double(MaximumBatch) }));
      batch = std::max<size_t>(batch / group * group, MinimumBatch);
    }
  }
  std::vector<cl_long>& tally = run.Tally;
  std::vector<cl_long>& count = run.Count;
  tally.assign(PHOTON_TALLY_COUNT, 0);
  count.assign(PHOTON_COUNTER_COUNT, 0);
  if (!ctx->ReadBuffer(tallies.Get(), PHOTON_TALLY_COUNT * sizeof(cl_long), tally.data(), this) ||
    !ctx->ReadBuffer(counters.Get(), PHOTON_COUNTER_COUNT * sizeof(cl_long), count.data(), this))
  {
    return false;
  }
  this->MarchingSeconds = Seconds(start);
  return true;
}

//------------------------------------------------------------------------------
int vtkPhotonTracer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!output)
  {
    vtkErrorMacro("The output is not a vtkImageData.");
    return 0;
  }
  output->Initialize();
  this->OctreeSeconds = this->GenerationSeconds = this->MarchingSeconds = 0;
  this->SmoothingSeconds = this->PeakDeviceMemoryBytes = 0;
  this->PlannedDeviceMemoryBytes = this->PlannedHostMemoryBytes = 0;
  this->UsedCurvedRays = this->UsedExtinction = this->UsedDeposit = false;
  this->UsedNodePlaneCuts = false;
  this->UsedOctree = this->ComputedGradient = false;
  this->UsedSurfaces = this->LastRunReusedSurfaces = this->UsedEnvironment = false;
  this->UsedAnalogScattering = false;
  this->LastSkippedDirectSurfaceLight = false;
  this->UsedScatteringOrders = 0;
  this->EnvironmentPhotons = 0;
  this->LastNumberOfLobes = 1;
  this->LastRunAborted = false;
  // The last run's device copies of its output go before this run allocates its own.
  this->GetContext()->GetDeviceArrays()->ForgetOwner(this);
  Internals run;
  run.Input = input;
  // The medium kept from the last run was validated then; a new one is validated now.
  vtkNew<vtkMediumValidator> validator;
  this->LastRunReusedMedium = input && this->TakeCachedMedium(run);
  if (!this->LastRunReusedMedium && !validator->Validate(input))
  {
    vtkErrorMacro("Input 0 is not a valid Refracta medium: " << validator->GetErrorMessage());
    return 0;
  }
  if (!this->SetUpLights(run))
  {
    return 0;
  }
  this->AssignLobes(run);
  this->SharePhotons(run);
  if (!this->InitializeDevice(run) || !this->PlanMemory(run) || !this->BuildOctreeStage(run) ||
    !this->GeneratePhotons(run) || !this->MarchPhotons(run) || !this->ResolveRadiance(run) ||
    !this->ResolveMultipleScattering(run) || !this->ResolveSurfaces(run) ||
    !this->ResolveVolumeCaustic(run))
  {
    this->ReleaseScratchBuffers(); // what a failed or aborted run left is not kept
    if (run.Aborted)
    {
      // An abort is not an error: the output stays empty, the device buffers are released with
      // `run`, and the next Update() (AbortExecute off again) runs from the start.
      this->LastRunAborted = true;
      return 1;
    }
    return 0;
  }
  this->PeakDeviceMemoryBytes = run.Alloc.Bytes;
  if (run.Alloc.Pool)
  {
    run.Alloc.Pool->EndRun();
  }
  this->WriteOutput(run, output);
  this->WriteVolumeCausticOutput(run, output);
  this->KeepMedium(run);
  this->KeepSurfaces(run);
  this->ReportProgress(run, 1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::SetReuseScratchBuffers(bool reuse)
{
  if (reuse != this->ReuseScratchBuffers)
  {
    this->ReuseScratchBuffers = reuse;
    if (!reuse)
    {
      this->ReleaseScratchBuffers();
    }
    // No Modified(): the output does not depend on where the buffers come from.
  }
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::ReleaseScratchBuffers()
{
  this->Scratch.reset();
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfLights: " << this->Lights->GetNumberOfItems() << "\n";
  this->PrintEnvironment(os, indent);
  os << indent << "LightRadius: " << this->LightRadius << "\n";
  os << indent << "DirectionalLightAngularRadius: " << this->DirectionalLightAngularRadius << "\n";
  os << indent << "NumberOfPhotons: " << this->NumberOfPhotons << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "PrimaryTolerance: " << this->PrimaryTolerance << "\n";
  os << indent << "SecondaryTolerance: " << this->SecondaryTolerance << "\n";
  os << indent << "SecondaryStepLimit: " << this->SecondaryStepLimit << " voxels\n";
  os << indent << "MinimumStep: " << this->MinimumStep << " voxels\n";
  os << indent << "MaximumStep: " << this->MaximumStep << " voxels\n";
  os << indent << "AdaptiveStepping: " << this->AdaptiveStepping << "\n";
  os << indent << "FixedStep: " << this->FixedStep << " voxels\n";
  os << indent << "ExtinctionStepLimit: " << this->ExtinctionStepLimit << "\n";
  os << indent << "RouletteThreshold: " << this->RouletteThreshold << "\n";
  os << indent << "MaximumNumberOfSteps: " << this->MaximumNumberOfSteps << "\n";
  os << indent << "CoherentPhotonOrder: " << (this->CoherentPhotonOrder ? "On" : "Off") << "\n";
  os << indent << "KeepDeviceCopies: " << (this->KeepDeviceCopies ? "On" : "Off") << "\n";
  os << indent << "ReuseScratchBuffers: " << (this->ReuseScratchBuffers ? "On" : "Off") << " ("
     << (this->Scratch ? this->Scratch->Entries.size() : 0) << " kept)\n";
  os << indent << "MaximumNumberOfInterfaceEvents: " << this->MaximumNumberOfInterfaceEvents
     << "\n";
  os << indent << "CausticSubdivision: " << this->CausticSubdivision << "\n";
  os << indent << "MaximumNumberOfCausticTexels: " << this->MaximumNumberOfCausticTexels << "\n";
  os << indent << "LastCausticSubdivision: " << this->LastCausticSubdivision << "\n";
  this->PrintVolumeCaustic(os, indent);
  os << indent << "MaximumTurn: " << this->MaximumTurn << "\n";
  os << indent << "StepTolerance: " << this->StepTolerance << "\n";
  os << indent << "Smoothing: " << this->Smoothing << "\n";
  os << indent << "SmoothingBias: " << this->SmoothingBias << "\n";
  os << indent << "StepsPerChunk: " << this->StepsPerChunk << "\n";
  os << indent << "PhotonBatchSize: " << this->PhotonBatchSize << "\n";
  os << indent << "NumberOfBatches: " << this->NumberOfBatches << "\n";
  os << indent << "LastRunAborted: " << this->LastRunAborted << "\n";
  os << indent << "UseProxyBounds: " << this->UseProxyBounds << "\n";
  os << indent << "Surfaces: " << this->Surfaces.Get() << " (used " << this->UsedSurfaces
     << ", reused " << this->LastRunReusedSurfaces << ")\n";
  os << indent << "AnalogScattering: " << this->AnalogScattering << " (used "
     << this->UsedAnalogScattering << ")\n";
  os << indent << "SkipDirectSurfaceLight: " << this->SkipDirectSurfaceLight << " (last run "
     << this->LastSkippedDirectSurfaceLight << ")\n";
  os << indent << "ScatteringOrders: " << this->ScatteringOrders << " (used "
     << this->UsedScatteringOrders << ")\n";
  os << indent << "Stage seconds (octree, generation, marching, smoothing): " << this->OctreeSeconds
     << ", " << this->GenerationSeconds << ", " << this->MarchingSeconds << ", "
     << this->SmoothingSeconds << "\n";
  os << indent << "PeakDeviceMemoryBytes: " << this->PeakDeviceMemoryBytes << "\n";
  os << indent << "PlannedDeviceMemoryBytes: " << this->PlannedDeviceMemoryBytes << "\n";
  os << indent << "PlannedHostMemoryBytes: " << this->PlannedHostMemoryBytes << "\n";
  os << indent << "Plan: curved " << this->UsedCurvedRays << ", extinction " << this->UsedExtinction
     << ", deposit " << this->UsedDeposit << ", node-plane cuts " << this->UsedNodePlaneCuts
     << ", octree " << this->UsedOctree << ", gradient computed " << this->ComputedGradient << "\n";
}
