// BenchmarkLatticeBoltzmann: cost of Refracta's Lattice-Boltzmann lighting
// (vtkLatticeBoltzmannSolver) next to the device's memory bandwidth measured in the same run.
//
// For each grid size (64^3 and 128^3 by default; --large adds 256^3) and albedo (0.5, 0.9, 0.99)
// it solves a homogeneous medium (sigma_t h = 0.5, g = 0) lit by a beam entering through the -x
// face (S1 = a sigma_t exp(-sigma_t x)) to the default tolerance, in the global (unblocked)
// schedule and in blocks (b = 4, StepsPerExchange = 4), and prints: steps to convergence, time
// per step, lattice updates per second (voxels x steps / s), the effective bytes per second of
// the update (state read + write, coefficients, source) and its ratio to the bandwidth of a plain
// OpenCL copy kernel over buffers of the state's size. Figures are medians of --repeats runs
// (default 3). Writes CSV to --csv (default lbl_benchmark.csv). --lattices 6,18 adds D3Q18 (global
// only: it never runs in blocks), whose update reads and writes 18 x 3 floats and 2 length
// classes' T.
//
// --table1 N runs instead the paper's Table I experiment on an N^3 medium entirely filled
// (sigma_t h = 0.5, albedo 0.9, a sphere of index 1.2 in the middle so that rays curve; a
// directional light, 65536 photons, fixed photon step of one voxel): total time of photon pass +
// diffusion to convergence for the interleaved schedule with k = 2, 4, 8, 16, 32, 64 and for the
// sequential one (march all, then diffuse), medians of --repeats runs. Each run builds a fresh
// schedule (medium validation, lattice coefficients, device buffers: a first render). With
// --persistent one schedule per row serves every run and each run turns the light by 2 degrees
// (a relight: the medium is already on the device, as in the paper's timing of the computation),
// and two more rows: the sequential schedule with the lattice's warm start, plain and with its
// coarse correction.
//
// Usage: BenchmarkLatticeBoltzmann [--large] [--sizes 32,64] [--repeats N] [--csv file]
//        [--max-steps N] [--isotropic] [--global-only] [--lattices 6,18]
//        [--table1 N [--persistent]]
#include "RefractaBenchmark.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkLight.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLKernelProfile.h"
#include "vtkPhotonDiffusionSchedule.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"

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
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

double FieldValue(vtkImageData* image, const char* name)
{
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  return a ? a->GetComponent(0, 0) : -1.0;
}

// Steps, convergence and times of the repeated solves of one configuration.
struct SolveRuns
{
  std::vector<double> Seconds;
  int Steps = 0;
  int CoarseSteps = 0;
  double CoarseCost = 0;
  bool Converged = false;
};

// max |a - b| over max |b|.
double MaxDifferenceOverPeak(const std::vector<float>& a, const std::vector<float>& b)
{
  double diff = 0, peak = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
  {
    diff = std::max(diff, std::abs(double(a[i]) - double(b[i])));
    peak = std::max(peak, std::abs(double(b[i])));
  }
  return peak > 0 ? diff / peak : diff;
}

// A directional light along +x, turned by `degrees` about z, for Table I.
void AimTable1Light(vtkLight* light, int n, double degrees)
{
  const double a = vtkMath::RadiansFromDegrees(degrees);
  light->SetPositional(false);
  light->SetFocalPoint(0, 0.3 * n, 0.4 * n);
  light->SetPosition(-10.0 * n * std::cos(a), 0.3 * n - 10.0 * n * std::sin(a), 0.4 * n);
}

