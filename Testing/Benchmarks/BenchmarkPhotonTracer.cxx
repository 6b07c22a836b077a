// BenchmarkPhotonTracer: the photon pass on a 128^3 medium (a refractive sphere, n = 1.5 with a
// smooth tanh boundary, in a scattering fog), with 2^16, 2^18 and 2^20 photons, adaptive and
// fixed (1 voxel) steps, and the extinction step limit. Prints, per configuration, the median of
// several runs: total steps, steps per second of marching, seconds per stage (octree,
// generation, marching, smoothing), device memory allocated, the process's peak resident
// memory, and the relative L2 error of Radiance against a reference run with 0.25-voxel fixed
// steps (same photons, same seed: the error is the stepping's, not noise). Writes a CSV.
// `adaptive-no-control` is adaptive with StepTolerance 0 (the marcher before the step control of
// issue 18): the run prints the control's cost as a same-run ratio. `adaptive-lattice-order` is
// adaptive with CoherentPhotonOrder off (the photons in the generation's order): the run prints
// the coherent order's gain in voxel pieces per second (the same pieces, the same output).
//
// Usage: BenchmarkPhotonTracer [--quick] [--max-log2 K] [--runs R] [--modes LIST] [output.csv]
//   --quick: 32^3 grid, 2^12 photons, one run, adaptive and adaptive-lattice-order only (a smoke
//   test of the program).
//   --max-log2 K: stop at 2^K photons (default 20). --runs R: runs per median (default 3).
//   --modes LIST: only these modes (comma-separated, from adaptive, adaptive-lattice-order,
//   adaptive-no-control, fixed-1, adaptive+ext0.1, adaptive-min0.5), e.g. for a profile of one.
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkSmartPointer.h"

#include "RefractaBenchmark.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace
{
vtkSmartPointer<vtkImageData> SphereInFog(int n)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  const double s = 1.0 / n;
  image->SetSpacing(s, s, s);
  vtkNew<vtkFloatArray> ri, ext, alb;
  ri->SetName("RefractiveIndex");
  ext->SetName("Extinction");
  ext->SetNumberOfComponents(3);
  alb->SetName("Albedo");
  alb->SetNumberOfComponents(3);
  const vtkIdType count = static_cast<vtkIdType>(n) * n * n;
  ri->SetNumberOfTuples(count);
  ext->SetNumberOfTuples(count);
  alb->SetNumberOfTuples(count);
  const double c = 0.5 * (n - 1) * s, R = 0.3, width = 1.0 * s;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const vtkIdType id = i + static_cast<vtkIdType>(n) * (j + static_cast<vtkIdType>(n) * k);
        const double x = i * s - c, y = j * s - c, z = k * s - c;
        const double r = std::sqrt(x * x + y * y + z * z);
        const double inside = 0.5 * (1 - std::tanh((r - R) / width));
        ri->SetValue(id, static_cast<float>(1.0 + 0.5 * inside));
        // Fog outside, clear glass inside (slightly absorbing).
        const float fog[3] = { static_cast<float>(0.6 * (1 - inside) + 0.05 * inside),
          static_cast<float>(0.8 * (1 - inside) + 0.05 * inside),
          static_cast<float>(1.0 * (1 - inside) + 0.05 * inside) };
        const float albedo[3] = { 0.9f, 0.9f, 0.9f };
        ext->SetTypedTuple(id, fog);
        alb->SetTypedTuple(id, albedo);
      }
  image->GetPointData()->AddArray(ri);
  image->GetPointData()->AddArray(ext);
  image->GetPointData()->AddArray(alb);
  return image;
}

double PeakRssMiB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

struct Result
{
  std::string Mode;
  int Photons = 0;
  double Steps = 0, Pieces = 0, Octree = 0, Generation = 0, Marching = 0, Smoothing = 0, Total = 0;
  double DeviceMiB = 0, RssMiB = 0, Error = -1;
  std::vector<float> Radiance;
};

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

