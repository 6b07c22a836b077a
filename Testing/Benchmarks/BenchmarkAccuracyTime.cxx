// BenchmarkAccuracyTime: what accuracy costs in time.
//
// For each procedural scene (glass sphere with a caustic in fog, heterogeneous cloud, GRIN lens,
// dense high-albedo cube; Support/RefractaScenes.h) the pipeline (analysis and effect plan, photon
// tracer, Lattice-Boltzmann lighting, view pass) renders the scene while one quality knob at a
// time moves away from a base setting: photon count, the photon tracer's minimum step, its octree
// tolerances, the lattice's convergence tolerance and block size, the view step and the volume
// resolution. Each image is compared with a converged vtkReferenceRenderer image of the same scene
// (at the finest resolution of the sweep): relative RMSE over the whole image and over the
// scene's region of interest (e.g. the caustic), with the reference's own Monte Carlo noise
// removed (the expected squared difference is the true squared error plus the reference's
// variance, which its StandardError image gives). The reference renderer's own curve (error
// against time as its samples per pixel grow, another seed) shows how much faster the pipeline
// reaches a given error than unbiased Monte Carlo.
//
// Outputs in --out: accuracy_time.csv (every pipeline run), reference_curve.csv, presets.csv,
// accuracy_<scene>.png (log-log error against time: one curve per knob, the reference's curve,
// the Pareto front and the presets; under an X server) and printed tables: the sweep, the Pareto
// front, the speed-up over the reference at 5% and 2% error, and quality presets chosen from the
// sweep (for a target error, each knob takes its cheapest value whose error stays within the
// target, or within 10% of the best that knob reaches where the target is out of reach, on every
// scene) measured as combinations.
//
//   BenchmarkAccuracyTime [--out DIR] [--image W] [--base-size N] [--reference-spp S]
//     [--reference-curve-max S] [--runs R] [--scenes a,b,...] [--knobs a,b,...] [--cache DIR]
//     [--smoke]
#include "RefractaBenchmark.h"
#include "RefractaPipeline.h"
#include "RefractaScenes.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
using refracta::bench::PipelineKnobs;
using refracta::bench::Table;
using refracta::scenes::Scene;

struct Settings
{
  std::string Out = "accuracy_time";
  std::string Cache;
  int Image = 64;
  int BaseSize = 48;
  int ReferenceSpp = 4096;
  int ReferenceCurveMax = 256;
  int Runs = 3;
  std::vector<std::string> Scenes;
  std::vector<std::string> KnobNames; // empty: every knob
  bool Smoke = false;
};

// One knob of one pass: its name, the values swept and how a value is applied.
struct Knob
{
  std::string Name;
  std::vector<double> Values;
  std::function<void(PipelineKnobs&, double)> Apply;
  std::function<double(const PipelineKnobs&)> Read;
};

