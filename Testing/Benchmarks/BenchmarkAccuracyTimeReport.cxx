// BenchmarkAccuracyTime's results: the Pareto fronts, the quality presets chosen from the sweep,
// the plots and the printed and CSV tables (the program's description is in
// BenchmarkAccuracyTime.cxx).
#include "BenchmarkAccuracyTime.h"

#include "vtkEffectPlan.h"
#include "vtkNew.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace refracta
{
namespace accuracy
{
using refracta::bench::NoiseLevel;

std::vector<Point> ParetoFront(std::vector<Point> points, const SceneResult& result)
{
  std::sort(points.begin(), points.end(),
    [](const Point& a, const Point& b) { return a.Seconds < b.Seconds; });
  std::vector<Point> front;
  for (const Point& p : points)
  {
    if (front.empty() || result.Error(p) < result.Error(front.back()))
    {
      front.push_back(p);
    }
  }
  return front;
}

double TimeToError(const std::vector<std::pair<double, double>>& curve, double target,
  bool extrapolate, bool* extrapolated, double exponent)
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
      const double e0 = std::log(std::max(curve[i - 1].second, 1e-12));
      const double e1 = std::log(std::max(curve[i].second, 1e-12));
      const double f = (std::log(target) - e0) / (e1 - e0);
      return std::exp(t0 + f * (t1 - t0));
    }
  }
  if (extrapolate && !curve.empty() && curve.back().second > 0)
  {
    *extrapolated = true;
    const double ratio = curve.back().second / target;
    return curve.back().first * std::pow(ratio, 1.0 / exponent);
  }
  return -1.0;
}

// For a target error e, every knob takes its cheapest swept value whose own error (against its
// most accurate value) stays within e / sqrt(K) on every scene, K the number of knobs: the
// knobs' errors add roughly in quadrature, so the combination should stay near e. The
// combinations are then measured on every scene against the reference and the finest setting.
void Benchmark::ChoosePresets(const std::vector<std::string>& names)
{
  const std::vector<std::pair<std::string, double>> targets = { { "draft", 0.10 },
    { "interactive", 0.05 }, { "production", 0.02 } };
  for (const auto& target : targets)
  {
    Setting setting = this->Base;
    const double budget = target.second / std::sqrt(static_cast<double>(this->Knobs.size()));
    for (const Knob& knob : this->Knobs)
    {
      double chosen = 0.0, cheapest = 1e300;
      bool found = false;
      for (double value : knob.Values)
      {
        double seconds = 0.0;
        bool within = true;
        for (const std::string& name : names)
        {
          double error = 1e300, time = 0.0;
          for (const Point& p : this->Results[name].Points)
          {
            if (p.Knob == knob.Name && p.Value == value)
            {
              error = p.KnobError;
              time = p.Seconds;
            }
          }
          within = within && error <= budget;
          seconds += time;
        }
        if (within && seconds < cheapest)
        {
          cheapest = seconds;
          chosen = value;
          found = true;
        }
      }
      if (found)
      {
        knob.Apply(setting, chosen);
      }
    }
    this->MeasurePreset(target.first, target.second, setting, names);
  }
}

void Benchmark::MeasurePreset(const std::string& label, double target, const Setting& setting,
  const std::vector<std::string>& names)
{
  for (const std::string& name : names)
  {
    Point point = this->Measure(name, setting);
    const PipelineKnobs& knobs = setting.Knobs;
    point.Knob = label;
    this->Results[name].Presets.push_back(point);
    this->Presets.AddRow({ label, Table::Format(target), std::to_string(knobs.Photons),
      Table::Format(knobs.PhotonMinimumStep), Table::Format(knobs.PrimaryTolerance),
      Table::Format(knobs.LatticeTolerance), std::to_string(knobs.BlockSize),
      Table::Format(knobs.ViewStep), std::to_string(setting.Size), name,
      Table::Format(point.Seconds), Table::Format(point.ReferenceError),
      Table::Format(point.ReferenceRegionError), Table::Format(point.SelfError),
      Table::Format(point.SelfRegionError) });
  }
}