int RunTable1(int n, int repeats, bool persistent, const std::string& csv)
{
  auto medium = vtkSmartPointer<vtkImageData>::New();
  medium->SetDimensions(n, n, n);
  const vtkIdType count = medium->GetNumberOfPoints();
  vtkNew<vtkFloatArray> ri, ext, alb;
  ri->SetName("RefractiveIndex");
  ri->SetNumberOfTuples(count);
  ext->SetName("Extinction");
  ext->SetNumberOfComponents(3);
  ext->SetNumberOfTuples(count);
  ext->Fill(0.5);
  alb->SetName("Albedo");
  alb->SetNumberOfComponents(3);
  alb->SetNumberOfTuples(count);
  alb->Fill(0.9);
  for (vtkIdType v = 0; v < count; ++v)
  {
    const double x = v % n - 0.5 * n, y = (v / n) % n - 0.5 * n, z = v / (n * n) - 0.5 * n;
    ri->SetValue(v, x * x + y * y + z * z < 0.09 * n * n ? 1.2f : 1.0f);
  }
  medium->GetPointData()->AddArray(ri);
  medium->GetPointData()->AddArray(ext);
  medium->GetPointData()->AddArray(alb);
  std::ofstream out(csv);
  out << "size,schedule,k,total_s,marching_s,final_solve_s,chunks,lbl_steps_during_marching,"
         "lbl_steps_total,persistent,coarse_start_cost\n";
  std::printf(
    "\n| schedule | k | total s | photon pass (+ interleaved diffusion) s | final solve s | "
    "chunks | LBL steps during marching | LBL steps total | coarse start (in full-grid steps) |\n"
    "|---|---|---|---|---|---|---|---|---|\n");
  // With REFRACTA_PROFILE_KERNELS=1 each schedule's kernels are listed (summed over the repeats):
  // their total against the wall time says how much of Table I is host work.
  vtkOpenCLKernelProfile* profile = vtkOpenCLContext::GetDefault()->GetKernelProfile();
  std::string kernels;
  int initializations = 0; // of the last row's schedule
  // The sequential schedule with the lattice's coarse start off (every step on the full grid),
  // the comparison for the sequential row with it on (the default); with --persistent also the
  // warm starts (each run's lattice continues from the last light's field), plain and with the
  // coarse correction (vtkLatticeBoltzmannSolver::CoarseWarmStart); then the interleaved rows.
  struct Row
  {
    const char* Name;
    int K; // 0: sequential
    bool CoarseStart, WarmStart, CoarseCorrection;
  };
  std::vector<Row> rows = { { "sequential cold start", 0, false, false, false },
    { "sequential", 0, true, false, false } };
  if (persistent)
  {
    rows.push_back({ "sequential warm start", 0, true, true, false });
    rows.push_back({ "sequential warm start, coarse correction", 0, true, true, true });
  }
  for (int k : { 2, 4, 8, 16, 32, 64 })
  {
    rows.push_back({ "interleaved", k, true, false, false });
  }
  for (const Row& row : rows)
  {
    const int k = row.K;
    std::vector<double> total, marching, solve;
    double chunks = 0, during = 0, steps = 0, coarseCost = 0;
    vtkSmartPointer<vtkPhotonDiffusionSchedule> schedule;
    vtkNew<vtkLight> light;
    for (int r = -1; r < repeats; ++r) // r = -1: warm-up (kernel builds), not timed
    {
      if (!schedule || !persistent)
      {
        schedule = vtkSmartPointer<vtkPhotonDiffusionSchedule>::New();
        schedule->SetInputData(medium);
        schedule->SetMode(k <= 0 ? vtkPhotonDiffusionSchedule::SEQUENTIAL
                                 : vtkPhotonDiffusionSchedule::INTERLEAVED);
        schedule->SetWarmStart(row.WarmStart);
        schedule->GetSolver()->SetCoarseStart(row.CoarseStart);
        schedule->GetSolver()->SetCoarseWarmStart(row.CoarseCorrection);
        schedule->SetStepsPerChunk(std::max(k, 1));
        schedule->GetPhotonTracer()->AddLight(light);
        schedule->GetPhotonTracer()->SetNumberOfPhotons(65536);
        schedule->GetPhotonTracer()->SetAdaptiveStepping(false);
        schedule->GetPhotonTracer()->SetFixedStep(1.0);
      }
      AimTable1Light(light, n, persistent ? 2.0 * (r + 1) : 0.0);
      schedule->Modified(); // the tracer does not watch its lights
      schedule->Update();
      vtkImageData* result = schedule->GetOutput();
      if (result->GetNumberOfPoints() == 0)
      {
        return 1;
      }
      if (r < 0)
      {
        profile->Reset(); // time the repeats only
        continue;
      }
      total.push_back(FieldValue(result, "ScheduleTotalSeconds"));
      marching.push_back(FieldValue(result, "ScheduleMarchingSeconds"));
      solve.push_back(FieldValue(result, "ScheduleFinalSolveSeconds"));
      chunks = FieldValue(result, "ScheduleChunks");
      during = FieldValue(result, "ScheduleDiffusionStepsDuringMarching");
      steps = FieldValue(result, "LatticeBoltzmannIterations");
      coarseCost = schedule->GetSolver()->GetCoarseStartCost();
    }
    initializations = schedule->GetNumberOfSolverInitializations();
    const char* name = row.Name;
    if (vtkOpenCLContext::GetDefault()->GetProfileKernels())
    {
      profile->Collect();
      kernels += std::string("\nKernels of ") + name + (k > 0 ? " k = " + std::to_string(k) : "") +
        ", " + std::to_string(repeats) + " runs:\n" + profile->GetTable();
    }
    std::printf("| %s | %s | %.4f | %.4f | %.4f | %g | %g | %g | %.1f |\n", name,
      k <= 0 ? "-" : std::to_string(k).c_str(), Median(total), Median(marching), Median(solve),
      chunks, during, steps, coarseCost);
    std::fflush(stdout);
    out << n << "," << name << "," << k << "," << Median(total) << "," << Median(marching) << ","
        << Median(solve) << "," << chunks << "," << during << "," << steps << ","
        << (persistent ? 1 : 0) << "," << coarseCost << "\n";
  }
  if (persistent)
  {
    std::printf("\nPersistent schedules (one per row, the light turned 2 degrees per run): the "
                "last row initialised its solver %d time(s) in %d runs\n",
      initializations, repeats + 1);
  }
  std::printf("%s\nCSV written to %s\n", kernels.c_str(), csv.c_str());
  return 0;
}