std::vector<Knob> MakeKnobs(const Settings& settings)
{
  std::vector<Knob> knobs;
  knobs.push_back({ "photons", { 1 << 12, 1 << 14, 1 << 16, 1 << 18, 1 << 20 },
    [](PipelineKnobs& k, double v) { k.Photons = static_cast<int>(v); },
    [](const PipelineKnobs& k) { return double(k.Photons); } });
  knobs.push_back({ "photon min step", { 4, 2, 1, 0.5, 0.25 },
    [](PipelineKnobs& k, double v) { k.PhotonMinimumStep = v; },
    [](const PipelineKnobs& k) { return k.PhotonMinimumStep; } });
  // Octree tolerances move together (eps' = 4 eps, as the defaults 0.005 / 0.02).
  knobs.push_back({ "octree eps", { 0.0025, 0.005, 0.02, 0.08, 0.32 },
    [](PipelineKnobs& k, double v)
    {
      k.PrimaryTolerance = v;
      k.SecondaryTolerance = 4 * v;
    },
    [](const PipelineKnobs& k) { return k.PrimaryTolerance; } });
  knobs.push_back({ "lattice tolerance", { 1e-2, 1e-3, 1e-4, 1e-5 },
    [](PipelineKnobs& k, double v) { k.LatticeTolerance = v; },
    [](const PipelineKnobs& k) { return k.LatticeTolerance; } });
  knobs.push_back({ "lattice block", { 0, 2, 4, 8 },
    [](PipelineKnobs& k, double v) { k.BlockSize = static_cast<int>(v); },
    [](const PipelineKnobs& k) { return double(k.BlockSize); } });
  knobs.push_back({ "view step", { 2, 1, 0.5, 0.25 },
    [](PipelineKnobs& k, double v) { k.ViewStep = v; },
    [](const PipelineKnobs& k) { return k.ViewStep; } });
  std::vector<double> sizes = { 16, 24, 32, 48, 64 };
  if (settings.Smoke)
  {
    sizes = { 12, 16 };
  }
  knobs.push_back({ "resolution", sizes, [](PipelineKnobs&, double) {},
    [](const PipelineKnobs&) { return 0.0; } });
  if (settings.Smoke)
  {
    for (Knob& knob : knobs)
    {
      if (knob.Name != "resolution")
      {
        knob.Values.resize(2);
      }
    }
    knobs[0].Values = { 1 << 10, 1 << 12 };
  }
  if (!settings.KnobNames.empty())
  {
    const auto& keep = settings.KnobNames;
    knobs.erase(std::remove_if(knobs.begin(), knobs.end(),
                  [&](const Knob& k)
                  { return k.Name != "resolution" && std::find(keep.begin(), keep.end(), k.Name) == keep.end(); }),
      knobs.end());
    if (std::find(keep.begin(), keep.end(), "resolution") == keep.end())
    {
      knobs.back().Values = { static_cast<double>(settings.BaseSize) };
    }
  }
  return knobs;
}

// An RGB image with its per-pixel standard error (zero for the pipeline).
struct Image
{
  std::vector<double> Value;
  std::vector<double> Error;
  double Seconds = 0.0;
};

// Which pixels (i + W j) see the scene's region of interest: the bounding rectangle of its box's
// projected corners.
std::vector<bool> RegionMask(const Scene& scene, int w, int h)
{
  vtkMatrix4x4* m = scene.Camera->GetCompositeProjectionTransformMatrix(double(w) / h, -1, 1);
  double lo[2] = { 1e30, 1e30 }, hi[2] = { -1e30, -1e30 };
  for (int corner = 0; corner < 8; ++corner)
  {
    const double* b = scene.RegionOfInterest;
    const double p[4] = { b[corner & 1], b[2 + ((corner >> 1) & 1)], b[4 + ((corner >> 2) & 1)], 1 };
    double q[4];
    m->MultiplyPoint(p, q);
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], q[a] / q[3]);
      hi[a] = std::max(hi[a], q[a] / q[3]);
    }
  }
  std::vector<bool> mask(static_cast<size_t>(w) * h);
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const double x = 2.0 * (i + 0.5) / w - 1.0, y = 2.0 * (j + 0.5) / h - 1.0;
      mask[i + static_cast<size_t>(w) * j] = x >= lo[0] && x <= hi[0] && y >= lo[1] && y <= hi[1];
    }
  }
  return mask;
}

// Relative RMSE of `image` against `reference` over the masked pixels, with the reference's
// variance taken out: E[(a - r)^2] = (a - truth)^2 + var(r) for an unbiased r independent of a.
double RelativeError(const Image& image, const Image& reference, const std::vector<bool>& mask)
{
  double squared = 0.0, variance = 0.0, norm = 0.0;
  for (size_t p = 0; p < mask.size(); ++p)
  {
    if (!mask[p])
    {
      continue;
    }
    for (int c = 0; c < 3; ++c)
    {
      const size_t v = 3 * p + c;
      const double d = image.Value[v] - reference.Value[v];
      squared += d * d;
      variance += reference.Error[v] * reference.Error[v];
      norm += reference.Value[v] * reference.Value[v];
    }
  }
  return norm > 0 ? std::sqrt(std::max(0.0, squared - variance) / norm) : 0.0;
}

