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
// With --unbiased-spp N the unbiased path tracer (vtkReferenceRenderer) renders each scene too; a
// second table then gives every estimator's time to 5% and 2% relative noise (interpolated
// between checkpoints, or extrapolated from the last two, marked *; the path tracer's with noise
// ~ time^-1/2) and, where the path tracer converges (the cloud, the dense cube), each photon-mapped
// image's difference from it over the two images' noise and its brightness against the path
// tracer's: the photon mapper's kernel bias, if it shows. Noise is the same measure for every
// estimator: the RMS standard error of a pixel (its three channels summed) over the mean pixel
// value, over the pixels with a value.
//
//   BenchmarkReferencePhotonMapper [--scenes a,b] [--size N] [--image W] [--passes P]
//     [--photons N] [--view-samples S] [--spacings 0,2,1,0.5] [--unbiased-spp N] [--csv FILE]
//     [--smoke]
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
  int UnbiasedSpp = 0; // 0: no path tracer
  std::string Csv;
};

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
      s.Scenes = refracta::bench::SplitList(value);
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
      for (const std::string& v : refracta::bench::SplitList(value))
      {
        s.Spacings.push_back(std::atof(v.c_str()));
      }
    }
    else if (key == "--unbiased-spp")
    {
      s.UnbiasedSpp = std::atoi(value.c_str());
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
    s.Spacings.empty() || s.UnbiasedSpp < 0)
  {
    std::cerr << "need --size >= 4, --image >= 2, --passes >= 2, --photons >= 1, "
                 "--view-samples >= 1, --unbiased-spp >= 0 and at least one spacing\n";
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

// vtkReferencePhotonMapper's CheckpointError measure for any image: RMS over the pixels with a
// value of their summed channels' standard error, over the mean summed value.
double RelativeNoise(const Image& image)
{
  double se2 = 0, mean = 0;
  size_t n = 0;
  for (size_t p = 0; p + 2 < image.Value.size(); p += 3)
  {
    const double m = image.Value[p] + image.Value[p + 1] + image.Value[p + 2];
    if (m > 0)
    {
      const double e = image.Error[p] + image.Error[p + 1] + image.Error[p + 2];
      se2 += e * e;
      mean += m;
      ++n;
    }
  }
  return n > 0 && mean > 0 ? std::sqrt(se2 / n) / (mean / n) : 0;
}

// Sum of the image's values.
double Brightness(const Image& image)
{
  double sum = 0;
  for (double v : image.Value)
  {
    sum += v;
  }
  return sum;
}

// A noise-against-time curve (increasing seconds).
struct Curve
{
  std::vector<double> Seconds, Noise;
};

// Seconds at which the curve reaches `target` noise: log-log interpolation between the
// checkpoints around it, or extrapolation along the last two (`extrapolated` set); -1 if the curve
// does not fall.
double SecondsTo(const Curve& c, double target, bool& extrapolated)
{
  extrapolated = false;
  const size_t n = c.Seconds.size();
  if (n == 0)
  {
    return -1;
  }
  if (c.Noise[0] <= target)
  {
    return c.Seconds[0];
  }
  size_t k = 1;
  while (k < n && c.Noise[k] > target)
  {
    ++k;
  }
  extrapolated = k == n;
  if (n < 2)
  {
    return -1;
  }
  const size_t b = extrapolated ? n - 1 : k, a = b - 1;
  const double slope =
    std::log(c.Noise[b] / c.Noise[a]) / std::log(c.Seconds[b] / c.Seconds[a]); // < 0
  if (!(slope < 0))
  {
    return -1;
  }
  return c.Seconds[a] * std::pow(target / c.Noise[a], 1 / slope);
}

std::string TimeCell(const Curve& c, double target)
{
  bool extrapolated = false;
  const double t = SecondsTo(c, target, extrapolated);
  return t < 0 ? "-" : Table::Format(t) + (extrapolated ? "*" : "");
}

// The scene's photon-mapped images, one per spacing, with their checkpoint rows in `table`; the
// noise curves and images in `curves` and `images`.
bool RenderPhotonMapped(const Scene& scene, const Settings& settings, Table& table,
  std::vector<Curve>& curves, std::vector<Image>& images)
{
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
      std::cerr << scene.Name << ": the photon mapper gave no image\n";
      return false;
    }
    Curve curve;
    for (int k = 0; k <= last; ++k)
    {
      const double passes = FieldValue(output, "CheckpointPasses", k);
      const double seconds = FieldValue(output, "CheckpointSeconds", k);
      const double noise = FieldValue(output, "CheckpointError", k);
      const double efficiency = noise > 0 && seconds > 0 ? 1 / (noise * noise * seconds) : 0;
      curve.Seconds.push_back(seconds);
      curve.Noise.push_back(noise);
      const bool end = k == last;
      if (end && images.empty())
      {
        firstEfficiency = efficiency;
      }
      table.AddRow({ scene.Name, Table::Format(spacing), Table::Format(passes),
        Table::Format(seconds), Table::Format(noise), Table::Format(efficiency),
        end && firstEfficiency > 0 ? Table::Format(efficiency / firstEfficiency) : "-",
        end && !images.empty() ? Table::Format(Agreement(image, images.front())) : "-" });
    }
    curves.push_back(curve);
    images.push_back(image);
  }
  return true;
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
  Table times({ "scene", "estimator", "seconds", "relative noise", "s to 5%", "s to 2%",
    "difference from the path tracer / noise", "brightness / path tracer's" });
  for (const std::string& name : settings.Scenes)
  {
    Scene scene;
    if (!MakeScene(name, settings.Size, scene))
    {
      std::cerr << "unknown scene " << name << "\n";
      return 1;
    }
    std::vector<Curve> curves;
    std::vector<Image> images;
    if (!RenderPhotonMapped(scene, settings, table, curves, images))
    {
      return 1;
    }
    if (settings.UnbiasedSpp < 1)
    {
      continue;
    }
    const Image unbiased =
      refracta::bench::RenderReference(scene, settings.ImageSize, settings.UnbiasedSpp, 1);
    const double noise = RelativeNoise(unbiased);
    auto unbiasedTime = [&](double target) // noise ~ time^-1/2
    {
      return Table::Format(unbiased.Seconds * (noise / target) * (noise / target)) +
        (noise > target ? "*" : "");
    };
    times.AddRow({ name, "path tracer, " + std::to_string(settings.UnbiasedSpp) + " spp",
      Table::Format(unbiased.Seconds), Table::Format(noise), unbiasedTime(0.05), unbiasedTime(0.02),
      "-", "-" });
    for (size_t k = 0; k < images.size(); ++k)
    {
      const Curve& c = curves[k];
      times.AddRow({ name, "photon mapper, spacing " + Table::Format(settings.Spacings[k]),
        Table::Format(c.Seconds.back()), Table::Format(c.Noise.back()), TimeCell(c, 0.05),
        TimeCell(c, 0.02), Table::Format(Agreement(images[k], unbiased)),
        Table::Format(Brightness(images[k]) / Brightness(unbiased)) });
    }
  }
  table.Print("Photon-mapped reference: noise against time by where view rays gather");
  if (settings.UnbiasedSpp > 0)
  {
    times.Print("Time to 5% and 2% noise (* extrapolated), and agreement with the path tracer");
  }
  if (!settings.Csv.empty() && !table.WriteCsv(settings.Csv))
  {
    std::cerr << "could not write " << settings.Csv << "\n";
    return 1;
  }
  return 0;
}
