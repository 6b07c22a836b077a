// BenchmarkViewPass: the cost of Refracta's view pass, and a comparison with VTK's CPU ray caster.
//
// Part 1: the view pass alone (vtkRefractaViewPass::Render, kernel + read-back) for W x W images
// of the GlassSphereInFog scene at N^3 (default 128^3) with its photon-traced lighting volume,
// curved rays (n varies: the sphere) and straight rays (RayMode STRAIGHT on the same medium), each
// by the general kernel and by the eight-lane one in the same run.
// Part 2: an emission-absorption-only scene (a procedural scalar field mapped by
// vtkTransferFunctionMedium with EmissionScale 1, i.e. VTK's compositing model) at N^3 and
// W = 512, rendered by Refracta's view pass (straight rays, one-voxel steps) and by
// vtkFixedPointVolumeRayCastMapper (sample distance one voxel, no auto-adjustment, no shading)
// in an offscreen render window of the same size, in the same run; prints the time ratio.
// Parts 2 and 3 time the general kernel (LaneMarching off) beside the eight-lane one
// (Kernels/view_lanes.cl, the default for straight rays without surfaces on a CPU device).
// Part 3: empty-space skipping. Every Refracta row above is timed with EmptySpaceSkipping off and
// on in the same run (column "skip"; "active" is the fraction of macro cells rays must march),
// and a third scene puts a small emission-absorption object (support radius 0.12 of the unit box,
// off centre) in the same N^3 grid, rendered by both Refracta settings and the fixed-point mapper.
// GlassSphereInFog is a full grid (fog everywhere: nothing to skip, so "on" measures the
// overhead of building the occupancy and choosing the plain kernel).
// Part 4: curved rays through a small glass ball (n 1.33, faint absorption) in the same grid,
// skipping off and on, and the image differences set beside those of a 1e-6 camera move.
// Part 5 (ms): the cost of shading multiple scattering about its direction: the same scene's
// lighting volume with the lattice's S_ms (vtkLatticeBoltzmannLighting, which gives
// MultipleScatteringDirection), the view pass with and without that array (the kernel reads 12
// more bytes per voxel corner), the runs interleaved.
// Medians of --runs runs (default 3; parts 2, 3 and 5 interleave the runs of every setting and of
// the fixed-point mapper); CSV to --csv (default benchmark_view_pass.csv).
//
// usage: BenchmarkViewPass [--sizes 256,512,1024] [--medium 128] [--runs 3] [--photons 65536]
//                          [--compare-size 512] [--cell-size 8]
//                          [--parts view,ea,small,glass,ms] [--csv FILE]
// --parts: which parts run (default all): view (part 1), ea (the emission-absorption ball of
// part 2), small (part 3's small object), glass (part 4), ms (part 5).
// --cell-size: vtkRefractaViewPass::MacroCellSize (voxels) for every Refracta row.
// Part 2 needs an X server (xvfb-run with Debian's VTK).
#include "RefractaBenchmark.h"
#include "RefractaScenes.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaRenderWindowCheck.h"
#include "vtkRefractaViewPass.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// A smooth procedural scalar field in [0, 1] on n^3 (unit cube), for the emission-absorption
// comparison: zero outside the ball of radius `radius` around `centre`.
vtkSmartPointer<vtkImageData> ScalarField(
  int n, double radius = 1 / 2.2, const double centre[3] = nullptr)
{
  const double c0[3] = { 0.5, 0.5, 0.5 };
  const double* c = centre ? centre : c0;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(1.0 / n, 1.0 / n, 1.0 / n);
  image->SetOrigin(0.5 / n, 0.5 / n, 0.5 / n);
  vtkNew<vtkFloatArray> s;
  s->SetName("density");
  s->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const double x = (i + 0.5) / n - c[0], y = (j + 0.5) / n - c[1], z = (k + 0.5) / n - c[2];
        const double r = std::sqrt(x * x + y * y + z * z);
        const double v = std::max(0.0, 1.0 - r / radius) *
          (0.6 + 0.4 * std::sin(18 * x) * std::cos(14 * y) * std::sin(11 * z + 1));
        s->SetValue(i + n * (j + static_cast<vtkIdType>(n) * k), static_cast<float>(v));
      }
    }
  }
  image->GetPointData()->SetScalars(s);
  return image;
}
// vtkFixedPointVolumeRayCastMapper rendering a field through the same property and camera in an
// offscreen window of size x size, one timed render at a time (so that its runs interleave with
// Refracta's and both see the same load on a shared machine). Ready() is false, with a message,
// where no render window can be opened (the Refracta rows still run).
class FixedPointRenderer
{
public:
  FixedPointRenderer(vtkImageData* data, vtkVolumeProperty* property, vtkCamera* camera, int size,
    int n, int threads)
    : Camera(camera)
  {
    if (!vtkRefractaRenderWindowCheck::CanOpen())
    {
      std::cerr << "skipping vtkFixedPointVolumeRayCastMapper: "
                << vtkRefractaRenderWindowCheck::GetReason() << "\n";
      return;
    }
    this->Window = vtkSmartPointer<vtkRenderWindow>::New();
    this->Window->SetOffScreenRendering(1);
    this->Window->SetSize(size, size);
    this->Window->AddRenderer(this->Renderer);
    this->Mapper->SetInputData(data);
    this->Mapper->SetAutoAdjustSampleDistances(0);
    this->Mapper->SetSampleDistance(1.0 / n);
    this->Mapper->SetImageSampleDistance(1.0);
    this->Mapper->SetNumberOfThreads(threads);
    this->Volume->SetMapper(this->Mapper);
    this->Volume->SetProperty(property);
    this->Renderer->AddVolume(this->Volume);
    this->Renderer->SetActiveCamera(camera);
    this->Renderer->ResetCameraClippingRange();
    camera->GetPosition(this->Position);
    this->Window->Render(); // warm-up: builds the mapper's tables
  }
  ~FixedPointRenderer() { this->Camera->SetPosition(this->Position); } // undo the jitter