// sqrt(sum SE^2 / sum value^2): the relative RMSE the reference's own noise amounts to.
double NoiseLevel(const Image& image)
{
  double variance = 0.0, norm = 0.0;
  for (size_t v = 0; v < image.Value.size(); ++v)
  {
    variance += image.Error[v] * image.Error[v];
    norm += image.Value[v] * image.Value[v];
  }
  return norm > 0 ? std::sqrt(variance / norm) : 0.0;
}

Image ReadImage(vtkImageData* output)
{
  Image image;
  vtkDataArray* hdr = output->GetPointData()->GetArray("HDR");
  vtkDataArray* se = output->GetPointData()->GetArray("StandardError");
  for (vtkIdType p = 0; hdr && p < hdr->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      image.Value.push_back(hdr->GetComponent(p, c));
      image.Error.push_back(se ? std::max(0.0, se->GetComponent(p, c)) : 0.0);
    }
  }
  if (vtkDataArray* seconds = output->GetFieldData()->GetArray("RenderSeconds"))
  {
    image.Seconds = seconds->GetComponent(0, 0);
  }
  return image;
}

// Write an image as an 8-bit PNG, scaled so that the reference's 99th percentile maps to white,
// with the sRGB-like 1/2.2 gamma: the same scale for the pipeline and the reference.
void WritePng(const std::string& path, const Image& image, int size, double scale)
{
  vtkNew<vtkImageData> png;
  png->SetDimensions(size, size, 1);
  png->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* pixels = static_cast<unsigned char*>(png->GetScalarPointer());
  for (size_t v = 0; v < image.Value.size() && v < 3u * size * size; ++v)
  {
    const double x = std::min(1.0, std::max(0.0, image.Value[v] * scale));
    pixels[v] = static_cast<unsigned char>(std::lround(255.0 * std::pow(x, 1.0 / 2.2)));
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(png);
  writer->SetFileName(path.c_str());
  writer->Write();
}

// Write an RGB image as a VTK XML image with a float "HDR" array, for a closer look.
void WriteHdr(const std::string& path, const Image& image, int size)
{
  vtkNew<vtkImageData> hdr;
  hdr->SetDimensions(size, size, 1);
  vtkNew<vtkFloatArray> values;
  values->SetName("HDR");
  values->SetNumberOfComponents(3);
  values->SetNumberOfTuples(static_cast<vtkIdType>(size) * size);
  for (size_t v = 0; v < image.Value.size() && v < 3u * size * size; ++v)
  {
    values->SetValue(static_cast<vtkIdType>(v), static_cast<float>(image.Value[v]));
  }
  hdr->GetPointData()->AddArray(values);
  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(hdr);
  writer->SetFileName(path.c_str());
  writer->Write();
}

double WhiteScale(const Image& reference)
{
  std::vector<double> values = reference.Value;
  if (values.empty())
  {
    return 1.0;
  }
  std::nth_element(values.begin(), values.begin() + values.size() * 99 / 100, values.end());
  const double p99 = values[values.size() * 99 / 100];
  return p99 > 0 ? 1.0 / p99 : 1.0;
}

Image RenderReference(const Scene& scene, int size, int spp, unsigned int seed)
{
  vtkNew<vtkReferenceRenderer> reference;
  reference->SetInputData(scene.Medium);
  reference->SetCamera(scene.Camera);
  for (const auto& light : scene.Lights)
  {
    reference->AddLight(light);
  }
  reference->SetImageSize(size, size);
  reference->SetBackgroundColor(scene.Background[0], scene.Background[1], scene.Background[2]);
  reference->SetLightRadius(scene.LightRadius);
  reference->SetDirectionalLightAngularRadius(scene.LightAngularRadius);
  reference->SetSamplesPerPixel(spp);
  reference->SetSeed(seed);
  const auto start = std::chrono::steady_clock::now();
  reference->Update();
  Image image = ReadImage(reference->GetOutput());
  image.Seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return image;
}

// The converged reference, read from the cache directory when an earlier run left it there.
Image ConvergedReference(const Scene& scene, int resolution, const Settings& settings)
{
  std::ostringstream name;
  name << settings.Cache << "/" << scene.Name << "_" << resolution << "_" << settings.Image << "_"
       << settings.ReferenceSpp << "_r" << scene.LightRadius << "_a" << scene.LightAngularRadius
       << ".vti";
  struct stat info;
  if (!settings.Cache.empty() && stat(name.str().c_str(), &info) == 0)
  {
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(name.str().c_str());
    reader->Update();
    Image image = ReadImage(reader->GetOutput());
    if (image.Value.size() == 3u * settings.Image * settings.Image)
    {
      std::cout << "  reference read from " << name.str() << "\n";
      return image;
    }
  }
  vtkNew<vtkReferenceRenderer> reference;
  reference->SetInputData(scene.Medium);
  reference->SetCamera(scene.Camera);
  for (const auto& light : scene.Lights)
  {
    reference->AddLight(light);
  }
  reference->SetImageSize(settings.Image, settings.Image);
  reference->SetBackgroundColor(scene.Background[0], scene.Background[1], scene.Background[2]);
  reference->SetLightRadius(scene.LightRadius);
  reference->SetDirectionalLightAngularRadius(scene.LightAngularRadius);
  reference->SetSamplesPerPixel(settings.ReferenceSpp);
  reference->SetSeed(1);
  reference->Update();
  if (!settings.Cache.empty())
  {
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(reference->GetOutput());
    writer->SetFileName(name.str().c_str());
    writer->Write();
  }
  Image image = ReadImage(reference->GetOutput());
  std::cout << "  converged reference: " << settings.ReferenceSpp << " samples per pixel in "
            << image.Seconds << " s\n";
  return image;
}

struct Point
{
  std::string Scene;
  std::string Knob;
  double Value = 0;
  double Seconds = 0;
  double ImageError = 0;
  double RegionError = 0;
};

// Points no other point beats in both time and error, by increasing time.
std::vector<Point> ParetoFront(std::vector<Point> points)
{
  std::sort(points.begin(), points.end(),
    [](const Point& a, const Point& b) { return a.Seconds < b.Seconds; });
  std::vector<Point> front;
  for (const Point& p : points)
  {
    if (front.empty() || p.ImageError < front.back().ImageError)
    {
      front.push_back(p);
    }
  }
  return front;
}

// Time at which a curve of (seconds, error) first reaches `target`, interpolated log-log between
// its points; < 0 when it never does. `extrapolate` continues a Monte Carlo curve past its last
// point with the error ~ time^(-1/2) law.
double TimeToError(const std::vector<std::pair<double, double>>& curve, double target,
  bool extrapolate, bool* extrapolated)
{
  *extrapolated = false;
  for (size_t i = 0; i < curve.size(); ++i)
  {
    if (curve[i].second <= target)
    {
      if (i == 0)
      {
        return curve[0].first;
      }
      const double t0 = std::log(curve[i - 1].first), t1 = std::log(curve[i].first);
      const double e0 = std::log(curve[i - 1].second), e1 = std::log(curve[i].second);
      const double f = (std::log(target) - e0) / (e1 - e0);
      return std::exp(t0 + f * (t1 - t0));
    }
  }
  if (extrapolate && !curve.empty() && curve.back().second > 0)
  {
    *extrapolated = true;
    const double ratio = curve.back().second / target;
    return curve.back().first * ratio * ratio;
  }
  return -1.0;
}

std::string FormatSpeedUp(double pipeline, double reference, bool extrapolated)
{
  if (pipeline < 0)
  {
    return "not reached";
  }
  return Table::Format(reference / pipeline) + (extrapolated ? " (ref. extrapolated)" : "");
}

std::vector<std::string> Split(const std::string& text)
{
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, ',');)
  {
    parts.push_back(part);
  }
  return parts;
}

