// BenchmarkAccuracyTime: what accuracy costs in time.
//
// For each procedural scene (glass sphere with a caustic in fog, heterogeneous cloud, GRIN lens,
// dense high-albedo cube; Support/RefractaScenes.h) the pipeline (analysis and effect plan, photon
// tracer, Lattice-Boltzmann lighting, view pass) renders the scene while one quality knob at a
// time moves away from a base setting: photon count, the photon tracer's minimum step, its octree
// tolerances, the lattice's convergence tolerance and block size, the view step and the volume
// resolution. Each image gets two errors (relative RMSE over the pixels that see the medium, where
// the reference has noise: background pixels are exact in both renderers, and over the scene's
// region of interest, e.g. the caustic):
// - against a converged reference image of the same scene with the same extended lights (at the
//   finest resolution of the sweep), with the reference's own Monte Carlo noise taken out (the
//   expected squared difference is the true squared error plus the reference's variance, which
//   its StandardError image gives). The reference is vtkReferenceRenderer (unbiased path tracing)
//   where it converges, and vtkReferencePhotonMapper (stochastic progressive photon mapping, a
//   consistent estimator) on the scenes where light is refracted before it scatters (the glass
//   sphere in fog, the GRIN lens), where the path tracer does not converge (issue #19). This is
//   the ground truth where the reference converged within its time budget (relative noise <= 2%
//   over the image and 3% in the region);
// - against the pipeline's own most accurate setting (every knob at its most accurate value):
//   how far a knob's value is from what the pipeline converges to. Where refracted light makes
//   the unbiased reference too noisy to converge (caustics), this is the error that is shown.
// The reference's own curve (error against time as its samples per pixel or passes grow, another
// seed) gives how much faster the pipeline reaches 5% and 2% error than the reference; on the
// photon-mapped scenes the unbiased renderer's time to those errors is extrapolated from its
// noise after a short run (noise ~ time^-1/2), for the speed-up against unbiased Monte Carlo.
//
// Outputs in --out: accuracy_time.csv (every pipeline run), reference_curve.csv, presets.csv,
// pareto.csv, speed_up.csv, accuracy_<scene>.png (log-log error against time: one curve per knob,
// the reference's curve, the Pareto front and the presets; needs an X server), the reference and
// finest pipeline images (PNG) and printed tables. Quality presets are chosen from the sweep:
// for a target error (draft 10%, interactive 5%, production 2%), each knob takes its cheapest
// value whose error against the finest setting stays within the target, or within 10% of the
// best that knob reaches where the target is out of reach, on every scene; the combinations are
// then measured, and so are the presets the library ships (vtkEffectPlan::SetQuality: "shipped
// draft", ...), against the same truths.
//
//   BenchmarkAccuracyTime [--out DIR] [--image W] [--base-size N] [--reference-seconds S]
//     [--reference-spp MAX] [--reference-curve-max S] [--runs R] [--scenes a,b,...]
//     [--knobs a,b,...] [--cache DIR] [--photons-per-pass N] [--unbiased-seconds S] [--smoke]
#include "BenchmarkAccuracyTime.h"

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
#include "vtkReferencePhotonMapper.h"
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

