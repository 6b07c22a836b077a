#include "RefractaRenderReport.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLKernelProfile.h"
#include "vtkOpenCLMemoryPlan.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaViewPass.h"
#include "vtkSceneAnalysis.h"

#include <algorithm>
#include <iostream>
#include <map>
#include <sstream>
#include <unistd.h>

namespace RefractaRender
{
// ---------------------------------------------------------------------------------------------
StageReporter::StageReporter(vtkRefractaRenderPipeline* pipeline, bool quiet)
  : Pipeline(pipeline)
  , Terminal(isatty(STDOUT_FILENO) != 0)
{
  if (quiet)
  {
    return;
  }
  this->Command->SetClientData(this);
  this->Command->SetCallback(&StageReporter::OnEvent);
  for (unsigned long event :
    { vtkCommand::StartEvent, vtkCommand::EndEvent, vtkCommand::ProgressEvent })
  {
    this->Tags.push_back(pipeline->AddObserver(event, this->Command));
  }
}

StageReporter::~StageReporter()
{
  for (unsigned long tag : this->Tags)
  {
    this->Pipeline->RemoveObserver(tag);
  }
}

void StageReporter::OnEvent(vtkObject*, unsigned long event, void* client, void* call)
{
  auto* self = static_cast<StageReporter*>(client);
  if (event == vtkCommand::ProgressEvent)
  {
    self->Bar(*static_cast<double*>(call));
    return;
  }
  const char* stage = static_cast<const char*>(call);
  if (event == vtkCommand::StartEvent)
  {
    self->Stage.Start = std::chrono::steady_clock::now();
    self->Line(std::string("  ") + stage + " ...");
    return;
  }
  std::ostringstream line;
  line << "  " << stage << " done, " << self->Stage.Seconds() << " s";
  self->Line(line.str());
}

void StageReporter::Line(const std::string& text)
{
  std::cout << (this->Terminal ? "\r\033[K" : "") << text << std::endl;
  this->Drawn = -1;
}

void StageReporter::Bar(double fraction)
{
  const int width = 40;
  const int filled = static_cast<int>(fraction * width);
  if (!this->Terminal || filled == this->Drawn)
  {
    return;
  }
  this->Drawn = filled;
  std::cout << "\r  [" << std::string(filled, '#') << std::string(width - filled, ' ') << "] "
            << static_cast<int>(100 * fraction) << "%" << std::flush;
}

// ---------------------------------------------------------------------------------------------
json FieldDataToJson(vtkFieldData* fd)
{
  json out = json::object();
  for (int i = 0; fd && i < fd->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* a = fd->GetArray(i);
    if (!a || !a->GetName() || a->GetNumberOfTuples() != 1 ||
      std::string(a->GetName()) == vtkRefractaLightingVolume::SurfaceIrradianceName())
    {
      continue; // per-texel or per-voxel arrays (the surfaces' irradiance, caustics) are no statistic
    }
    if (a->GetNumberOfComponents() == 1)
    {
      out[a->GetName()] = a->GetComponent(0, 0);
    }
    else
    {
      json v = json::array();
      for (int c = 0; c < a->GetNumberOfComponents(); ++c)
      {
        v.push_back(a->GetComponent(0, c));
      }
      out[a->GetName()] = v;
    }
  }
  return out;
}

void AddStageSeconds(vtkRefractaImageRenderer* renderer, json& seconds)
{
  vtkRefractaRenderPipeline* pipeline = renderer->GetPipeline();
  seconds["plan"] = pipeline->GetStageSeconds(vtkRefractaRenderPipeline::PLAN);
  seconds["light_pass"] = pipeline->GetStageSeconds(vtkRefractaRenderPipeline::LIGHTING);
  seconds["view_pass"] = pipeline->GetStageSeconds(vtkRefractaRenderPipeline::VIEW);
  seconds["view_pass_device"] = renderer->GetViewPass()->GetLastSeconds();
}

json PlanReport(vtkRefractaRenderPipeline* pipeline)
{
  vtkEffectPlan* plan = pipeline->GetEffectPlan();
  json report;
  report["summary"] = plan->GetSummary();
  vtkSceneAnalysis* analysis = pipeline->GetSceneAnalysis();
  report["analysis"] = analysis->GetSummary();
  report["voxel_optical_depth"] = analysis->GetMaximumVoxelOpticalDepth();
  report["under_resolved"] = analysis->IsUnderResolved();
  report["tolerance"] = plan->GetTolerance();
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    report["effects"][vtkEffectPlan::GetEffectName(e)] = { { "enabled", plan->IsEnabled(e) },
      { "estimated_change", plan->GetEstimatedContribution(e) }, { "reason", plan->GetReason(e) } };
  }
  report["single_scattering_method"] = { { "requested",
                                           vtkEffectPlan::GetSingleScatteringMethodName(
                                             plan->GetSingleScatteringMethod()) },
    { "chosen",
      vtkEffectPlan::GetSingleScatteringMethodName(plan->GetChosenSingleScatteringMethod()) },
    { "reason", plan->GetSingleScatteringMethodReason() } };
  return report;
}