bool ParseArguments(int argc, char* argv[], Settings& settings)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string key = argv[i];
    if (key == "--smoke")
    {
      settings.Smoke = true;
      settings.Image = 12;
      settings.BaseSize = 16;
      settings.ReferenceSpp = 16;
      settings.ReferenceCurveMax = 4;
      settings.Runs = 1;
      continue;
    }
    if (i + 1 >= argc)
    {
      std::cerr << "option " << key << " needs a value\n";
      return false;
    }
    const std::string value = argv[++i];
    if (key == "--out")
      settings.Out = value;
    else if (key == "--cache")
      settings.Cache = value;
    else if (key == "--image")
      settings.Image = std::atoi(value.c_str());
    else if (key == "--base-size")
      settings.BaseSize = std::atoi(value.c_str());
    else if (key == "--reference-spp")
      settings.ReferenceSpp = std::atoi(value.c_str());
    else if (key == "--reference-curve-max")
      settings.ReferenceCurveMax = std::atoi(value.c_str());
    else if (key == "--runs")
      settings.Runs = std::atoi(value.c_str());
    else if (key == "--scenes")
      settings.Scenes = Split(value);
    else if (key == "--knobs")
      settings.KnobNames = Split(value);
    else
    {
      std::cerr << "unknown option " << key
                << "; valid: --out --cache --image --base-size --reference-spp "
                   "--reference-curve-max --runs --scenes --knobs --smoke\n";
      return false;
    }
  }
  if (settings.Image < 4 || settings.BaseSize < 4 || settings.ReferenceSpp < 1 ||
    settings.ReferenceCurveMax < 1 || settings.Runs < 1)
  {
    std::cerr << "--image and --base-size must be >= 4, --reference-spp, --reference-curve-max "
                 "and --runs >= 1\n";
    return false;
  }
  return true;
}

