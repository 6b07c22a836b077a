// The benchmark helpers compute medians correctly, write a CSV that reads back, and (with an X
// server) write a non-empty PNG plot.
#include "RefractaBenchmark.h"
#include "RefractaScenes.h"
#include "vtkRefractaRenderWindowCheck.h"

#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkSceneAnalysis.h"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

int main(int argc, char* argv[])
{
  using namespace refracta::bench;
  const std::string dir = argc > 1 ? argv[1] : ".";
  int failures = 0;
  auto check = [&](bool ok, const char* what)
  {
    if (!ok)
    {
      std::cerr << "FAIL: " << what << "\n";
      ++failures;
    }
  };
  check(Median({ 3, 1, 2 }) == 2, "odd median");
  check(Median({ 4, 1, 3, 2 }) == 2.5, "even median");
  check(Median({}) == 0, "empty median");
  int calls = 0;
  const double seconds = MedianSeconds(5, [&] { ++calls; });
  check(calls == 5 && seconds >= 0, "MedianSeconds runs the work each time");
  check(PeakMemoryMiB() > 1.0, "peak memory is reported");

  Table table({ "photons", "seconds" });
  table.AddRow({ Table::Format(65536), Table::Format(0.012345678) });
  table.Print("smoke");
  const std::string csv = dir + "/benchmark-support.csv";
  check(table.WriteCsv(csv), "CSV written");
  std::ifstream in(csv);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  check(header == "photons,seconds" && row == "65536,0.01235", "CSV content");

  // Every procedural scene is a valid medium with the facts it is designed to have.
  for (const auto& scene : refracta::scenes::AllScenes(24))
  {
    vtkNew<vtkMediumValidator> validator;
    check(validator->Validate(scene.Medium), scene.Name.c_str());
    vtkNew<vtkSceneAnalysis> analysis;
    analysis->SetMedium(scene.Medium);
    for (const auto& light : scene.Lights)
    {
      analysis->AddLight(light);
    }
    check(analysis->Analyze() && analysis->GetNumberOfPoweredLights() == 1, "scene is analysable");
    std::cout << scene.Name << ": " << analysis->GetSummary() << "\n";
    if (scene.Name == "glass-sphere-in-fog")
    {
      check(analysis->GetRefractiveIndexRange()[1] > 1.45, "glass reaches n = 1.5");
      check(analysis->GetHasScattering(), "fog scatters");
    }
    if (scene.Name == "dense-high-albedo")
    {
      // 60 per unit across a cube of side 0.4 (smoothed edges): tau about 24.
      const double tau = analysis->GetMaximumOpticalThickness();
      check(tau > 22 && tau < 26, "dense object tau about 24");
    }
  }

  if (vtkRefractaRenderWindowCheck::CanOpen())
  {
    const std::string png = dir + "/benchmark-support.png";
    std::remove(png.c_str());
    check(
      WritePlot(png, "smoke", "time (s)", "error", { { "a", { 1, 10, 100 }, { 1, 0.1, 0.01 } } }),
      "plot rendered");
    std::ifstream p(png, std::ios::binary | std::ios::ate);
    check(p && p.tellg() > 1000, "PNG written");
  }
  std::cout << (failures ? "benchmark support FAILED" : "benchmark support passed") << "\n";
  return failures ? 1 : 0;
}
