// BenchmarkReferencePhotonMapper: how fast the ground truth for refracted light converges, by
// where its view rays gather photons (issue 19).
//
// vtkReferencePhotonMapper's view rays either gather at their first real collision in the medium
// (GatherSpacing 0: delta tracking, one gather per view path, the estimator of Knaus and Zwicker
// with Jarosz et al.'s point-point 3D kernel) or at every tentative collision along the whole ray,
// weighted by its probability of being real (ratio tracking) with tentative collisions at least
// every GatherSpacing x the pass's radius. For each scene (the accuracy benchmark's glass sphere
// in fog, GRIN lens and heterogeneous cloud; RefractaScenes.h) and each spacing, the same passes
// of the same photons are rendered; the program prints, at each of the renderer's checkpoints,
// the time and the relative noise (the spread of 8 independent streams), the efficiency
// 1 / (noise^2 x seconds) at the end and its ratio to the first-collision estimator's (measured in
// the same run), and whether the two estimators agree: their images' difference over its expected
// size from both noise estimates (about 1 when both converge to the same image: they share the
// kernel's bias at each pass, so a larger value would be a bias of the ratio-tracking sum).
//
//   BenchmarkReferencePhotonMapper [--scenes a,b] [--size N] [--image W] [--passes P]
//     [--photons N] [--view-samples S] [--spacings 0,2,1,0.5] [--csv FILE] [--smoke]
#include "RefractaBenchmark.h"
#include "RefractaReferenceImages.h"
#include "RefractaScenes.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using refracta::bench::Image;
using refracta::bench::Table;
using refracta::scenes::Scene;

struct Settings
{
  std::vector<std::string> Scenes = { "glass-sphere-in-fog", "grin-lens", "heterogeneous-cloud" };
  int Size = 48;
  int ImageSize = 32;
  int Passes = 64;
  int Photons = 20000;
  int ViewSamples = 8;
  std::vector<double> Spacings = { 0, 2, 1, 0.5 };
  std::string Csv;
};

std::vector<std::string> Split(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
  {
    items.push_back(item);
  }
  return items;
}

bool Parse(int argc, char* argv[], Settings& s)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string key = argv[i];
    if (key == "--smoke")
    {
      s.Size = 16;
      s.ImageSize = 12;
      s.Passes = 8;
      s.Photons = 2000;
      s.ViewSamples = 2;
      s.Spacings = { 0, 1 };
      continue;
    }
    if (i + 1 >= argc)
    {
      std::cerr << "missing value after " << key << "\n";
      return false;
    }
    const std::string value = argv[++i];
    if (key == "--scenes")
    {
      s.Scenes = Split(value);
    }
    else if (key == "--size")
    {
      s.Size = std::atoi(value.c_str());
    }
    else if (key == "--image")
    {
      s.ImageSize = std::atoi(value.c_str());
    }
    else if (key == "--passes")
    {
      s.Passes = std::atoi(value.c_str());
    }
    else if (key == "--photons")
    {
      s.Photons = std::atoi(value.c_str());
    }
    else if (key == "--view-samples")
    {
      s.ViewSamples = std::atoi(value.c_str());
    }
    else if (key == "--spacings")
    {
      s.Spacings.clear();
      for (const std::string& v : Split(value))
      {
        s.Spacings.push_back(std::atof(v.c_str()));
      }
    }
    else if (key == "--csv")
    {
      s.Csv = value;
    }
    else
    {
      std::cerr << "unknown option " << key << "\n";
      return false;
    }
  }
  if (s.Size < 4 || s.ImageSize < 2 || s.Passes < 2 || s.Photons < 1 || s.ViewSamples < 1 ||
    s.Spacings.empty())
  {
    std::cerr << "need --size >= 4, --image >= 2, --passes >= 2, --photons >= 1, "
                 "--view-samples >= 1 and at least one spacing\n";
    return false;
  }
  return true;
}

bool MakeScene(const std::string& name, int n, Scene& scene)
{
  for (Scene& s : refracta::scenes::AllScenes(n))
  {
    if (s.Name == name)
    {
      scene = s;
      return true;
    }
  }
  return false;
}

// The two images' difference over its expected size: sqrt(sum (a - b)^2 / sum (SE_a^2 + SE_b^2))
// over the values either estimates (sums, not per-pixel ratios: a pixel whose few streams all
// read 0 has a standard error of 0). About 1 when both converge to the same image.
double Agreement(const Image& a, const Image& b)
{
  double d2 = 0, var = 0;
  for (size_t v = 0; v < a.Value.size(); ++v)
  {
    const double ea = std::max(a.Error[v], 0.0), eb = std::max(b.Error[v], 0.0);
    if (ea > 0 || eb > 0)
    {
      const double d = a.Value[v] - b.Value[v];
      d2 += d * d;
      var += ea * ea + eb * eb;
    }
  }
  return var > 0 ? std::sqrt(d2 / var) : 0;
}

double FieldValue(vtkImageData* image, const char* name, int index)
{
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  return a && index < a->GetNumberOfTuples() ? a->GetComponent(index, 0) : -1;
}
} // namespace

int main(int argc, char* argv[])
{
  Settings settings;
  if (!Parse(argc, argv, settings))
  {
    return 1;
  }
  Table table({ "scene", "gather spacing (radii)", "passes", "seconds", "relative noise",
    "efficiency 1/(noise^2 s)", "efficiency vs first collision", "difference / its noise" });
  bool ok = true;
  for (const std::string& name : settings.Scenes)
  {
    Scene scene;
    if (!MakeScene(name, settings.Size, scene))
    {
      std::cerr << "unknown scene " << name << "\n";
      return 1;
    }
    Image first;
    double firstEfficiency = 0;
    for (double spacing : settings.Spacings)
    {
      vtkNew<vtkImageData> output;
      const Image image = refracta::bench::RenderPhotonReference(scene, settings.ImageSize,
        settings.Passes, settings.Photons, settings.ViewSamples, 1, output, spacing);
      vtkDataArray* checkpoints = output->GetFieldData()->GetArray("CheckpointPasses");
      const int last = checkpoints ? static_cast<int>(checkpoints->GetNumberOfTuples()) - 1 : -1;
      if (last < 0 || image.Value.empty())
      {
        std::cerr << name << ": the photon mapper gave no image\n";
        ok = false;
        continue;
      }
      const bool isFirst = first.Value.empty();
      for (int k = 0; k <= last; ++k)
      {
        const double passes = FieldValue(output, "CheckpointPasses", k);
        const double seconds = FieldValue(output, "CheckpointSeconds", k);
        const double noise = FieldValue(output, "CheckpointError", k);
        const double efficiency = noise > 0 && seconds > 0 ? 1 / (noise * noise * seconds) : 0;
        const bool end = k == last;
        if (end && isFirst)
        {
          firstEfficiency = efficiency;
        }
        table.AddRow({ name, Table::Format(spacing), Table::Format(passes), Table::Format(seconds),
          Table::Format(noise), Table::Format(efficiency),
          end && firstEfficiency > 0 ? Table::Format(efficiency / firstEfficiency) : "-",
          end && !isFirst ? Table::Format(Agreement(image, first)) : "-" });
      }
      if (isFirst)
      {
        first = image;
      }
    }
  }
  table.Print("Photon-mapped reference: noise against time by where view rays gather");
  if (!settings.Csv.empty() && !table.WriteCsv(settings.Csv))
  {
    std::cerr << "could not write " << settings.Csv << "\n";
    return 1;
  }
  return ok ? 0 : 1;
}
