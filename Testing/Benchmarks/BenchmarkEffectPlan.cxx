// BenchmarkEffectPlan: what the effect plan saves. For each scene (the four procedural benchmark
// scenes, an emission-only and a pure-absorption scene, and two scenes whose effects exist but
// sit below the tolerance: a thin dark fog (multiple scattering) and a faint index bump in fog
// (refraction)), the full pipeline (photon tracer ->
// Lattice-Boltzmann -> view pass) runs once as planned and once with every effect forced on; the
// table gives the median times, their ratio and the relative L2 difference of the two HDR images.
//
//   BenchmarkEffectPlan [--size N] [--image W] [--photons P] [--runs R] [--csv FILE]
#include "RefractaBenchmark.h"
#include "RefractaPipeline.h"
#include "RefractaScenes.h"

#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using refracta::scenes::Scene;

struct Settings
{
  int Size = 48;
  int Image = 128;
  int Photons = 1 << 17;
  int Runs = 3;
  std::string Csv = "effect_plan.csv";
};

std::vector<double> Render(const Scene& scene, vtkEffectPlan* plan, const Settings& settings)
{
  refracta::bench::PipelineKnobs knobs;
  knobs.Photons = settings.Photons;
  knobs.ImageWidth = knobs.ImageHeight = settings.Image;
  return refracta::bench::RenderPipeline(scene, plan, knobs);
}

double RelativeDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  double diff = 0.0, norm = 0.0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
  {
    diff += (a[i] - b[i]) * (a[i] - b[i]);
    norm += b[i] * b[i];
  }
  return norm > 0 ? std::sqrt(diff / norm) : std::sqrt(diff);
}

// Emission only (a glowing ball in an almost clear medium) and pure absorption (no light).
Scene SimpleScene(const std::string& name, int n, bool emission)
{
  Scene scene = refracta::scenes::DenseObject(n);
  scene.Name = name;
  vtkPointData* pd = scene.Medium->GetPointData();
  vtkDataArray* ext = pd->GetArray("Extinction");
  vtkDataArray* emi = pd->GetArray("Emission");
  for (vtkIdType p = 0; p < ext->GetNumberOfTuples(); ++p)
  {
    const double inside = ext->GetComponent(p, 0) / 60.0;
    for (int c = 0; c < 3; ++c)
    {
      ext->SetComponent(p, c, emission ? 1e-3 : 4.0 * inside);
      emi->SetComponent(p, c, emission ? inside : 0.0);
    }
  }
  pd->GetArray("Albedo")->Fill(0.0);
  scene.Lights.clear();
  scene.Background[0] = scene.Background[1] = scene.Background[2] = emission ? 0.0 : 0.6;
  return scene;
}
}

int main(int argc, char* argv[])
{
  Settings settings;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string key = argv[i];
    if (key == "--size")
      settings.Size = std::atoi(argv[i + 1]);
    else if (key == "--image")
      settings.Image = std::atoi(argv[i + 1]);
    else if (key == "--photons")
      settings.Photons = std::atoi(argv[i + 1]);
    else if (key == "--runs")
      settings.Runs = std::atoi(argv[i + 1]);
    else if (key == "--csv")
      settings.Csv = argv[i + 1];
    else
    {
      std::cerr << "unknown option " << key << "\n";
      return 2;
    }
  }
  std::vector<Scene> scenes = refracta::scenes::AllScenes(settings.Size);
  scenes.push_back(SimpleScene("emission-only", settings.Size, true));
  scenes.push_back(SimpleScene("pure-absorption", settings.Size, false));
  {
    // Multiple scattering exists but carries q = 0.15 (1 - exp(-0.05)) < 1% of the scattered light.
    Scene thin = refracta::scenes::HeterogeneousCloud(settings.Size);
    thin.Name = "thin-dark-fog";
    thin.Medium->GetPointData()->GetArray("Extinction")->Fill(0.05);
    thin.Medium->GetPointData()->GetArray("Albedo")->Fill(0.15);
    scenes.push_back(thin);
    // Refraction exists but bends rays by far less than a voxel: n - 1 scaled down to 1e-6.
    Scene faint = refracta::scenes::GlassSphereInFog(settings.Size);
    faint.Name = "faint-index-in-fog";
    vtkDataArray* n = faint.Medium->GetPointData()->GetArray("RefractiveIndex");
    for (vtkIdType p = 0; p < n->GetNumberOfTuples(); ++p)
    {
      n->SetComponent(p, 0, 1.0 + 2e-6 * (n->GetComponent(p, 0) - 1.0));
    }
    refracta::scenes::ComputeIndexGradient(faint.Medium);
    scenes.push_back(faint);
  }

  using refracta::bench::Table;
  Table table({ "scene", "plan", "planned s", "all on s", "speed-up", "image difference" });
  for (const Scene& scene : scenes)
  {
    vtkNew<vtkEffectPlan> planned, everything;
    for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
    {
      everything->SetEffectMode(e, vtkEffectPlan::FORCE_ON);
    }
    if (!refracta::bench::PlanScene(scene, planned) ||
      !refracta::bench::PlanScene(scene, everything))
    {
      return 1;
    }
    std::string on;
    for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
    {
      on += planned->IsEnabled(e) ? std::string(1, "RASME"[e]) : std::string("-");
    }
    std::vector<double> a, b;
    Render(scene, planned, settings); // warm the kernel caches
    Render(scene, everything, settings);
    const double tPlanned =
      refracta::bench::MedianSeconds(settings.Runs, [&] { a = Render(scene, planned, settings); });
    const double tAll = refracta::bench::MedianSeconds(
      settings.Runs, [&] { b = Render(scene, everything, settings); });
    table.AddRow({ scene.Name, on, Table::Format(tPlanned), Table::Format(tAll),
      Table::Format(tAll / tPlanned), Table::Format(RelativeDifference(a, b)) });
  }
  table.Print(
    "Effect plan: planned vs every effect forced on (R refraction, A absorption, S single "
    "scattering, M multiple scattering, E emission)");
  table.WriteCsv(settings.Csv);
  return 0;
}