// Everything measured on one scene.
struct SceneResult
{
  std::vector<Point> Points;                        // pipeline runs (sweeps)
  std::vector<std::pair<double, double>> Reference; // (seconds, image error)
  std::vector<Point> ReferencePoints;
};

class Benchmark
{
public:
  explicit Benchmark(const Settings& settings)
    : Config(settings)
    , Knobs(MakeKnobs(settings))
  {
    for (double size : this->Knobs.back().Values)
    {
      this->FinestSize = std::max(this->FinestSize, static_cast<int>(size));
    }
    this->Base.ImageWidth = this->Base.ImageHeight = settings.Image;
  }

  int Run();

private:
  const Scene& SceneAt(const std::string& name, int size);
  Point Measure(const std::string& sceneName, const PipelineKnobs& knobs, int size,
    const Image& reference, const std::vector<bool>& mask);
  void SweepScene(const std::string& name, SceneResult& result);
  void ReferenceCurve(const std::string& name, SceneResult& result);
  void ChoosePresets(std::vector<std::string>& names);
  void Report(const std::vector<std::string>& names);

  Settings Config;
  std::vector<Knob> Knobs;
  PipelineKnobs Base;
  int FinestSize = 0;
  std::map<std::string, Scene> Scenes; // by name and size
  std::map<std::string, Image> References;
  std::map<std::string, std::vector<bool>> Masks;
  std::map<std::string, SceneResult> Results;
  std::vector<std::string> AllScenes;
  Table Runs{ { "scene", "knob", "value", "seconds", "image error", "region error" } };
  Table ReferenceRuns{ { "scene", "samples per pixel", "seconds", "image error",
    "region error" } };
  Table Presets{ { "preset", "target", "photons", "photon min step", "octree eps",
    "lattice tolerance", "lattice block", "view step", "resolution", "scene", "seconds",
    "image error", "region error" } };
  std::map<std::string, std::vector<Point>> PresetPoints;
};

const Scene& Benchmark::SceneAt(const std::string& name, int size)
{
  const std::string key = name + "@" + std::to_string(size);
  auto found = this->Scenes.find(key);
  if (found == this->Scenes.end())
  {
    for (Scene& scene : refracta::scenes::AllScenes(size))
    {
      this->Scenes[scene.Name + "@" + std::to_string(size)] = scene;
    }
    found = this->Scenes.find(key);
  }
  return found->second;
}