json LightPassReport(vtkRefractaRenderPipeline* pipeline, int lightCount)
{
  vtkEffectPlan* plan = pipeline->GetEffectPlan();
  vtkImageData* lighting = pipeline->GetLighting();
  json report;
  if (!lighting)
  {
    report["skipped"] = lightCount == 0
      ? std::string("no lights")
      : std::string("single scattering ") + plan->GetReason(vtkEffectPlan::SINGLE_SCATTERING);
    return report;
  }
  vtkPhotonTracer* tracer = pipeline->GetPhotonTracer();
  report = FieldDataToJson(lighting->GetFieldData());
  report["octree_seconds"] = tracer->GetOctreeSeconds();
  report["generation_seconds"] = tracer->GetGenerationSeconds();
  report["marching_seconds"] = tracer->GetMarchingSeconds();
  report["smoothing_seconds"] = tracer->GetSmoothingSeconds();
  report["curved_rays"] = tracer->GetUsedCurvedRays();
  report["octree"] = tracer->GetUsedOctree();
  report["device_memory_planned_bytes"] = tracer->GetPlannedDeviceMemoryBytes();
  report["device_memory_used_bytes"] = tracer->GetPeakDeviceMemoryBytes();
  report["host_memory_planned_bytes"] = tracer->GetPlannedHostMemoryBytes();
  report["photon_seconds"] = pipeline->GetStageSeconds(vtkRefractaRenderPipeline::LIGHTING);
  report["volume_caustic"] = { { "subdivision", tracer->GetLastVolumeCausticSubdivision() },
    { "bricks", tracer->GetLastNumberOfVolumeCausticBricks() } };
  if (tracer->GetUsedSurfaces())
  {
    // Where the lit surfaces' direct light came from (photons where they curve or the sky
    // lights the scene, whatever was asked).
    report["direct_surface_light"] = {
      { "method", pipeline->GetLastDirectSurfaceLightByRays() ? "light_rays" : "photons" },
      { "seconds",
        pipeline->GetLastDirectSurfaceLightByRays() ? pipeline->GetLightRays()->GetSurfaceSeconds()
                                                    : 0.0 }
    };
  }
  if (plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING))
  {
    // The plan's method, the orders the photons carried (0 none, k, -1 every order) and, where
    // the lattice ran, its solve.
    json ms = { { "method",
                  vtkEffectPlan::GetMultipleScatteringMethodName(
                    plan->GetChosenMultipleScatteringMethod()) },
      { "reason", plan->GetMultipleScatteringMethodReason() },
      { "photon_orders", tracer->GetUsedScatteringOrders() } };
    if (tracer->GetUsedScatteringOrders() != vtkPhotonTracer::EVERY_ORDER)
    {
      ms["iterations"] = report.value("LatticeBoltzmannIterations", 0.0);
      ms["residual"] = report.value("LatticeBoltzmannResidual", 0.0);
      ms["converged"] = report.value("LatticeBoltzmannConverged", 0.0) != 0.0;
      ms["schedule"] = pipeline->GetLastScheduleInterleaved() ? "interleaved" : "sequential";
      // The lattice's update: blocks in local memory, or the global update (block size 0, or a
      // device whose local memory is ordinary memory: vtkLatticeBoltzmannSolver::BlockPolicy).
      vtkLatticeBoltzmannSolver* solver = pipeline->GetLatticeSolver();
      ms["update"] = solver->UsesBlocks()
        ? "blocks of " + std::to_string(solver->GetBlockSize()) + "^3"
        : std::string(solver->GetBlockSize() > 0 ? "global (the device has no on-chip local memory)"
                                                 : "global");
      ms["lattice"] = "D3Q" + std::to_string(solver->GetLattice());
      ms["seconds"] = report.value("ScheduleFinalSolveSeconds", 0.0);
      // The coarse start's steps (all coarser grids) and their cost in steps of the full grid.
      ms["coarse_start_steps"] = solver->GetCoarseStartSteps();
      ms["coarse_start_cost"] = solver->GetCoarseStartCost();
      ms["device_memory_planned_bytes"] =
        pipeline->GetLatticeSolver()->GetPlannedDeviceMemoryBytes();
    }
    report["multiple_scattering"] = ms;
  }
  else
  {
    report["multiple_scattering"] =
      std::string("off (") + plan->GetReason(vtkEffectPlan::MULTIPLE_SCATTERING) + ")";
  }
  return report;
}