namespace refracta
{
namespace accuracy
{
namespace
{
using refracta::bench::NoiseLevel;
using refracta::bench::ReadImage;
using refracta::bench::RelativeError;
using refracta::bench::RenderPhotonReference;
using refracta::bench::RenderReference;

// An RGB image with its per-pixel standard error (zero for the pipeline).
// Which pixels (i + W j) see the scene's region of interest: the bounding rectangle of its box's
// projected corners.
std::vector<bool> RegionMask(const Scene& scene, int w, int h)
{
  vtkMatrix4x4* m = scene.Camera->GetCompositeProjectionTransformMatrix(double(w) / h, -1, 1);
  double lo[2] = { 1e30, 1e30 }, hi[2] = { -1e30, -1e30 };
  for (int corner = 0; corner < 8; ++corner)
  {
    const double* b = scene.RegionOfInterest;
    const double p[4] = { b[corner & 1], b[2 + ((corner >> 1) & 1)], b[4 + ((corner >> 2) & 1)],
      1 };
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

// The scenes whose ground truth is the photon mapper: light refracted before it scatters, which
// the unbiased path tracer does not converge on (Documentation/Benchmarks.md).
bool UsesPhotonMapper(const std::string& scene)
{
  return scene == "glass-sphere-in-fog" || scene == "grin-lens";
}

// The photon mapper's image of `scene` after `passes` passes.
Image PhotonReference(
  const Scene& scene, int passes, unsigned int seed, const Settings& settings, vtkImageData* out)
{
  return RenderPhotonReference(
    scene, settings.Image, passes, settings.PhotonsPerPass, settings.ViewSamples, seed, out);
}

// The converged reference, read from the cache directory when an earlier run left it there.
Image ConvergedReference(const Scene& scene, int resolution, const Settings& settings)
{
  const bool photonMap = UsesPhotonMapper(scene.Name);
  std::ostringstream name;
  name << settings.Cache << "/" << scene.Name << "_" << resolution << "_" << settings.Image << "_"
       << settings.ReferenceSeconds << "s_r" << scene.LightRadius << "_a"
       << scene.LightAngularRadius
       << (photonMap ? "_sppm" + std::to_string(settings.PhotonsPerPass) : std::string()) << ".vti";
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
  if (photonMap)
  {
    // Passes: the largest power of two (>= 8) that fits the time budget, timed on 4.
    const double t4 = PhotonReference(scene, 4, 3, settings, nullptr).Seconds;
    int passes = 8;
    while (t4 * (2 * passes) / 4 <= settings.ReferenceSeconds)
    {
      passes *= 2;
    }
    vtkNew<vtkImageData> output;
    const Image image = PhotonReference(scene, passes, 1, settings, output);
    if (!settings.Cache.empty())
    {
      vtkNew<vtkXMLImageDataWriter> writer;
      writer->SetInputData(output);
      writer->SetFileName(name.str().c_str());
      writer->Write();
    }
    std::cout << "  converged reference (photon mapper): " << passes << " passes of "
              << settings.PhotonsPerPass << " photons in " << image.Seconds << " s\n";
    return image;
  }
  // Samples per pixel: the largest power of two that fits the time budget, timed on 16.
  const double t16 = RenderReference(scene, settings.Image, 16, 3).Seconds;
  int spp = 16;
  while (2 * spp <= settings.ReferenceSpp && t16 * (2 * spp) / 16 <= settings.ReferenceSeconds)
  {
    spp *= 2;
  }
  vtkNew<vtkImageData> output;
  const Image image = RenderReference(scene, settings.Image, spp, 1, output);
  if (!settings.Cache.empty())
  {
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(output);
    writer->SetFileName(name.str().c_str());
    writer->Write();
  }
  std::cout << "  converged reference: " << spp << " samples per pixel in " << image.Seconds
            << " s\n";
  return image;
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
      settings.ReferenceSeconds = 1;
      settings.ReferenceCurveMax = 4;
      settings.PhotonsPerPass = 2000;
      settings.ViewSamples = 1;
      settings.UnbiasedSeconds = 0.5;
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
    else if (key == "--reference-seconds")
      settings.ReferenceSeconds = std::atof(value.c_str());
    else if (key == "--reference-curve-max")
      settings.ReferenceCurveMax = std::atoi(value.c_str());
    else if (key == "--photons-per-pass")
      settings.PhotonsPerPass = std::atoi(value.c_str());
    else if (key == "--view-samples")
      settings.ViewSamples = std::atoi(value.c_str());
    else if (key == "--unbiased-seconds")
      settings.UnbiasedSeconds = std::atof(value.c_str());
    else if (key == "--runs")
      settings.Runs = std::atoi(value.c_str());
    else if (key == "--scenes")
      settings.Scenes = refracta::bench::SplitList(value);
    else if (key == "--knobs")
      settings.KnobNames = refracta::bench::SplitList(value);
    else
    {
      std::cerr << "unknown option " << key
                << "; valid: --out --cache --image --base-size --reference-spp "
                   "--reference-seconds --reference-curve-max --photons-per-pass --view-samples "
                   "--unbiased-seconds --runs --scenes --knobs --smoke\n";
      return false;
    }
  }
  if (settings.Image < 4 || settings.BaseSize < 4 || settings.ReferenceSpp < 1 ||
    settings.ReferenceCurveMax < 1 || settings.Runs < 1 || settings.PhotonsPerPass < 1 ||
    settings.ViewSamples < 1)
  {
    std::cerr << "--image and --base-size must be >= 4, --reference-spp, --reference-curve-max, "
                 "--photons-per-pass, --view-samples and --runs >= 1\n";
    return false;
  }
  return true;
}
} // namespace

std::vector<Knob> MakeKnobs(const Settings& settings)
{
  std::vector<Knob> knobs;
  knobs.push_back({ "photons", { 1 << 12, 1 << 14, 1 << 16, 1 << 18, 1 << 20 },
    [](Setting& s, double v) { s.Knobs.Photons = static_cast<int>(v); } });
  knobs.push_back({ "photon min step", { 4, 2, 1, 0.5, 0.25 },
    [](Setting& s, double v) { s.Knobs.PhotonMinimumStep = v; } });
  // Octree tolerances move together (eps' = 4 eps, as the defaults 0.005 / 0.02).
  knobs.push_back({ "octree eps", { 0.0025, 0.005, 0.02, 0.08, 0.32 },
    [](Setting& s, double v)
    {
      s.Knobs.PrimaryTolerance = v;
      s.Knobs.SecondaryTolerance = 4 * v;
    } });
  knobs.push_back({ "lattice tolerance", { 1e-2, 1e-3, 1e-4, 1e-5 },
    [](Setting& s, double v) { s.Knobs.LatticeTolerance = v; } });
  knobs.push_back({ "lattice block", { 0, 2, 4, 8 },
    [](Setting& s, double v) { s.Knobs.BlockSize = static_cast<int>(v); } });
  knobs.push_back(
    { "view step", { 2, 1, 0.5, 0.25 }, [](Setting& s, double v) { s.Knobs.ViewStep = v; } });
  // Multiple scattering (issue 14): photon orders k with D3Q6 (0: the lattice alone, -1: every
  // order by photons), then D3Q18 as k + 100.
  knobs.push_back({ "photon orders", { 0, 1, 3, 7, 100, 103, -1 },
    [](Setting& s, double v)
    {
      const int k = static_cast<int>(v);
      s.Knobs.Lattice = k >= 100 ? 18 : 6;
      s.Knobs.ScatteringOrders = k >= 100 ? k - 100 : k;
    } });
  // Every order by photons, as their number grows: the photon method's own convergence (on the
  // dense cube it is what reaches 3%, where the lattice's bias stays at 5-7%).
  knobs.push_back({ "photons every order", { 1 << 16, 1 << 18, 1 << 20, 1 << 22 },
    [](Setting& s, double v)
    {
      s.Knobs.Photons = static_cast<int>(v);
      s.Knobs.ScatteringOrders = -1;
    } });
  knobs.push_back({ "resolution",
    settings.Smoke ? std::vector<double>{ 12, 16 } : std::vector<double>{ 16, 24, 32, 48, 64 },
    [](Setting& s, double v) { s.Size = static_cast<int>(v); } });
  if (settings.Smoke)
  {
    for (Knob& knob : knobs)
    {
      knob.Values.resize(2);
    }
    for (Knob& knob : knobs)
    {
      if (knob.Name.compare(0, 7, "photons") == 0)
      {
        knob.Values = { 1 << 10, 1 << 12 };
      }
    }
  }
  if (!settings.KnobNames.empty())
  {
    const auto& keep = settings.KnobNames;
    knobs.erase(
      std::remove_if(knobs.begin(), knobs.end(),
        [&](const Knob& k) { return std::find(keep.begin(), keep.end(), k.Name) == keep.end(); }),
      knobs.end());
  }
  return knobs;
}

const Scene& Benchmark::SceneAt(const std::string& name, int size)
{
  const std::string key = name + "@" + std::to_string(size);
  auto found = this->Scenes.find(key);
  if (found == this->Scenes.end())
  {
    for (const auto& set :
      { refracta::scenes::AllScenes(size), refracta::scenes::ExtraScenes(size) })
    {
      for (const Scene& scene : set)
      {
        this->Scenes[scene.Name + "@" + std::to_string(size)] = scene;
      }
    }
    found = this->Scenes.find(key);
  }
  return found->second;
}

// The whole pipeline, the plan included (analysed and decided on every run, as in an
// application), median time of Runs runs.
Image Benchmark::RenderTimed(const std::string& name, const Setting& setting)
{
  const Scene& scene = this->SceneAt(name, setting.Size);
  const PipelineKnobs& knobs = setting.Knobs;
  // Kernels are compiled per option set (step lengths, variants are -D options): a cheap untimed
  // run with the same options first, so that no timed run pays for a compilation.
  PipelineKnobs warm = knobs;
  warm.Photons = 1024;
  warm.LatticeTolerance = 1.0;
  warm.ImageWidth = warm.ImageHeight = 8;
  {
    vtkNew<vtkEffectPlan> plan;
    refracta::bench::PlanScene(scene, plan);
    refracta::bench::RenderPipeline(scene, plan, warm);
  }
  Image image;
  image.Seconds = refracta::bench::MedianSeconds(this->Config.Runs,
    [&]
    {
      vtkNew<vtkEffectPlan> plan;
      refracta::bench::PlanScene(scene, plan);
      image.Value = refracta::bench::RenderPipeline(scene, plan, knobs);
    });
  image.Error.assign(image.Value.size(), 0.0);
  return image;
}

Point Benchmark::Measure(const std::string& name, const Setting& setting)
{
  const SceneResult& result = this->Results[name];
  const Image image = this->RenderTimed(name, setting);
  Point point;
  point.Seconds = image.Seconds;
  if (image.Value.size() != result.Reference.Value.size())
  {
    std::cerr << "pipeline image of " << name << " has the wrong size\n";
    point.ReferenceError = point.ReferenceRegionError = std::nan("");
    point.SelfError = point.SelfRegionError = std::nan("");
    return point;
  }
  const std::vector<bool>& all = result.Seen;
  point.ReferenceError = RelativeError(image, result.Reference, all);
  point.ReferenceRegionError = RelativeError(image, result.Reference, result.Region);
  point.SelfError = RelativeError(image, result.Finest, all);
  point.SelfRegionError = RelativeError(image, result.Finest, result.Region);
  point.Picture = image;
  return point;
}

void Benchmark::SweepScene(const std::string& name)
{
  SceneResult& result = this->Results[name];
  std::map<std::string, Point> measured; // identical settings are measured once
  for (const Knob& knob : this->Knobs)
  {
    for (double value : knob.Values)
    {
      Setting setting = this->Base;
      knob.Apply(setting, value);
      const PipelineKnobs& k = setting.Knobs;
      std::ostringstream key;
      key << setting.Size << " " << k.Photons << " " << k.PhotonMinimumStep << " "
          << k.PrimaryTolerance << " " << k.LatticeTolerance << " " << k.BlockSize << " "
          << k.ViewStep << " " << k.ScatteringOrders << " " << k.Lattice;
      auto found = measured.find(key.str());
      Point point = found != measured.end() ? found->second
                                            : (measured[key.str()] = this->Measure(name, setting));
      point.Knob = knob.Name;
      point.Value = value;
      result.Points.push_back(point);
      std::cout << "  " << knob.Name << " = " << value << ": " << point.Seconds
                << " s, error vs reference " << point.ReferenceError << " (region "
                << point.ReferenceRegionError << "), vs finest " << point.SelfError << "\n"
                << std::flush;
    }
    // The knob's own error: against its most accurate value.
    const std::vector<bool>& all = result.Seen;
    const Point* best = nullptr;
    for (const Point& p : result.Points)
    {
      best = p.Knob == knob.Name && p.Value == MostAccurate(knob) ? &p : best;
    }
    for (Point& p : result.Points)
    {
      if (p.Knob == knob.Name && best)
      {
        p.KnobError = RelativeError(p.Picture, best->Picture, all);
        p.KnobRegionError = RelativeError(p.Picture, best->Picture, result.Region);
        this->Runs.AddRow({ name, knob.Name, Table::Format(p.Value), Table::Format(p.Seconds),
          Table::Format(p.ReferenceError), Table::Format(p.ReferenceRegionError),
          Table::Format(p.SelfError), Table::Format(p.KnobError),
          Table::Format(p.KnobRegionError) });
      }
    }
  }
}

void Benchmark::ReferenceCurve(const std::string& name)
{
  SceneResult& result = this->Results[name];
  const Scene& scene = this->SceneAt(name, this->Most.Size);
  const std::vector<bool>& all = result.Seen;
  if (result.PhotonMapped)
  {
    // The photon mapper's own curve (another seed) against the converged photon-mapped truth,
    // and the unbiased path tracer's noise after a short run.
    for (int passes = 2; passes <= this->Config.ReferenceCurveMax; passes *= 2)
    {
      const Image image = PhotonReference(scene, passes, 2, this->Config, nullptr);
      Point point;
      point.Knob = "reference";
      point.Value = passes;
      point.Seconds = image.Seconds;
      point.ReferenceError = RelativeError(image, result.Reference, all);
      point.ReferenceRegionError = RelativeError(image, result.Reference, result.Region);
      result.ReferencePoints.push_back(point);
      this->ReferenceRuns.AddRow(
        { name, "photon mapper", std::to_string(passes), Table::Format(point.Seconds),
          Table::Format(point.ReferenceError), Table::Format(point.ReferenceRegionError) });
    }
    const double t16 = RenderReference(scene, this->Config.Image, 16, 3).Seconds;
    const int spp = std::max(
      16, static_cast<int>(16 * this->Config.UnbiasedSeconds / std::max(t16, 1e-3)) / 16 * 16);
    const Image unbiased = RenderReference(scene, this->Config.Image, spp, 4);
    result.UnbiasedNoise = NoiseLevel(unbiased, all);
    result.UnbiasedSeconds = unbiased.Seconds;
    std::cout << "  unbiased path tracer: " << spp << " samples per pixel in " << unbiased.Seconds
              << " s, noise " << result.UnbiasedNoise << "\n";
    return;
  }
  for (int spp = 1; spp <= this->Config.ReferenceCurveMax; spp *= 2)
  {
    const Image image = RenderReference(scene, this->Config.Image, spp, 2);
    Point point;
    point.Knob = "reference";
    point.Value = spp;
    point.Seconds = image.Seconds;
    point.ReferenceError = RelativeError(image, result.Reference, all);
    point.ReferenceRegionError = RelativeError(image, result.Reference, result.Region);
    result.ReferencePoints.push_back(point);
    this->ReferenceRuns.AddRow(
      { name, "path tracer", std::to_string(spp), Table::Format(point.Seconds),
        Table::Format(point.ReferenceError), Table::Format(point.ReferenceRegionError) });
  }
}

int Benchmark::Run()
{
  mkdir(this->Config.Out.c_str(), 0755);
  if (!this->Config.Cache.empty())
  {
    mkdir(this->Config.Cache.c_str(), 0755);
  }
  std::vector<std::string> names;
  const auto& wanted = this->Config.Scenes;
  auto named = [&](const Scene& scene)
  { return std::find(wanted.begin(), wanted.end(), scene.Name) != wanted.end(); };
  for (const Scene& scene : refracta::scenes::AllScenes(4))
  {
    if (wanted.empty() || named(scene))
    {
      names.push_back(scene.Name);
    }
  }
  for (const Scene& scene : refracta::scenes::ExtraScenes(4))
  {
    if (named(scene)) // only when asked for
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
    SceneResult& result = this->Results[name];
    const Scene& finest = this->SceneAt(name, this->Most.Size);
    result.PhotonMapped = UsesPhotonMapper(name);
    result.Reference = ConvergedReference(finest, this->Most.Size, this->Config);
    result.Region = RegionMask(finest, this->Config.Image, this->Config.Image);
    result.Seen.assign(result.Region.size(), false);
    for (size_t v = 0; v < result.Reference.Error.size(); ++v)
    {
      // Rounding leaves standard errors of ~1e-9 x the value where every sample is the same.
      result.Seen[v / 3] =
        result.Seen[v / 3] || result.Reference.Error[v] > 1e-6 * result.Reference.Value[v];
    }
    result.ImageNoise = NoiseLevel(result.Reference, result.Seen);
    result.RegionNoise = NoiseLevel(result.Reference, result.Region);
    result.Converged =
      result.ImageNoise <= ConvergedImageNoise && result.RegionNoise <= ConvergedRegionNoise;
    std::cout << "  reference noise (relative): image " << result.ImageNoise << ", region "
              << result.RegionNoise << (result.Converged ? " (converged)" : " (not converged)")
              << "\n";
    // The most accurate setting, which the other runs are also compared with.
    result.Finest = this->RenderTimed(name, this->Most);
    std::cout << "  finest pipeline setting: " << result.Finest.Seconds << " s\n";
    const double scale = WhiteScale(result.Reference);
    WritePng(
      this->Config.Out + "/pipeline_" + name + ".png", result.Finest, this->Config.Image, scale);
    WritePng(this->Config.Out + "/reference_" + name + ".png", result.Reference, this->Config.Image,
      scale);
    WriteHdr(this->Config.Out + "/pipeline_" + name + ".vti", result.Finest, this->Config.Image);
    this->ReferenceCurve(name);
    this->SweepScene(name);
  }
  this->ChoosePresets(names);
  this->MeasureShippedPresets(names);
  this->Report(names);
  return 0;
}
} // namespace accuracy
} // namespace refracta

int main(int argc, char* argv[])
{
  using namespace refracta::accuracy;
  Settings settings;
  if (!ParseArguments(argc, argv, settings))
  {
    return 2;
  }
  return Benchmark(settings).Run();
}