// Copy bandwidth in bytes/s (read + write) over buffers of `bytes` bytes.
double CopyBandwidth(vtkOpenCLContext* context, size_t bytes, int repeats)
{
  cl_program program = context->GetProgram({ "refracta_common.cl", "lbl.cl" }, "");
  vtkOpenCLKernel kernel = context->CreateKernel(program, "lbl_copy");
  vtkOpenCLBuffer a = context->CreateBuffer(CL_MEM_READ_WRITE, bytes, nullptr, "copy a");
  vtkOpenCLBuffer b = context->CreateBuffer(CL_MEM_READ_WRITE, bytes, nullptr, "copy b");
  context->ZeroBuffer(a.Get(), bytes);
  const cl_ulong count = bytes / 16;
  vtkOpenCLSetKernelArgs(kernel.Get(), a.Get(), b.Get(), count);
  const size_t global = count;
  const size_t local = 128;
  context->RunKernel(kernel.Get(), 1, &global, &local, "copy"); // warm up
  context->Finish();
  std::vector<double> rates;
  for (int r = 0; r < repeats; ++r)
  {
    const int copies = 10;
    const double t0 = Now();
    for (int c = 0; c < copies; ++c)
    {
      context->RunKernel(kernel.Get(), 1, &global, &local, "copy");
    }
    context->Finish();
    rates.push_back(2.0 * bytes * copies / (Now() - t0));
  }
  return Median(rates);
}
}