json ViewPassReport(vtkRefractaImageRenderer* renderer)
{
  vtkRefractaViewPass* view = renderer->GetViewPass();
  int size[2];
  renderer->GetImageSize(size);
  return { { "curved_rays", view->GetLastCurved() }, { "total_steps", view->GetLastTotalSteps() },
    { "steps_per_pixel", view->GetLastTotalSteps() / (double(size[0]) * size[1]) },
    { "empty_space_skipping", view->GetLastSkipping() },
    { "active_cell_fraction", view->GetLastActiveCellFraction() },
    { "lane_marching", view->GetLastLaneMarching() },
    { "buffer_tiles", view->GetLastNumberOfBufferTiles() },
    { "fine_caustic_texels", view->GetLastNumberOfFineCausticTexels() },
    { "supersampled_pixels", view->GetLastNumberOfSupersampledPixels() },
    { "device_memory_planned_bytes", view->GetPlannedDeviceMemoryBytes() },
    { "memory_plan", view->GetMemoryPlan()->GetSummary() } };
}

// ---------------------------------------------------------------------------------------------
namespace
{
// Adds the components of report[key], one by one, to `sum` where it is an array of 3 numbers.
bool Sum3(const json& report, const char* key, double& sum)
{
  const json a = report.value(key, json::array());
  if (a.size() != 3)
  {
    return false;
  }
  for (const json& component : a)
  {
    sum += component.get<double>();
  }
  return true;
}

// "light", "multiple" and "energy" lines: photons, the Lattice-Boltzmann solve, the balance.
void PrintLightPass(const json& light)
{
  if (light.contains("skipped"))
  {
    std::cout << "  light     skipped: " << light["skipped"].get<std::string>() << "\n";
    return;
  }
  std::cout << "  light     " << light.value("NumberOfPhotons", 0.0) << " photons, "
            << (light.value("curved_rays", false) ? "curved" : "straight") << " paths, "
            << light.value("TotalSteps", 0.0) << " steps, " << light.value("photon_seconds", 0.0)
            << " s\n";
  if (light.contains("direct_surface_light"))
  {
    const json& direct = light["direct_surface_light"];
    std::cout << "  direct    surfaces' direct light by "
              << (direct["method"] == "light_rays" ? "light rays (" +
                       std::to_string(direct["seconds"].get<double>()) + " s), photons for the rest"
                                                   : std::string("photons"))
              << "\n";
  }
  const json volumeCaustic = light.value("volume_caustic", json::object());
  if (volumeCaustic.value("subdivision", 1) > 1)
  {
    const int c = volumeCaustic["subdivision"].get<int>();
    std::cout << "  caustic   " << volumeCaustic["bricks"].get<long long>()
              << " voxel(s) of focused light resolved in " << c << "^3 fine voxels\n";
  }
  std::cout << "  memory    photon pass: device "
            << vtkOpenCLMemoryPlan::FormatBytes(light.value("device_memory_planned_bytes", 0.0))
            << " planned, "
            << vtkOpenCLMemoryPlan::FormatBytes(light.value("device_memory_used_bytes", 0.0))
            << " used; host "
            << vtkOpenCLMemoryPlan::FormatBytes(light.value("host_memory_planned_bytes", 0.0))
            << " planned\n";
  if (light["multiple_scattering"].is_object())
  {
    const json& ms = light["multiple_scattering"];
    std::cout << "  multiple  " << ms["method"].get<std::string>() << " ("
              << ms["reason"].get<std::string>() << ")";
    if (ms.contains("iterations"))
    {
      std::cout << "; Lattice-Boltzmann " << ms["lattice"].get<std::string>() << ", "
                << ms["iterations"].get<double>() << " iterations";
      if (ms["coarse_start_steps"].get<int>() > 0)
      {
        std::cout << " after a coarse start (" << ms["coarse_start_steps"].get<int>()
                  << " steps on coarser grids, costing "
                  << ms["coarse_start_cost"].get<double>() << " full-grid steps)";
      }
      std::cout << ", residual " << ms["residual"].get<double>()
                << (ms["converged"].get<bool>() ? " (converged), " : " (NOT converged), ")
                << ms["seconds"].get<double>() << " s, " << ms["update"].get<std::string>()
                << " update";
    }
    std::cout << "\n";
  }
  double emitted = 0, out = 0;
  if (Sum3(light, "EnergyEmitted", emitted) && Sum3(light, "EnergyScattered", out) &&
    Sum3(light, "EnergyAbsorbed", out) && Sum3(light, "EnergyEscaped", out) &&
    Sum3(light, "EnergyRemaining", out))
  {
    // The surfaces' term where the scene has surfaces (the photon tracer's EnergySurface).
    const bool surfaces = Sum3(light, "EnergySurface", out);
    std::cout << "  energy    emitted " << emitted << " = scattered+absorbed+"
              << (surfaces ? "surfaces+" : "") << "escaped+remaining " << out
              << " (relative difference " << (emitted > 0 ? (out - emitted) / emitted : 0.0)
              << ")\n";
  }
  // Photons stopped by the step cap (light trapped by total internal reflection in many nested
  // bodies, say) took their power out of the image: say how many, not only in the report.
  const double capped = light.value("TerminatedStepCap", 0.0);
  const double marched = light.value("PhotonsMarched", 0.0);
  if (capped > 0 && marched > 0 && capped >= 0.001 * marched)
  {
    std::cout << "  warning   " << capped << " photons (" << 100.0 * capped / marched
              << "% of those marched) stopped at the step cap; their power is not in the image "
                 "(it is booked as remaining)\n";
  }
}

// "surfaces" line: how many of each kind, the triangles; nothing without surfaces.
void PrintSurfaces(const json& surfaces, double seconds)
{
  const int interfaces = surfaces.is_object() ? surfaces.value("interface_surfaces", 0) : 0;
  if (interfaces > 0)
  {
    std::cout << "  glass     " << interfaces << " exact interface(s) from the medium's meshes, "
              << surfaces.value("interface_triangles", 0LL) << " triangles\n";
  }
  if (!surfaces.is_object() || surfaces.value("count", 0) == 0)
  {
    return;
  }
  std::map<std::string, int> kinds;
  for (const json& s : surfaces["list"])
  {
    ++kinds[s["kind"].get<std::string>()];
  }
  std::string list;
  for (const char* kind : { "plane", "box", "sphere", "file" })
  {
    if (kinds.count(kind))
    {
      list += (list.empty() ? "" : ", ") + std::to_string(kinds[kind]) + " " + kind;
    }
  }
  std::cout << "  surfaces  " << surfaces["count"].get<int>() << " (" << list << "), "
            << surfaces["triangles"].get<long long>() << " triangles, " << seconds << " s\n";
}
}