// The presets the library ships (vtkEffectPlan::SetQuality, its Recommended* settings, and the
// automatic multiple-scattering method of the front ends), measured on every scene like the
// chosen ones: whether the truth keeps them within their targets.
void Benchmark::MeasureShippedPresets(const std::vector<std::string>& names)
{
  const std::pair<int, double> qualities[] = { { vtkEffectPlan::DRAFT, 0.10 },
    { vtkEffectPlan::INTERACTIVE, 0.05 }, { vtkEffectPlan::PRODUCTION, 0.02 } };
  for (const auto& quality : qualities)
  {
    vtkNew<vtkEffectPlan> plan;
    plan->SetQuality(quality.first);
    Setting setting = this->Base;
    PipelineKnobs& knobs = setting.Knobs;
    knobs.Photons = plan->GetRecommendedNumberOfPhotons();
    knobs.PhotonMinimumStep = plan->GetRecommendedPhotonMinimumStep();
    knobs.PrimaryTolerance = plan->GetRecommendedOctreeTolerance();
    knobs.SecondaryTolerance = 4 * knobs.PrimaryTolerance;
    knobs.LatticeTolerance = plan->GetRecommendedLatticeTolerance();
    knobs.BlockSize = plan->GetRecommendedLatticeBlockSize();
    knobs.ViewStep = plan->GetRecommendedViewStep();
    knobs.ScatteringOrders = -2;
    setting.Size = plan->GetRecommendedResolution();
    if (setting.Size != this->Most.Size)
    {
      // The truth is of the scene voxelized at the sweep's finest resolution: another grid is
      // another medium.
      std::cout << "  shipped presets not measured: they recommend " << setting.Size
                << "^3, the truth is at " << this->Most.Size << "^3\n";
      return;
    }
    const std::string label = std::string("shipped ") +
      (quality.first == vtkEffectPlan::DRAFT
          ? "draft"
          : (quality.first == vtkEffectPlan::INTERACTIVE ? "interactive" : "production"));
    this->MeasurePreset(label, quality.second, setting, names);
  }
}

// Two log-log plots per scene: every run's error (against the converged reference, else against
// the finest setting) with one curve per knob, the reference renderer's own curve, the Pareto front
// and the presets; and each knob's own error.
void Benchmark::Plot(const std::string& name)
{
  const SceneResult& result = this->Results[name];
  auto positive = [](double e) { return std::max(e, 1e-5); };
  std::vector<refracta::bench::Series> series, knobs;
  for (const Knob& knob : this->Knobs)
  {
    refracta::bench::Series curve{ knob.Name, {}, {} };
    refracta::bench::Series own{ knob.Name, {}, {} };
    for (const Point& p : result.Points)
    {
      if (p.Knob == knob.Name)
      {
        curve.X.push_back(p.Seconds);
        curve.Y.push_back(positive(result.Error(p)));
        if (p.Value != MostAccurate(knob))
        {
          own.X.push_back(p.Seconds);
          own.Y.push_back(positive(p.KnobError));
        }
      }
    }
    series.push_back(curve);
    knobs.push_back(own);
  }
  refracta::bench::WritePlot(this->Config.Out + "/knobs_" + name + ".png",
    name + ": each knob's own error (vs its most accurate value)", "seconds", "relative RMSE",
    knobs);
  refracta::bench::Series reference{
    result.PhotonMapped ? "reference photon mapper" : "reference Monte Carlo", {}, {}
  };
  for (const Point& p : result.ReferencePoints)
  {
    reference.X.push_back(p.Seconds);
    reference.Y.push_back(positive(p.ReferenceError));
  }
  if (result.Converged)
  {
    series.push_back(reference);
  }
  refracta::bench::Series front{ "Pareto front", {}, {} };
  std::vector<Point> all = result.Points;
  all.insert(all.end(), result.Presets.begin(), result.Presets.end());
  for (const Point& p : ParetoFront(all, result))
  {
    front.X.push_back(p.Seconds);
    front.Y.push_back(positive(result.Error(p)));
  }
  series.push_back(front);
  refracta::bench::Series presets{ "presets", {}, {} };
  for (const Point& p : result.Presets)
  {
    presets.X.push_back(p.Seconds);
    presets.Y.push_back(positive(result.Error(p)));
  }
  series.push_back(presets);
  refracta::bench::WritePlot(this->Config.Out + "/accuracy_" + name + ".png",
    name + (result.Converged ? ": error vs converged reference" : ": error vs finest pipeline"),
    "seconds", "relative RMSE", series);
}