Point Benchmark::Measure(const std::string& sceneName, const PipelineKnobs& knobs, int size,
  const Image& reference, const std::vector<bool>& mask)
{
  const Scene& scene = this->SceneAt(sceneName, size);
  vtkNew<vtkEffectPlan> plan;
  refracta::bench::PlanScene(scene, plan);
  Image image;
  image.Seconds = refracta::bench::MedianSeconds(this->Config.Runs,
    [&]
    {
      // The plan is part of the pipeline's cost: analyse and decide on every run.
      vtkNew<vtkEffectPlan> timedPlan;
      refracta::bench::PlanScene(scene, timedPlan);
      image.Value = refracta::bench::RenderPipeline(scene, timedPlan, knobs);
    });
  image.Error.assign(image.Value.size(), 0.0);
  Point point;
  point.Scene = sceneName;
  point.Seconds = image.Seconds;
  if (image.Value.size() != reference.Value.size())
  {
    std::cerr << "pipeline image of " << sceneName << " has the wrong size\n";
    point.ImageError = point.RegionError = std::nan("");
    return point;
  }
  std::vector<bool> all(mask.size(), true);
  point.ImageError = RelativeError(image, reference, all);
  point.RegionError = RelativeError(image, reference, mask);
  return point;
}

void Benchmark::SweepScene(const std::string& name, SceneResult& result)
{
  const Image& reference = this->References[name];
  const std::vector<bool>& mask = this->Masks[name];
  // Warm the kernel caches so that no run pays for compilation; keep that image to look at.
  {
    const Scene& scene = this->SceneAt(name, this->Config.BaseSize);
    vtkNew<vtkEffectPlan> plan;
    refracta::bench::PlanScene(scene, plan);
    Image image;
    image.Value = refracta::bench::RenderPipeline(scene, plan, this->Base);
    const double scale = WhiteScale(reference);
    WritePng(this->Config.Out + "/pipeline_" + name + ".png", image, this->Config.Image, scale);
    WritePng(this->Config.Out + "/reference_" + name + ".png", reference, this->Config.Image, scale);
    WriteHdr(this->Config.Out + "/pipeline_" + name + ".vti", image, this->Config.Image);
    std::cout << "  plan: " << plan->GetSummary() << "\n";
  }
  std::map<std::string, Point> measured; // identical settings are measured once
  for (const Knob& knob : this->Knobs)
  {
    for (double value : knob.Values)
    {
      PipelineKnobs knobs = this->Base;
      int size = this->Config.BaseSize;
      if (knob.Name == "resolution")
      {
        size = static_cast<int>(value);
      }
      else
      {
        knob.Apply(knobs, value);
      }
      std::ostringstream key;
      key << size << " " << knobs.Photons << " " << knobs.PhotonMinimumStep << " "
          << knobs.PrimaryTolerance << " " << knobs.LatticeTolerance << " " << knobs.BlockSize
          << " " << knobs.ViewStep;
      auto found = measured.find(key.str());
      Point point = found != measured.end()
        ? found->second
        : (measured[key.str()] = this->Measure(name, knobs, size, reference, mask));
      point.Knob = knob.Name;
      point.Value = value;
      result.Points.push_back(point);
      this->Runs.AddRow({ name, knob.Name, Table::Format(value), Table::Format(point.Seconds),
        Table::Format(point.ImageError), Table::Format(point.RegionError) });
      std::cout << "  " << knob.Name << " = " << value << ": " << point.Seconds << " s, error "
                << point.ImageError << " (region " << point.RegionError << ")\n"
                << std::flush;
    }
  }
}

void Benchmark::ReferenceCurve(const std::string& name, SceneResult& result)
{
  const Scene& scene = this->SceneAt(name, this->FinestSize);
  std::vector<bool> all(this->Masks[name].size(), true);
  for (int spp = 1; spp <= this->Config.ReferenceCurveMax; spp *= 2)
  {
    const Image image = RenderReference(scene, this->Config.Image, spp, 2);
    Point point;
    point.Scene = name;
    point.Knob = "reference";
    point.Value = spp;
    point.Seconds = image.Seconds;
    point.ImageError = RelativeError(image, this->References[name], all);
    point.RegionError = RelativeError(image, this->References[name], this->Masks[name]);
    result.Reference.emplace_back(point.Seconds, point.ImageError);
    result.ReferencePoints.push_back(point);
    this->ReferenceRuns.AddRow({ name, std::to_string(spp), Table::Format(point.Seconds),
      Table::Format(point.ImageError), Table::Format(point.RegionError) });
  }
}

