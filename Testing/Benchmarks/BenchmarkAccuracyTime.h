/**
 * @file    BenchmarkAccuracyTime.h
 * @brief   Private to BenchmarkAccuracyTime (its two source files): the settings, the knobs, one
 *          scene's measurements and the benchmark itself. The program's description is at the top
 *          of BenchmarkAccuracyTime.cxx.
 */
#ifndef BenchmarkAccuracyTime_h
#define BenchmarkAccuracyTime_h

#include "RefractaBenchmark.h"
#include "RefractaPipeline.h"
#include "RefractaReferenceImages.h"
#include "RefractaScenes.h"

#include <algorithm>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace refracta
{
namespace accuracy
{
using refracta::bench::Image;
using refracta::bench::PipelineKnobs;
using refracta::bench::Table;
using refracta::scenes::Scene;

struct Settings
{
  std::string Out = "accuracy_time";
  std::string Cache;
  int Image = 64;
  int BaseSize = 48;
  int ReferenceSpp = 65536;      // at most; the time budget decides
  double ReferenceSeconds = 150; // budget of the converged reference per scene
  int ReferenceCurveMax = 256;
  int PhotonsPerPass = 50000;  // the photon mapper's, on the photon-mapped scenes
  int ViewSamples = 16;        // its view rays per pixel and pass
  double UnbiasedSeconds = 20; // the short path tracer run whose noise is extrapolated
  int Runs = 3;
  std::vector<std::string> Scenes;
  std::vector<std::string> KnobNames; // empty: every knob
  bool Smoke = false;
};

// What one pipeline run is given: the passes' knobs and the grid resolution of the scene.
struct Setting
{
  PipelineKnobs Knobs;
  int Size = 48;
};

// One knob: its name, the values swept and how a value is applied.
struct Knob
{
  std::string Name;
  std::vector<double> Values;
  std::function<void(Setting&, double)> Apply;
};

// One pipeline run: its time and its errors against the converged reference (ground truth, where
// the reference converged) and against the pipeline's own most accurate setting (how far the
// knob's value is from what the pipeline converges to).
struct Point
{
  std::string Knob;
  double Value = 0;
  double Seconds = 0;
  double ReferenceError = 0;
  double ReferenceRegionError = 0;
  double SelfError = 0;
  double SelfRegionError = 0;
  // Against the run with this knob at its most accurate value and every other knob at the base:
  // the error this knob alone contributes.
  double KnobError = 0;
  double KnobRegionError = 0;
  Image Picture;
};

// The reference converged when its own noise is below these (relative RMSE); its variance is
// taken out of every error, so errors of that size stay measurable.
constexpr double ConvergedImageNoise = 0.02;
constexpr double ConvergedRegionNoise = 0.03;

// Everything measured on one scene.
struct SceneResult
{
  Image Reference;
  Image Finest;
  std::vector<bool> Region;
  // Pixels that see the medium (the reference has noise there): errors "over the image" are
  // taken over these, so that background pixels, exact in both renderers, do not dilute them.
  std::vector<bool> Seen;
  double ImageNoise = 0;
  double RegionNoise = 0;
  bool Converged = false;
  bool PhotonMapped = false; // the truth is the photon mapper's
  // The unbiased path tracer on photon-mapped scenes: its noise after a short run of that many
  // seconds (for its extrapolated time to an error).
  double UnbiasedNoise = 0;
  double UnbiasedSeconds = 0;
  std::vector<Point> Points;          // pipeline runs (sweeps)
  std::vector<Point> ReferencePoints; // the reference renderer's own curve
  std::vector<Point> Presets;
  // The error the fronts and plots use: against the reference where it converged, otherwise
  // against the pipeline's most accurate setting.
  double Error(const Point& p) const { return this->Converged ? p.ReferenceError : p.SelfError; }
};

// Points no other point beats in both time and error, by increasing time.
std::vector<Point> ParetoFront(std::vector<Point> points, const SceneResult& result);

// Time at which a curve of (seconds, error) first reaches `target`, interpolated log-log between
// its points; < 0 when it never does. `extrapolate` continues a Monte Carlo curve past its last
// point with the error ~ time^(-exponent) law (1/2 for unbiased Monte Carlo; Alpha / 2 = 1/3,
// the noise rate of the photon mapper's schedule, for progressive photon mapping).
double TimeToError(const std::vector<std::pair<double, double>>& curve, double target,
  bool extrapolate, bool* extrapolated, double exponent = 0.5);

// The knobs swept and how each is applied (BenchmarkAccuracyTime.cxx).
std::vector<Knob> MakeKnobs(const Settings& settings);

class Benchmark
{
public:
  explicit Benchmark(const Settings& settings)
    : Config(settings)
    , Knobs(MakeKnobs(settings))
  {
    this->Base.Knobs.ImageWidth = this->Base.Knobs.ImageHeight = settings.Image;
    this->Base.Size = settings.BaseSize;
    // Multiple scattering by the lattice alone at the base, as the presets were measured; the
    // methods are the "photon orders" knob.
    this->Base.Knobs.ScatteringOrders = 0;
    // The most accurate setting: every knob at its most accurate swept value.
    this->Most = this->Base;
    for (const Knob& knob : this->Knobs)
    {
      if (knob.Name != "lattice block") // a speed knob: every block size converges alike
      {
        knob.Apply(this->Most, MostAccurate(knob));
      }
    }
  }

  int Run();

private:
  static double MostAccurate(const Knob& knob)
  {
    // More photons and voxels are more accurate; for every other knob, smaller is.
    const bool more = knob.Name.compare(0, 7, "photons") == 0 || knob.Name == "resolution";
    return more ? *std::max_element(knob.Values.begin(), knob.Values.end())
                : *std::min_element(knob.Values.begin(), knob.Values.end());
  }
  const Scene& SceneAt(const std::string& name, int size);
  Image RenderTimed(const std::string& name, const Setting& setting);
  Point Measure(const std::string& name, const Setting& setting);
  void SweepScene(const std::string& name);
  void ReferenceCurve(const std::string& name);
  void ChoosePresets(const std::vector<std::string>& names);
  // Measures `setting` on every scene as the preset `label` (target error `target`).
  void MeasurePreset(const std::string& label, double target, const Setting& setting,
    const std::vector<std::string>& names);
  void MeasureShippedPresets(const std::vector<std::string>& names);
  void Report(const std::vector<std::string>& names);
  void Plot(const std::string& name);

  Settings Config;
  std::vector<Knob> Knobs;
  Setting Base, Most;
  std::map<std::string, Scene> Scenes; // by name@size
  std::map<std::string, SceneResult> Results;
  Table Runs{ { "scene", "knob", "value", "seconds", "error vs reference", "region vs reference",
    "error vs finest", "knob error", "knob region error" } };
  Table ReferenceRuns{ { "scene", "estimator", "samples per pixel or passes", "seconds", "error",
    "region error" } };
  Table Presets{ { "preset", "target", "photons", "photon min step", "octree eps",
    "lattice tolerance", "lattice block", "view step", "resolution", "scene", "seconds",
    "error vs reference", "region vs reference", "error vs finest", "region vs finest" } };
};

} // namespace accuracy
} // namespace refracta

#endif