int main(int argc, char* argv[])
{
  std::vector<int> sizes = { 64, 128 };
  std::vector<int> lattices = { 6 };
  int repeats = 3;
  int maxSteps = 5000;
  bool isotropic = false;
  bool globalOnly = false;
  int table1 = 0;
  bool persistent = false;
  std::string csv = "lbl_benchmark.csv";
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--large"))
    {
      sizes.push_back(256);
    }
    else if (!std::strcmp(argv[i], "--sizes") && i + 1 < argc)
    {
      sizes = refracta::bench::ParseIntList(argv[++i]);
    }
    else if (!std::strcmp(argv[i], "--lattices") && i + 1 < argc)
    {
      lattices = refracta::bench::ParseIntList(argv[++i]);
      for (int lattice : lattices)
      {
        if (lattice != 6 && lattice != 18)
        {
          std::fprintf(stderr, "--lattices takes 6 and/or 18, not %d\n", lattice);
          return 1;
        }
      }
    }
    else if (!std::strcmp(argv[i], "--isotropic"))
    {
      isotropic = true;
    }
    else if (!std::strcmp(argv[i], "--table1") && i + 1 < argc)
    {
      table1 = std::max(4, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--persistent"))
    {
      persistent = true;
    }
    else if (!std::strcmp(argv[i], "--global-only"))
    {
      globalOnly = true;
    }
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc)
    {
      repeats = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--max-steps") && i + 1 < argc)
    {
      maxSteps = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc)
    {
      csv = argv[++i];
    }
    else
    {
      std::fprintf(stderr, "unknown argument %s\n", argv[i]);
      return 1;
    }
  }
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::fprintf(stderr, "no OpenCL device\n");
    return 1;
  }
  std::printf("device: %s (%s), %d compute units\n", context->GetDeviceName(),
    context->GetPlatformName(), context->GetNumberOfComputeUnits());
  if (table1 > 0)
  {
    return RunTable1(table1, repeats, persistent, csv);
  }
  std::ofstream out(csv);
  out << "size,lattice,albedo,schedule,steps,converged,seconds,ms_per_step,mlups,effective_GBps,"
         "copy_GBps,ratio\n";
  std::string coarseRows;
  std::printf(
    "\n| size | lattice | albedo | schedule | steps | converged | ms/step | M updates/s | "
    "effective GB/s | copy GB/s | ratio |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const int n : sizes)
  {
    for (const int lattice : lattices)
    {
      const int dims[3] = { n, n, n };
      const double spacing[3] = { 1, 1, 1 };
      const size_t voxels = size_t(n) * n * n;
      const double sigmaT = 0.5;
      // State Q x 3 floats read and written; per length class (D3Q6 one, D3Q18 two on cubic voxels)
      // 3 T, then 3 albedo + g; 3 + 3 source values (phase-function source).
      const int classes = lattice == 18 ? 2 : 1;
      const double bytesPerUpdate = (2.0 * 3 * lattice + 3 * classes + 4 + 6) * 4;
      const double copy =
        CopyBandwidth(context, size_t(3 * lattice) * voxels * sizeof(float), repeats);
      for (double albedo : { 0.5, 0.9, 0.99 })
      {
        std::vector<float> ext(voxels * 3, float(sigmaT)), alb(voxels * 3, float(albedo)),
          g(voxels, 0.0f), s1(voxels * 3), dir(voxels * 3, 0.0f);
        for (size_t v = 0; v < voxels; ++v)
        {
          const int x = static_cast<int>(v % n);
          for (int c = 0; c < 3; ++c)
          {
            s1[v * 3 + c] = float(albedo * sigmaT * std::exp(-sigmaT * x));
          }
          dir[v * 3] = 1.0f;
        }
        for (int blocked : { 0, 1 })
        {
          if (blocked && (globalOnly || lattice == 18))
          {
            continue;
          }
          // Cold (CoarseStart off: every step on this grid, the bandwidth rows), then with the
          // coarse start (the class default) against the cold answer.
          SolveRuns cold, coarse;
          std::vector<float> coldOutput, coarseOutput;
          for (bool coarseStart : { false, true })
          {
            SolveRuns& runs = coarseStart ? coarse : cold;
            for (int r = -1; r < repeats; ++r) // r = -1: warm-up (kernel builds), not timed
            {
              vtkNew<vtkLatticeBoltzmannSolver> solver;
              solver->SetLattice(lattice);
              solver->SetCoarseStart(coarseStart);
              solver->SetBlockSize(blocked ? 4 : 0);
              solver->SetBlockPolicy(vtkLatticeBoltzmannSolver::ALWAYS_BLOCKS);
              solver->SetStepsPerExchange(4);
              // The warm-up only builds the kernels (a few steps).
              solver->SetMaximumIterations(r < 0 ? 8 : maxSteps);
              if (isotropic)
              {
                solver->SetSourceDistribution(vtkLatticeBoltzmannSolver::ISOTROPIC_SOURCE);
              }
              if (!solver->Initialize(dims, spacing, ext.data(), alb.data(), g.data()) ||
                !solver->SetSource(s1.data(), dir.data()))
              {
                return 1;
              }
              const double t0 = Now();
              if (!solver->Solve())
              {
                return 1;
              }
              if (r >= 0)
              {
                runs.Seconds.push_back(Now() - t0);
              }
              runs.Steps = solver->GetIterations();
              runs.CoarseSteps = solver->GetCoarseStartSteps();
              runs.CoarseCost = solver->GetCoarseStartCost();
              runs.Converged = solver->GetConverged();
              std::vector<float>& output = coarseStart ? coarseOutput : coldOutput;
              output.resize(voxels * 3);
              if (r == repeats - 1 && !solver->ComputeMultipleScattering(output.data()))
              {
                return 1;
              }
            }
          }
          const int steps = cold.Steps;
          const bool converged = cold.Converged;
          const double t = Median(cold.Seconds);
          const double mlups = double(voxels) * steps / t / 1e6;
          const double effective = mlups * 1e6 * bytesPerUpdate;
          const char* schedule = blocked ? "blocks b=4 m=4" : "global";
          std::printf("| %d^3 | D3Q%d | %.2f | %s | %d | %s | %.2f | %.1f | %.2f | %.2f | %.3f |\n",
            n, lattice, albedo, schedule, steps, converged ? "yes" : "no", 1e3 * t / steps, mlups,
            effective / 1e9, copy / 1e9, effective / copy);
          std::fflush(stdout);
          out << n << "," << lattice << "," << albedo << "," << schedule << "," << steps << ","
              << converged << "," << t << "," << 1e3 * t / steps << "," << mlups << ","
              << effective / 1e9 << "," << copy / 1e9 << "," << effective / copy << "\n";
          const double coarseSeconds = Median(coarse.Seconds);
          char row[512];
          std::snprintf(row, sizeof(row),
            "| %d^3 | D3Q%d | %.2f | %s | %d | %.4f | %d + %d coarse (%.1f) | %s | %.4f | %.2f | "
            "%.2e |\n",
            n, lattice, albedo, schedule, cold.Steps, t, coarse.Steps, coarse.CoarseSteps,
            coarse.CoarseCost, coarse.Converged ? "yes" : "no", coarseSeconds, t / coarseSeconds,
            MaxDifferenceOverPeak(coarseOutput, coldOutput));
          coarseRows += row;
        }
      }
    }
  }
  std::printf(
    "\nCoarse start (vtkLatticeBoltzmannSolver::CoarseStart, the default) against the "
    "cold start above, same run; steps on this grid + on the coarser ones (their cost "
    "in steps of this grid); the difference of S_ms over its peak:\n\n"
    "| size | lattice | albedo | schedule | cold steps | cold s | coarse-start steps | converged | "
    "s | speed-up | max S_ms difference / peak |\n|---|---|---|---|---|---|---|---|---|---|---|\n"
    "%s",
    coarseRows.c_str());
  std::printf("\nCSV written to %s\n", csv.c_str());
  return 0;
}