// For each target error: every knob takes its cheapest swept value whose image error stays within
// max(target, 1.1 x the knob's best) on every scene; the combination is then measured.
void Benchmark::ChoosePresets(std::vector<std::string>& names)
{
  const std::vector<std::pair<std::string, double>> targets = { { "draft", 0.10 },
    { "interactive", 0.05 }, { "production", 0.02 } };
  for (const auto& target : targets)
  {
    PipelineKnobs knobs = this->Base;
    int size = this->Config.BaseSize;
    for (const Knob& knob : this->Knobs)
    {
      double bestValue = 0.0, bestSeconds = 1e300;
      bool found = false;
      for (double value : knob.Values)
      {
        double seconds = 0.0;
        bool within = true;
        for (const std::string& name : names)
        {
          double best = 1e300, error = 0.0, time = 0.0;
          for (const Point& p : this->Results[name].Points)
          {
            if (p.Knob == knob.Name)
            {
              best = std::min(best, p.ImageError);
              if (p.Value == value)
              {
                error = p.ImageError;
                time = p.Seconds;
              }
            }
          }
          within = within && error <= std::max(target.second, 1.1 * best);
          seconds += time;
        }
        if (within && seconds < bestSeconds)
        {
          bestSeconds = seconds;
          bestValue = value;
          found = true;
        }
      }
      if (!found)
      {
        continue;
      }
      if (knob.Name == "resolution")
      {
        size = static_cast<int>(bestValue);
      }
      else
      {
        knob.Apply(knobs, bestValue);
      }
    }
    for (const std::string& name : names)
    {
      Point point = this->Measure(name, knobs, size, this->References[name], this->Masks[name]);
      point.Knob = target.first;
      this->PresetPoints[name].push_back(point);
      this->Presets.AddRow({ target.first, Table::Format(target.second),
        std::to_string(knobs.Photons), Table::Format(knobs.PhotonMinimumStep),
        Table::Format(knobs.PrimaryTolerance), Table::Format(knobs.LatticeTolerance),
        std::to_string(knobs.BlockSize), Table::Format(knobs.ViewStep), std::to_string(size),
        name, Table::Format(point.Seconds), Table::Format(point.ImageError),
        Table::Format(point.RegionError) });
    }
  }
}