Result Measure(vtkImageData* medium, int photons, const std::string& mode, int runs)
{
  vtkNew<vtkPhotonTracer> tracer;
  tracer->SetInputData(medium);
  vtkNew<vtkLight> sun;
  sun->SetPositional(false);
  sun->SetPosition(-1, 1.3, 0.8);
  sun->SetFocalPoint(0.5, 0.5, 0.5);
  sun->SetIntensity(1.0);
  tracer->AddLight(sun);
  tracer->SetNumberOfPhotons(photons);
  if (mode == "fixed-1")
  {
    tracer->AdaptiveSteppingOff();
    tracer->SetFixedStep(1.0);
  }
  else if (mode == "fixed-0.25")
  {
    tracer->AdaptiveSteppingOff();
    tracer->SetFixedStep(0.25);
  }
  else if (mode == "adaptive+ext0.1")
  {
    tracer->SetExtinctionStepLimit(0.1);
  }
  else if (mode == "adaptive-min0.5")
  {
    tracer->SetMinimumStep(0.5);
  }
  else if (mode == "adaptive-lattice-order")
  {
    tracer->CoherentPhotonOrderOff(); // the photons in the generation's order (before issue 17)
  }
  else if (mode == "adaptive-no-control")
  {
    tracer->SetStepTolerance(0.0); // the marcher before the step control (issue 18)
  }
  // Warm-up with a few photons: compiles the kernels (the photon count is not a build option).
  tracer->SetNumberOfPhotons(256);
  tracer->Update();
  tracer->SetNumberOfPhotons(photons);
  std::vector<double> octree, generation, marching, smoothing, total;
  Result r;
  r.Mode = mode;
  r.Photons = photons;
  for (int run = 0; run < runs; ++run)
  {
    tracer->Modified();
    const auto start = std::chrono::steady_clock::now();
    tracer->Update();
    total.push_back(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    octree.push_back(tracer->GetOctreeSeconds());
    generation.push_back(tracer->GetGenerationSeconds());
    marching.push_back(tracer->GetMarchingSeconds());
    smoothing.push_back(tracer->GetSmoothingSeconds());
  }
  vtkImageData* out = tracer->GetOutput();
  r.Steps = out->GetFieldData()->GetArray("TotalSteps")->GetComponent(0, 0);
  r.Pieces = out->GetFieldData()->GetArray("TotalVoxelPieces")->GetComponent(0, 0);
  r.Octree = Median(octree);
  r.Generation = Median(generation);
  r.Marching = Median(marching);
  r.Smoothing = Median(smoothing);
  r.Total = Median(total);
  r.DeviceMiB = tracer->GetPeakDeviceMemoryBytes() / 1048576.0;
  r.RssMiB = PeakRssMiB();
  auto* rad = vtkFloatArray::SafeDownCast(
    out->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName()));
  r.Radiance.assign(rad->GetPointer(0), rad->GetPointer(0) + rad->GetNumberOfValues());
  return r;
}

double RelativeL2(const std::vector<float>& a, const std::vector<float>& b)
{
  double num = 0, den = 0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    num += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    den += double(b[i]) * b[i];
  }
  return std::sqrt(num / den);
}
}