  bool Ready() const { return this->Window != nullptr; }

  // Seconds of one render after a tiny camera move (which forces a re-render).
  double Render()
  {
    this->Camera->Azimuth(this->Runs++ % 2 ? 0.01 : -0.01);
    const double t0 = Now();
    this->Window->Render();
    return Now() - t0;
  }

private:
  vtkCamera* Camera;
  double Position[3] = { 0, 0, 0 };
  int Runs = 0;
  vtkSmartPointer<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkFixedPointVolumeRayCastMapper> Mapper;
  vtkNew<vtkVolume> Volume;
};

// The photon pass on a scene's medium and lights (not run yet).
vtkSmartPointer<vtkPhotonTracer> PhotonPass(const refracta::scenes::Scene& scene, int photons)
{
  auto tracer = vtkSmartPointer<vtkPhotonTracer>::New();
  tracer->SetInputData(scene.Medium);
  for (auto& light : scene.Lights)
  {
    tracer->AddLight(light);
  }
  tracer->SetNumberOfPhotons(photons);
  return tracer;
}
}

int main(int argc, char* argv[])
{
  std::vector<int> sizes = { 256, 512, 1024 };
  int n = 128, runs = 3, photons = 65536, compareSize = 512, cellSize = 8;
  std::string csv = "benchmark_view_pass.csv";
  std::string parts = "view,ea,small,glass,ms";
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--sizes" && hasValue)
      sizes = refracta::bench::ParseIntList(argv[++i]);
    else if (arg == "--medium" && hasValue)
      n = std::stoi(argv[++i]);
    else if (arg == "--runs" && hasValue)
      runs = std::stoi(argv[++i]);
    else if (arg == "--photons" && hasValue)
      photons = std::stoi(argv[++i]);
    else if (arg == "--compare-size" && hasValue)
      compareSize = std::stoi(argv[++i]);
    else if (arg == "--cell-size" && hasValue)
      cellSize = std::stoi(argv[++i]);
    else if (arg == "--csv" && hasValue)
      csv = argv[++i];
    else if (arg == "--parts" && hasValue)
      parts = argv[++i];
    else
    {
      std::cerr << "usage: BenchmarkViewPass [--sizes 256,512,1024] [--medium 128] [--runs 3] "
                   "[--photons 65536] [--compare-size 512] [--cell-size 8] "
                   "[--parts view,ea,small,glass,ms] [--csv FILE]\n";
      return 2;
    }
  }
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::cerr << context->GetLastErrorMessage() << "\n";
    return 1;
  }
  std::cout << "device: " << context->GetDeviceName() << " (" << context->GetPlatformName()
            << "), medium " << n << "^3, medians of " << runs << " runs\n";
  refracta::bench::Table table({ "part", "rays", "image", "skip", "active", "median_ms",
    "steps_per_pixel", "Msteps_per_s", "ratio" });

  const auto runs_part = [&parts](const std::string& name)
  { return ("," + parts + ",").find("," + name + ",") != std::string::npos; };

  // ---- Part 1: the view pass alone.
  std::vector<float> hdr;
  if (runs_part("view"))
  {
    refracta::scenes::Scene scene = refracta::scenes::GlassSphereInFog(n);
    auto tracer = PhotonPass(scene, photons);
    tracer->Update();
    vtkNew<vtkRefractaViewPass> pass;
    pass->SetMacroCellSize(cellSize);
    if (!pass->SetMedium(scene.Medium) || !pass->SetLighting(tracer->GetOutput()))
    {
      return 1;
    }
    // Curved and straight rays, each by the general kernel and by the eight-lane one (the
    // default on a CPU device).
    const std::pair<int, bool> modes[] = { { vtkRefractaViewPass::CURVED, false },
      { vtkRefractaViewPass::CURVED, true }, { vtkRefractaViewPass::STRAIGHT, false },
      { vtkRefractaViewPass::STRAIGHT, true } };
    for (const auto& mode : modes)
    {
      pass->SetRayMode(mode.first);
      pass->SetLaneMarching(mode.second);
      for (int w : sizes)
      {
        for (bool skip : { false, true })
        {
          pass->SetEmptySpaceSkipping(skip);
          if (!pass->Render(scene.Camera, w, w, nullptr, nullptr, hdr)) // warm-up: compile
          {
            return 1;
          }
          std::vector<double> seconds;
          for (int r = 0; r < runs; ++r)
          {
            pass->Render(scene.Camera, w, w, nullptr, nullptr, hdr);
            seconds.push_back(pass->GetLastSeconds());
          }
          const double median = refracta::bench::Median(seconds);
          const double steps = pass->GetLastTotalSteps();
          const std::string rays = std::string(pass->GetLastCurved() ? "curved" : "straight") +
            (pass->GetLastLaneMarching() ? ", 8 lanes" : ", general kernel");
          table.AddRow({ "view pass", rays, std::to_string(w) + "x" + std::to_string(w),
            skip ? (pass->GetLastSkipping() ? "on" : "on (no empty cell)") : "off",
            refracta::bench::Table::Format(pass->GetLastActiveCellFraction()),
            refracta::bench::Table::Format(median * 1e3),
            refracta::bench::Table::Format(steps / (double(w) * w)),
            refracta::bench::Table::Format(steps / median / 1e6), "" });
          std::cout << "  " << rays << " " << w << "x" << w << " skipping " << (skip ? "on" : "off")
                    << ": " << median * 1e3 << " ms\n";
        }
      }
    }
  }

  // ---- Part 5: multiple scattering shaded about its direction, or as isotropic.
  if (runs_part("ms"))
  {
    refracta::scenes::Scene scene = refracta::scenes::GlassSphereInFog(n);
    auto tracer = PhotonPass(scene, photons);
    vtkNew<vtkLatticeBoltzmannLighting> lattice;
    lattice->SetInputData(scene.Medium);
    lattice->SetLightingConnection(tracer->GetOutputPort());
    lattice->Update();
    vtkNew<vtkImageData> isotropic;
    isotropic->ShallowCopy(lattice->GetOutput());
    isotropic->GetPointData()->RemoveArray(
      vtkRefractaLightingVolume::MultipleScatteringDirectionName());
    vtkImageData* lightings[2] = { isotropic, lattice->GetOutput() };
    vtkNew<vtkRefractaViewPass> passes[2];
    std::vector<double> seconds[2];
    const int w = sizes.front();
    for (int r = -1; r < runs; ++r) // run -1: the warm-up (compilation)
    {
      for (int k = 0; k < 2; ++k)
      {
        if ((r < 0 &&
              (!passes[k]->SetMedium(scene.Medium) || !passes[k]->SetLighting(lightings[k]))) ||
          !passes[k]->Render(scene.Camera, w, w, nullptr, nullptr, hdr))
        {
          return 1;
        }
        if (r >= 0)
        {
          seconds[k].push_back(passes[k]->GetLastSeconds());
        }
      }
    }
    const double iso = refracta::bench::Median(seconds[0]);
    const double directed = refracta::bench::Median(seconds[1]);
    for (int k = 0; k < 2; ++k)
    {
      const double median = k == 0 ? iso : directed;
      const double steps = passes[k]->GetLastTotalSteps();
      table.AddRow({ k == 0 ? "S_ms isotropic" : "S_ms about its direction",
        passes[k]->GetLastCurved() ? "curved" : "straight",
        std::to_string(w) + "x" + std::to_string(w), passes[k]->GetLastSkipping() ? "on" : "off",
        refracta::bench::Table::Format(passes[k]->GetLastActiveCellFraction()),
        refracta::bench::Table::Format(median * 1e3),
        refracta::bench::Table::Format(steps / (double(w) * w)),
        refracta::bench::Table::Format(steps / median / 1e6),
        k == 0 ? "" : refracta::bench::Table::Format(directed / iso) });
    }
    std::cout << "  S_ms about its direction " << directed * 1e3 << " ms, isotropic " << iso * 1e3
              << " ms (x" << directed / iso << ")\n";
  }

  // ---- Part 2 and 3: emission-absorption against vtkFixedPointVolumeRayCastMapper, for the
  // default field (a ball filling most of the box) and a small object in the same grid.
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(1.0, 0.08);
  vtkNew<vtkColorTransferFunction> colour;
  colour->AddRGBPoint(0.0, 0.2, 0.3, 1.0);
  colour->AddRGBPoint(0.5, 1.0, 0.6, 0.2);
  colour->AddRGBPoint(1.0, 1.0, 1.0, 0.9);
  vtkNew<vtkVolumeProperty> property;
  property->SetScalarOpacity(opacity);
  property->SetColor(colour);
  property->SetScalarOpacityUnitDistance(1.0 / n);
  property->ShadeOff();
  property->SetInterpolationTypeToLinear();
  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(0.5, 0.5, 0.5);
  camera->SetPosition(1.6, 1.3, 2.4);
  camera->SetViewAngle(30);
  const std::string image = std::to_string(compareSize) + "x" + std::to_string(compareSize);
  std::vector<std::string> summary;

  const double smallCentre[3] = { 0.38, 0.56, 0.44 };
  struct Field
  {
    const char* Name;
    vtkSmartPointer<vtkImageData> Data;
  };
  std::vector<Field> fields;
  if (runs_part("ea"))
  {
    fields.push_back({ "emission-absorption", ScalarField(n) });
  }
  if (runs_part("small"))
  {
    fields.push_back({ "small object (r 0.12) in the grid", ScalarField(n, 0.12, smallCentre) });
  }
  for (const Field& field : fields)
  {
    vtkNew<vtkTransferFunctionMedium> mapping;
    mapping->SetInputData(field.Data);
    mapping->SetVolumeProperty(property);
    mapping->SetEmissionScale(1.0);
    mapping->Update();
    vtkNew<vtkRefractaViewPass> eaPass;
    eaPass->SetRayMode(vtkRefractaViewPass::STRAIGHT);
    eaPass->SetMacroCellSize(cellSize);
    if (!eaPass->SetMedium(mapping->GetOutput()))
    {
      return 1;
    }
    // The general kernel (LaneMarching off) and the eight-lane one (the default here), skipping
    // off and on, in the same run. Cutoff 0: every ray marches through the whole box (without
    // skipping); 1e-4 (the default): rays stop once the medium in front is opaque, like the
    // fixed-point mapper's early ray termination. The last setting is the pass's defaults.
    struct Setting
    {
      bool Lanes;
      double Cutoff;
      bool Skip;
    };
    const Setting settings[] = { { false, 1e-4, false }, { false, 1e-4, true }, { true, 0.0, false },
      { true, 1e-4, false }, { true, 1e-4, true } };
    const int count = static_cast<int>(sizeof(settings) / sizeof(settings[0]));
    auto apply = [&](const Setting& setting)
    {
      eaPass->SetLaneMarching(setting.Lanes);
      eaPass->SetTransmittanceCutoff(setting.Cutoff);
      eaPass->SetEmptySpaceSkipping(setting.Skip);
    };
    std::vector<double> medians(count), steps(count), active(count);
    std::vector<bool> used(count), lanes(count);
    std::vector<float> reference;
    double maxDiff = 0; // of every cutoff-1e-4 image from the general kernel's without skipping
    // Two warm-up renders per setting (kernel builds, first touches of the buffers), then the
    // timed runs interleaved: each run renders every setting and the fixed-point mapper once.
    for (const Setting& setting : settings)
    {
      apply(setting);
      for (int warm = 0; warm < 2; ++warm)
      {
        if (!eaPass->Render(camera, compareSize, compareSize, nullptr, nullptr, hdr))
        {
          return 1;
        }
      }
    }
    FixedPointRenderer fixedPoint(
      field.Data, property, camera, compareSize, n, context->GetNumberOfComputeUnits());
    std::vector<std::vector<double>> seconds(count);
    std::vector<double> vtkSeconds;
    for (int r = 0; r < runs; ++r)
    {
      for (int c = 0; c < count; ++c)
      {
        apply(settings[c]);
        eaPass->Render(camera, compareSize, compareSize, nullptr, nullptr, hdr);
        seconds[c].push_back(eaPass->GetLastSeconds());
        steps[c] = eaPass->GetLastTotalSteps();
        active[c] = eaPass->GetLastActiveCellFraction();
        used[c] = eaPass->GetLastSkipping();
        lanes[c] = eaPass->GetLastLaneMarching();
        if (c == 0)
        {
          reference = hdr;
        }
        else if (settings[c].Cutoff > 0)
        {
          for (size_t i = 0; i < hdr.size(); ++i)
          {
            maxDiff = std::max(maxDiff, static_cast<double>(std::abs(hdr[i] - reference[i])));
          }
        }
      }
      if (fixedPoint.Ready())
      {
        vtkSeconds.push_back(fixedPoint.Render());
      }
    }
    for (int c = 0; c < count; ++c)
    {
      medians[c] = refracta::bench::Median(seconds[c]);
    }
    const double vtkMedian = fixedPoint.Ready() ? refracta::bench::Median(vtkSeconds)
                                                : std::numeric_limits<double>::quiet_NaN();
    const bool haveVTK = !std::isnan(vtkMedian);
    for (int c = 0; c < count; ++c)
    {
      table.AddRow({ field.Name,
        std::string("refracta straight, ") + (lanes[c] ? "8 lanes" : "general kernel") +
          ", cutoff " + (settings[c].Cutoff > 0 ? "1e-4" : "0"),
        image, used[c] ? "on" : "off", refracta::bench::Table::Format(active[c]),
        refracta::bench::Table::Format(medians[c] * 1e3),
        refracta::bench::Table::Format(steps[c] / (double(compareSize) * compareSize)),
        refracta::bench::Table::Format(steps[c] / medians[c] / 1e6),
        haveVTK ? refracta::bench::Table::Format(vtkMedian / medians[c]) : "-" });
    }
    if (haveVTK)
    {
      table.AddRow({ field.Name, "vtkFixedPointVolumeRayCastMapper", image, "", "",
        refracta::bench::Table::Format(vtkMedian * 1e3), "", "", "1" });
    }
    std::ostringstream line;
    line << field.Name << " (" << image << ", " << n << "^3): ";
    if (lanes[3])
    {
      line << "8 lanes / general kernel speed-up " << medians[0] / medians[3]
           << "x without skipping, " << medians[1] / medians[4] << "x with";
    }
    else
    {
      line << "no lanes on this device (the general kernel in every row)";
    }
    line << " (active cells " << active[4] << ", occupancy built in "
         << eaPass->GetOccupancySeconds() * 1e3 << " ms, max |HDR difference| " << maxDiff
         << "); vtkFixedPointVolumeRayCastMapper / Refracta time ratio " << vtkMedian / medians[3]
         << " without, " << vtkMedian / medians[4] << " with skipping (" << vtkMedian * 1e3
         << " ms; general kernel " << vtkMedian / medians[0] << " and " << vtkMedian / medians[1]
         << ")";
    summary.push_back(line.str());
  }

  // ---- Part 4: curved rays through a small glass ball (n = 1.33 inside, ambient 1, boundary
  // smoothed over ~3 voxels with compact support, faint absorption inside) in the same N^3 grid,
  // seen against a grey background: skipping off and on.
  if (runs_part("glass"))
  {
    auto glass = vtkSmartPointer<vtkImageData>::New();
    glass->SetDimensions(n, n, n);
    glass->SetSpacing(1.0 / n, 1.0 / n, 1.0 / n);
    glass->SetOrigin(0.5 / n, 0.5 / n, 0.5 / n);
    const vtkIdType count = static_cast<vtkIdType>(n) * n * n;
    vtkNew<vtkFloatArray> index, extinction;
    index->SetName("RefractiveIndex");
    index->SetNumberOfTuples(count);
    extinction->SetName("Extinction");
    extinction->SetNumberOfComponents(3);
    extinction->SetNumberOfTuples(count);
    const double radius = 0.12, width = 3.0 / n;
    for (int k = 0; k < n; ++k)
    {
      for (int j = 0; j < n; ++j)
      {
        for (int i = 0; i < n; ++i)
        {
          const vtkIdType id = i + n * (j + static_cast<vtkIdType>(n) * k);
          const double x = (i + 0.5) / n - smallCentre[0], y = (j + 0.5) / n - smallCentre[1],
                       z = (k + 0.5) / n - smallCentre[2];
          const double r = std::sqrt(x * x + y * y + z * z);
          // Smoothstep from 1 (r <= radius - width) to 0 (r >= radius): compact support.
          const double a = std::min(1.0, std::max(0.0, (radius - r) / width));
          const double inside = a * a * (3 - 2 * a);
          index->SetValue(id, static_cast<float>(1.0 + 0.33 * inside));
          extinction->SetTuple3(id, 2.0 * inside, 1.0 * inside, 0.5 * inside);
        }
      }
    }
    glass->GetPointData()->AddArray(index);
    glass->GetPointData()->AddArray(extinction);
    vtkNew<vtkRefractaViewPass> glassPass;
    glassPass->SetMacroCellSize(cellSize);
    glassPass->SetBackgroundColor(0.5, 0.5, 0.5);
    if (!glassPass->SetMedium(glass))
    {
      return 1;
    }
    // Differences between two HDR images: the largest, and how many values differ by > 1e-3.
    auto compare =
      [](const std::vector<float>& a, const std::vector<float>& b, double& largest, int& count)
    {
      largest = 0;
      count = 0;
      for (size_t i = 0; i < a.size(); ++i)
      {
        const double d = std::abs(static_cast<double>(a[i]) - b[i]);
        largest = std::max(largest, d);
        count += d > 1e-3 ? 1 : 0;
      }
    };
    double medians[2], steps[2], active[2];
    std::vector<float> reference;
    double maxDiff = 0;
    int bad = 0;
    for (int c = 0; c < 2; ++c)
    {
      glassPass->SetEmptySpaceSkipping(c == 1);
      if (!glassPass->Render(camera, compareSize, compareSize, nullptr, nullptr, hdr))
      {
        return 1;
      }
      std::vector<double> seconds;
      for (int r = 0; r < runs; ++r)
      {
        glassPass->Render(camera, compareSize, compareSize, nullptr, nullptr, hdr);
        seconds.push_back(glassPass->GetLastSeconds());
      }
      medians[c] = refracta::bench::Median(seconds);
      steps[c] = glassPass->GetLastTotalSteps();
      active[c] = glassPass->GetLastActiveCellFraction();
      if (c == 0)
      {
        reference = hdr;
      }
      else
      {
        compare(hdr, reference, maxDiff, bad);
      }
      table.AddRow({ "glass ball (r 0.12) in the grid",
        glassPass->GetLastCurved() ? "refracta curved" : "refracta straight (?)", image,
        glassPass->GetLastSkipping() ? "on" : "off", refracta::bench::Table::Format(active[c]),
        refracta::bench::Table::Format(medians[c] * 1e3),
        refracta::bench::Table::Format(steps[c] / (double(compareSize) * compareSize)),
        refracta::bench::Table::Format(steps[c] / medians[c] / 1e6), "" });
    }
    // What float rounding alone does to these rays: the camera moved by 1e-6 (relative), no
    // skipping. Grazing rays that are totally reflected inside the ball are chaotic, so a few
    // pixels change by O(0.1) either way (skipping lands on positions that differ by rounding;
    // widening the cells' dilation from 2 to 6 voxels leaves the same 64 values changed, so it is
    // not a missed footprint).
    glassPass->SetEmptySpaceSkipping(false);
    double position[3];
    camera->GetPosition(position);
    camera->SetPosition(position[0] * (1 + 1e-6), position[1], position[2]);
    std::vector<float> jittered;
    if (!glassPass->Render(camera, compareSize, compareSize, nullptr, nullptr, jittered))
    {
      return 1;
    }
    camera->SetPosition(position);
    double jitterDiff = 0;
    int jitterBad = 0;
    compare(jittered, reference, jitterDiff, jitterBad);
    std::ostringstream line;
    line << "glass ball, curved rays (" << image << ", " << n << "^3): skipping "
         << medians[0] * 1e3 << " -> " << medians[1] * 1e3 << " ms (" << medians[0] / medians[1]
         << "x, active cells " << active[1] << "); HDR values differing by > 1e-3: " << bad
         << " of " << reference.size() << " (largest " << maxDiff
         << "); without skipping, camera moved by 1e-6: " << jitterBad << " (largest " << jitterDiff
         << ")";
    summary.push_back(line.str());
  }

  table.Print("BenchmarkViewPass (ratio = vtkFixedPointVolumeRayCastMapper time / this time; for "
              "S_ms about its direction: its time / the isotropic one's; skip = whether the "
              "skipping kernel ran; active = macro cells marched)");
  for (const std::string& line : summary)
  {
    std::cout << line << "\n";
  }
  if (!table.WriteCsv(csv))
  {
    return 1;
  }
  return 0;
}