void Benchmark::Report(const std::vector<std::string>& names)
{
  Table front({ "scene", "knob", "value", "seconds", "error", "region error" });
  Table speedUp({ "scene", "truth", "reference noise (image / region)", "pipeline best error",
    "pipeline s to 5%", "reference s to 5%", "speed-up at 5%", "unbiased s to 5%",
    "speed-up vs unbiased at 5%", "pipeline s to 2%", "reference s to 2%", "speed-up at 2%",
    "unbiased s to 2%", "speed-up vs unbiased at 2%" });
  for (const std::string& name : names)
  {
    const SceneResult& result = this->Results[name];
    std::vector<Point> all = result.Points;
    all.insert(all.end(), result.Presets.begin(), result.Presets.end());
    const std::vector<Point> pareto = ParetoFront(all, result);
    std::vector<std::pair<double, double>> frontCurve, referenceCurve;
    for (const Point& p : pareto)
    {
      front.AddRow({ name, p.Knob, Table::Format(p.Value), Table::Format(p.Seconds),
        Table::Format(result.Error(p)),
        Table::Format(result.Converged ? p.ReferenceRegionError : p.SelfRegionError) });
      frontCurve.emplace_back(p.Seconds, result.Error(p));
    }
    for (const Point& p : result.ReferencePoints)
    {
      referenceCurve.emplace_back(p.Seconds, p.ReferenceError);
    }
    std::vector<std::string> row = { name, result.PhotonMapped ? "photon mapper" : "path tracer",
      Table::Format(result.ImageNoise) + " / " + Table::Format(result.RegionNoise),
      result.Converged ? Table::Format(pareto.back().ReferenceError) : "not measurable" };
    for (double target : { 0.05, 0.02 })
    {
      bool unused = false, extrapolated = false;
      const double tPipeline = TimeToError(frontCurve, target, false, &unused);
      if (!result.Converged)
      {
        // The reference's own noise after its budget, extrapolated with noise ~ time^(-1/2)
        // (time^(-1/3) for the photon mapper),
        // says how long unbiased Monte Carlo would need; the pipeline's error against it cannot
        // be measured.
        const double tReference = result.Reference.Seconds *
          std::pow(result.ImageNoise / target, result.PhotonMapped ? 3.0 : 2.0);
        row.push_back("-");
        row.push_back(Table::Format(tReference) + "*");
        row.push_back("not measurable");
        row.push_back("-");
        row.push_back("-");
        continue;
      }
      const double tReference = TimeToError(
        referenceCurve, target, true, &extrapolated, result.PhotonMapped ? 1.0 / 3.0 : 0.5);
      row.push_back(tPipeline < 0 ? "not reached" : Table::Format(tPipeline));
      row.push_back(Table::Format(tReference) + (extrapolated ? "*" : ""));
      row.push_back(tPipeline < 0 ? "-" : Table::Format(tReference / tPipeline));
      // The unbiased path tracer: the reference itself, or on photon-mapped scenes its noise after
      // a short run extrapolated with noise ~ time^(-1/2) (a lower bound: it has no bias).
      const double tUnbiased = result.PhotonMapped
        ? result.UnbiasedSeconds * std::pow(result.UnbiasedNoise / target, 2.0)
        : tReference;
      row.push_back(Table::Format(tUnbiased) + (result.PhotonMapped || extrapolated ? "*" : ""));
      row.push_back(tPipeline < 0 ? "-" : Table::Format(tUnbiased / tPipeline));
    }
    speedUp.AddRow(row);
    this->Plot(name);
  }
  this->Runs.Print("Accuracy and time: one knob at a time from the base setting");
  this->ReferenceRuns.Print("Reference estimators: error against time (seed 2 against the "
                            "converged seed-1 image of the same estimator)");
  this->Presets.Print("Quality presets chosen from the sweep, measured");
  front.Print("Pareto front per scene (error vs reference where it converged, else vs finest)");
  speedUp.Print("Speed-up of the pipeline over the reference at equal error (* extrapolated: "
                "error ~ time^-1/2 for the path tracer, time^-1/3 for the photon mapper)");
  this->Runs.WriteCsv(this->Config.Out + "/accuracy_time.csv");
  this->ReferenceRuns.WriteCsv(this->Config.Out + "/reference_curve.csv");
  this->Presets.WriteCsv(this->Config.Out + "/presets.csv");
  front.WriteCsv(this->Config.Out + "/pareto.csv");
  speedUp.WriteCsv(this->Config.Out + "/speed_up.csv");
}
} // namespace accuracy
} // namespace refracta