void PrintSummary(const json& report)
{
  const json& image = report["image"];
  const json& quality = report["quality"];
  const json& medium = report["medium"];
  const json& view = report["view_pass"];
  const json& seconds = report["seconds"];
  std::cout << "refracta-render: " << image["width"].get<int>() << " x "
            << image["height"].get<int>() << " -> " << report["output"].get<std::string>() << " on "
            << report["device"].get<std::string>() << "\n";
  std::cout << "  plan      " << report["plan"]["summary"].get<std::string>() << "\n";
  if (report["plan"].value("under_resolved", false))
  {
    std::cout << "  warning   a voxel's optical depth reaches "
              << report["plan"]["voxel_optical_depth"].get<double>()
              << " in a scattering medium: dense parts scatter their light within a fraction of a "
                 "voxel of their surface, which the grid does not resolve, so it is "
                 "underestimated; a finer grid (medium.grid.dimensions) resolves it\n";
  }
  const json& method = report["plan"]["single_scattering_method"];
  // S1 in lobes (vtkPhotonTracer::MaximumRadianceLobes): lights from different sides
  // each shaded about their own direction.
  const int lobes = static_cast<int>(report["light_pass"].value("RadianceLobes", 1.0));
  std::cout << "  single    " << method["chosen"].get<std::string>() << " ("
            << method["reason"].get<std::string>() << ")"
            << (lobes > 1 ? ", S1 in " + std::to_string(lobes) + " lobes of lights" : "") << "\n";
  std::cout << "  quality   preset " << quality["preset"].get<std::string>() << ": "
            << quality["photons"].get<int>() << " photons, photon min step "
            << quality["photon_min_step"].get<double>() << ", octree eps "
            << quality["octree_tolerance"].get<double>() << ", lattice tolerance "
            << quality["multiple_scattering_tolerance"].get<double>() << ", lattice block "
            << quality["multiple_scattering_block_size"].get<int>() << ", view step "
            << quality["view_step"].get<double>() << "\n";
  std::cout << "  medium    " << medium["dimensions"][0].get<int>() << " x "
            << medium["dimensions"][1].get<int>() << " x " << medium["dimensions"][2].get<int>()
            << " (" << medium["source"].get<std::string>()
            << (medium.contains("interfaces")
                   ? ", " + medium["interfaces"].get<std::string>() + " interfaces"
                   : std::string())
            << "), " << seconds["medium"].get<double>() << " s\n";
  PrintSurfaces(report["surfaces"], seconds.value("surfaces", 0.0));
  PrintLightPass(report["light_pass"]);
  std::cout << "  view      " << (view["curved_rays"].get<bool>() ? "curved" : "straight")
            << " rays, " << view["total_steps"].get<double>() << " steps, "
            << (view["empty_space_skipping"].get<bool>() ? "empty-space skipping (" +
                     std::to_string(100.0 * view["active_cell_fraction"].get<double>()) +
                     "% of macro cells active), "
                                                         : std::string("no empty space skipped, "))
            << (view["lane_marching"].get<bool>() ? "8 rays per work-item, " : "")
            << seconds["view_pass"].get<double>() << " s\n";
  if (const long long edges = view.value("supersampled_pixels", 0LL))
  {
    std::cout << "  edges     " << edges << " pixel(s) over edges of glass, "
              << quality["glass_supersampling"].get<int>() << " x "
              << quality["glass_supersampling"].get<int>() << " rays each\n";
  }
  if (const long long fine = view.value("fine_caustic_texels", 0LL))
  {
    std::cout << "  caustic   " << fine << " atlas texel(s) read from their fine texels\n";
  }
  std::cout << "  memory    view pass: " << view["memory_plan"].get<std::string>() << " planned, "
            << view["buffer_tiles"].get<int>() << " buffer tile(s)\n";
  std::cout << "  total     " << seconds["total"].get<double>() << " s\n";
  if (report.contains("kernels"))
  {
    for (const json& k : report["kernels"])
    {
      std::cout << "  kernel    " << k["label"].get<std::string>() << ": "
                << k["launches"].get<int>() << " launches, " << k["device_seconds"].get<double>()
                << " s on the device, " << k["host_seconds"].get<double>()
                << " s of host time in the calls\n";
    }
  }
}

json KernelProfileReport(vtkOpenCLContext* context)
{
  vtkOpenCLKernelProfile* profile = context->GetKernelProfile();
  std::vector<int> order(profile->GetNumberOfKernels());
  for (size_t i = 0; i < order.size(); ++i)
  {
    order[i] = static_cast<int>(i);
  }
  std::stable_sort(order.begin(), order.end(),
    [profile](int a, int b)
    { return profile->GetDeviceSeconds(a) > profile->GetDeviceSeconds(b); });
  json kernels = json::array();
  for (int i : order)
  {
    kernels.push_back(
      { { "label", profile->GetKernelLabel(i) }, { "launches", profile->GetNumberOfLaunches(i) },
        { "device_seconds", profile->GetDeviceSeconds(i) },
        { "host_seconds", profile->GetHostSeconds(i) } });
  }
  return kernels;
}
}