int main(int argc, char* argv[])
{
  bool quick = false;
  int maxLog2 = 20;
  int runsWanted = 3;
  std::string csv = "BenchmarkPhotonTracer.csv";
  std::vector<std::string> onlyModes;
  const std::vector<std::string> knownModes = { "adaptive", "adaptive-lattice-order",
    "adaptive-no-control", "fixed-1", "adaptive+ext0.1", "adaptive-min0.5" };
  for (int a = 1; a < argc; ++a)
  {
    if (std::strcmp(argv[a], "--quick") == 0)
    {
      quick = true;
    }
    else if (std::strcmp(argv[a], "--max-log2") == 0 && a + 1 < argc)
    {
      maxLog2 = std::atoi(argv[++a]);
    }
    else if (std::strcmp(argv[a], "--runs") == 0 && a + 1 < argc)
    {
      runsWanted = std::atoi(argv[++a]);
    }
    else if (std::strcmp(argv[a], "--modes") == 0 && a + 1 < argc)
    {
      onlyModes = refracta::bench::SplitList(argv[++a]);
      for (const auto& mode : onlyModes)
      {
        if (std::find(knownModes.begin(), knownModes.end(), mode) == knownModes.end())
        {
          std::fprintf(stderr,
            "--modes: unknown mode '%s' (valid: adaptive, adaptive-lattice-order, "
            "adaptive-no-control, fixed-1, "
            "adaptive+ext0.1, adaptive-min0.5)\n",
            mode.c_str());
          return 2;
        }
      }
    }
    else if (argv[a][0] != '-')
    {
      csv = argv[a];
    }
    else
    {
      std::fprintf(stderr,
        "usage: BenchmarkPhotonTracer [--quick] [--max-log2 K] [--runs R] [--modes LIST] "
        "[output.csv]\n");
      return std::strcmp(argv[a], "--help") == 0 ? 0 : 2;
    }
  }
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::fprintf(stderr, "No OpenCL device.\n");
    return 1;
  }
  const int n = quick ? 32 : 128;
  const int runs = quick ? 1 : std::max(1, runsWanted);
  std::printf("Photon tracer benchmark: %d^3 refractive sphere in fog, device %s (%d compute "
              "units), median of %d runs (one run at 2^20)\n",
    n, context->GetDeviceName(), context->GetNumberOfComputeUnits(), runs);
  auto medium = SphereInFog(n);
  std::vector<int> counts;
  for (int k : { 16, 18, 20 })
  {
    if (k <= maxLog2)
    {
      counts.push_back(1 << k);
    }
  }
  if (quick)
  {
    counts = { 1 << 12 };
  }
  std::vector<Result> results;
  std::ofstream out(csv);
  out << "photons,mode,total_steps,voxel_pieces,steps_per_s,octree_s,generation_s,marching_s,"
         "smoothing_s,total_s,device_MiB,peak_rss_MiB,rel_L2_error_vs_0.25\n";
  std::printf("| photons | steps | total steps | voxel pieces | Msteps/s | Mpieces/s | octree s | "
              "generation s | marching s | smoothing s | total s | device MiB | peak RSS MiB | "
              "L2 error vs 0.25-voxel |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  auto report = [&](const Result& r)
  {
    const double rate = r.Steps / r.Marching;
    std::printf(
      "| 2^%d | %s | %.3g | %.3g | %.2f | %.1f | %.3f | %.3f | %.3f | %.3f | %.3f | %.0f | "
      "%.0f | %.4f |\n",
      static_cast<int>(std::lround(std::log2(r.Photons))), r.Mode.c_str(), r.Steps, r.Pieces,
      rate / 1e6, r.Pieces / r.Marching / 1e6, r.Octree, r.Generation, r.Marching, r.Smoothing,
      r.Total, r.DeviceMiB, r.RssMiB, r.Error);
    std::fflush(stdout);
    out << r.Photons << "," << r.Mode << "," << r.Steps << "," << r.Pieces << "," << rate << ","
        << r.Octree << "," << r.Generation << "," << r.Marching << "," << r.Smoothing << ","
        << r.Total << "," << r.DeviceMiB << "," << r.RssMiB << "," << r.Error << std::endl;
  };
  for (int photons : counts)
  {
    // The reference for the error column: same photons with 0.25-voxel fixed steps.
    Result reference = Measure(medium, photons, "fixed-0.25", 1);
    reference.Error = 0;
    std::vector<std::string> modes = { "adaptive", "adaptive-lattice-order" };
    if (!quick)
    {
      modes.push_back("adaptive-no-control");
      modes.push_back("fixed-1");
    }
    if (photons == (1 << 18))
    {
      modes.push_back("adaptive+ext0.1");
      modes.push_back("adaptive-min0.5");
    }
    if (!onlyModes.empty())
    {
      modes.erase(std::remove_if(modes.begin(), modes.end(),
                    [&](const std::string& m)
                    { return std::find(onlyModes.begin(), onlyModes.end(), m) == onlyModes.end(); }),
        modes.end());
    }
    for (const auto& mode : modes)
    {
      Result r = Measure(medium, photons, mode, photons > (1 << 18) ? 1 : runs);
      r.Error = RelativeL2(r.Radiance, reference.Radiance);
      r.Radiance.clear();
      report(r);
      results.push_back(std::move(r));
    }
    reference.Radiance.clear();
    report(reference);
    results.push_back(std::move(reference));
  }
  // Ratios measured in this run.
  for (int photons : counts)
  {
    const Result* a = nullptr;
    const Result* f = nullptr;
    const Result* u = nullptr;
    const Result* l = nullptr;
    for (const auto& r : results)
    {
      if (r.Photons == photons && r.Mode == "adaptive-lattice-order")
        l = &r;
      if (r.Photons == photons && r.Mode == "adaptive")
        a = &r;
      if (r.Photons == photons && r.Mode == "fixed-1")
        f = &r;
      if (r.Photons == photons && r.Mode == "adaptive-no-control")
        u = &r;
    }
    if (a && u)
    {
      std::printf("2^%d photons: cost of the step control (adaptive / adaptive-no-control): "
                  "steps x%.3f, marching time x%.3f; L2 error %.4f -> %.4f\n",
        static_cast<int>(std::lround(std::log2(photons))), a->Steps / u->Steps,
        a->Marching / u->Marching, u->Error, a->Error);
    }
    if (a && l)
    {
      std::printf("2^%d photons: coherent photon order (adaptive / adaptive-lattice-order): voxel "
                  "pieces per second x%.2f (%.3g / %.3g), same pieces: %s\n",
        static_cast<int>(std::lround(std::log2(photons))),
        (a->Pieces / a->Marching) / (l->Pieces / l->Marching), a->Pieces / a->Marching,
        l->Pieces / l->Marching, a->Pieces == l->Pieces && a->Error == l->Error ? "yes" : "NO");
    }
    if (a && f)
    {
      std::printf("2^%d photons: fixed-1 / adaptive: steps x%.2f, marching time x%.2f\n",
        static_cast<int>(std::lround(std::log2(photons))), f->Steps / a->Steps,
        f->Marching / a->Marching);
    }
  }
  std::printf("CSV written to %s\n", csv.c_str());
  return 0;
}