void Benchmark::Report(const std::vector<std::string>& names)
{
  Table front({ "scene", "knob", "value", "seconds", "image error", "region error" });
  Table speedUp({ "scene", "pipeline best error", "pipeline s to 5%", "reference s to 5%",
    "speed-up at 5%", "pipeline s to 2%", "reference s to 2%", "speed-up at 2%" });
  for (const std::string& name : names)
  {
    SceneResult& result = this->Results[name];
    std::vector<Point> all = result.Points;
    for (const Point& p : this->PresetPoints[name])
    {
      all.push_back(p);
    }
    const std::vector<Point> pareto = ParetoFront(all);
    std::vector<std::pair<double, double>> frontCurve;
    for (const Point& p : pareto)
    {
      front.AddRow({ name, p.Knob, Table::Format(p.Value), Table::Format(p.Seconds),
        Table::Format(p.ImageError), Table::Format(p.RegionError) });
      frontCurve.emplace_back(p.Seconds, p.ImageError);
    }
    std::vector<std::string> row = { name, Table::Format(pareto.back().ImageError) };
    for (double target : { 0.05, 0.02 })
    {
      bool unused = false, extrapolated = false;
      const double tPipeline = TimeToError(frontCurve, target, false, &unused);
      const double tReference = TimeToError(result.Reference, target, true, &extrapolated);
      row.push_back(tPipeline < 0 ? "-" : Table::Format(tPipeline));
      row.push_back(Table::Format(tReference) + (extrapolated ? "*" : ""));
      row.push_back(FormatSpeedUp(tPipeline, tReference, extrapolated));
    }
    speedUp.AddRow(row);

    // The plot: one curve per knob, the reference's curve, the front and the presets.
    std::vector<refracta::bench::Series> series;
    for (const Knob& knob : this->Knobs)
    {
      refracta::bench::Series curve{ knob.Name, {}, {} };
      for (const Point& p : result.Points)
      {
        if (p.Knob == knob.Name && p.ImageError > 0)
        {
          curve.X.push_back(p.Seconds);
          curve.Y.push_back(p.ImageError);
        }
      }
      series.push_back(curve);
    }
    refracta::bench::Series reference{ "reference Monte Carlo", {}, {} };
    for (const auto& p : result.Reference)
    {
      reference.X.push_back(p.first);
      reference.Y.push_back(std::max(p.second, 1e-6));
    }
    refracta::bench::Series paretoSeries{ "Pareto front", {}, {} };
    for (const auto& p : frontCurve)
    {
      paretoSeries.X.push_back(p.first);
      paretoSeries.Y.push_back(std::max(p.second, 1e-6));
    }
    refracta::bench::Series presets{ "presets", {}, {} };
    for (const Point& p : this->PresetPoints[name])
    {
      presets.X.push_back(p.Seconds);
      presets.Y.push_back(std::max(p.ImageError, 1e-6));
    }
    series.push_back(reference);
    series.push_back(paretoSeries);
    series.push_back(presets);
    refracta::bench::WritePlot(this->Config.Out + "/accuracy_" + name + ".png",
      name + ": relative RMSE against time", "seconds", "relative RMSE (image)", series);
  }
  this->Runs.Print("Accuracy and time: one knob at a time from the base setting");
  this->ReferenceRuns.Print("Reference renderer: error against time (seed 2 against the "
                            "converged seed-1 image)");
  this->Presets.Print("Quality presets chosen from the sweep, measured");
  front.Print("Pareto front per scene (all runs and presets)");
  speedUp.Print("Speed-up of the pipeline over the reference renderer at equal error (* "
                "extrapolated with error ~ time^-1/2)");
  this->Runs.WriteCsv(this->Config.Out + "/accuracy_time.csv");
  this->ReferenceRuns.WriteCsv(this->Config.Out + "/reference_curve.csv");
  this->Presets.WriteCsv(this->Config.Out + "/presets.csv");
  front.WriteCsv(this->Config.Out + "/pareto.csv");
  speedUp.WriteCsv(this->Config.Out + "/speed_up.csv");
}

int Benchmark::Run()
{
  mkdir(this->Config.Out.c_str(), 0755);
  if (!this->Config.Cache.empty())
  {
    mkdir(this->Config.Cache.c_str(), 0755);
  }
  std::vector<std::string> names;
  for (const Scene& scene : refracta::scenes::AllScenes(4))
  {
    if (this->Config.Scenes.empty() ||
      std::find(this->Config.Scenes.begin(), this->Config.Scenes.end(), scene.Name) !=
        this->Config.Scenes.end())
    {
      names.push_back(scene.Name);
    }
  }
  if (names.empty())
  {
    std::cerr << "--scenes matches none of glass-sphere-in-fog, heterogeneous-cloud, grin-lens, "
                 "dense-high-albedo\n";
    return 2;
  }
  for (const std::string& name : names)
  {
    std::cout << name << "\n";
    const Scene& finest = this->SceneAt(name, this->FinestSize);
    this->References[name] = ConvergedReference(finest, this->FinestSize, this->Config);
    this->Masks[name] = RegionMask(finest, this->Config.Image, this->Config.Image);
    const Image& reference = this->References[name];
    std::cout << "  reference noise (relative standard error of the image): "
              << NoiseLevel(this->References[name]) << "\n";
    this->ReferenceCurve(name, this->Results[name]);
    this->SweepScene(name, this->Results[name]);
  }
  this->ChoosePresets(names);
  this->Report(names);
  return 0;
}
}

int main(int argc, char* argv[])
{
  Settings settings;
  if (!ParseArguments(argc, argv, settings))
  {
    return 2;
  }
  return Benchmark(settings).Run();
}
