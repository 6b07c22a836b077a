// BenchmarkSingleScattering: Ren et al. (2008) Table 2 on our scenes. Per-voxel light rays against
// the gradient-based interpolation with dynamic sampling (vtkLightRaySingleScattering), at 1, 8,
// 32 and 64 lights on HeterogeneousCloud grids, with the interpolation's RMS error against the
// light rays, and the photon pass (vtkPhotonTracer) at the same error: median times and speed-ups
// from one run.
//
// Usage: BenchmarkSingleScattering [--sizes 64,128] [--lights 1,8,32,64] [--repeats 3]
//          [--max-photons 4194304] [--photon-lights 1] [--csv file] [--box-means 1] [--lobes 1]
// --box-means 1 instead times the light rays with and without their box means at sharp voxels
// (vtkLightRaySingleScattering::SharpVoxelBoxMeans) on dense media of 1 optical depth per voxel
// (the lower half of the grid, a ball of radius 0.35) under a sun: what the box means cost.
// --lobes 1 instead times what S1's lobes cost (MaximumRadianceLobes 1, 2 and 4) on the cloud
// (g = 0.6) under --lights lights (those >= 2): the light rays, the interpolation, the photon pass
// (2^18 photons; its march alone in brackets) and the view pass (vtkRefractaImageRenderer,
// 512 x 512, of the light rays' output, a camera move per frame).
// The photon search doubles the photon count from 2^14 until its RMS distance to the light rays
// is at most the interpolation's (or --max-photons); it runs for the light counts in
// --photon-lights only (its cost does not grow with the lights, only its error target moves).
#include "RefractaBenchmark.h"
#include "RefractaScenes.h"

#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkPointData.h"
#include "vtkRefractaImageRenderer.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
// The scene's sun plus count - 1 point lights on a sphere around the unit cube (golden spiral),
// the total power split evenly so every row lights the cloud alike.
std::vector<vtkSmartPointer<vtkLight>> Lights(const refracta::scenes::Scene& scene, int count)
{
  std::vector<vtkSmartPointer<vtkLight>> lights;
  auto sun = vtkSmartPointer<vtkLight>::New();
  sun->DeepCopy(scene.Lights[0]);
  sun->SetIntensity(sun->GetIntensity() / count);
  lights.push_back(sun);
  for (int l = 1; l < count; ++l)
  {
    const double z = 1.0 - 2.0 * (l + 0.5) / count;
    const double r = std::sqrt(1.0 - z * z), phi = 2.39996323 * l;
    auto light = vtkSmartPointer<vtkLight>::New();
    light->SetPositional(true);
    light->SetConeAngle(180.0);
    light->SetPosition(0.5 + 1.2 * r * std::cos(phi), 0.5 + 1.2 * r * std::sin(phi), 0.5 + 1.2 * z);
    light->SetFocalPoint(0.5, 0.5, 0.5);
    light->SetIntensity(1.0 / count);
    lights.push_back(light);
  }
  return lights;
}

double RelativeRms(vtkImageData* a, vtkImageData* reference)
{
  const char* name = vtkRefractaLightingVolume::RadianceName();
  vtkFloatArray* x = vtkFloatArray::SafeDownCast(a->GetPointData()->GetArray(name));
  vtkFloatArray* y = vtkFloatArray::SafeDownCast(reference->GetPointData()->GetArray(name));
  if (!x || !y || x->GetNumberOfValues() != y->GetNumberOfValues())
  {
    return -1.0;
  }
  double diff = 0, ref = 0;
  for (vtkIdType i = 0; i < x->GetNumberOfValues(); ++i)
  {
    diff += std::pow(double(x->GetValue(i)) - y->GetValue(i), 2);
    ref += std::pow(double(y->GetValue(i)), 2);
  }
  return std::sqrt(diff / std::max(ref, 1e-300));
}
}

// n^3 voxels over the unit cube: sigma_t = n (an optical depth of 1 per voxel) in the lower half
// (slab) or in a ball of radius 0.35, 0 elsewhere; albedo 0.8.
vtkSmartPointer<vtkImageData> DenseMedium(int n, bool ball)
{
  auto medium = vtkSmartPointer<vtkImageData>::New();
  const double h = 1.0 / n;
  medium->SetDimensions(n, n, n);
  medium->SetSpacing(h, h, h);
  medium->SetOrigin(0.5 * h, 0.5 * h, 0.5 * h);
  vtkNew<vtkFloatArray> extinction, albedo;
  extinction->SetName(vtkRefractaMedium::ExtinctionName());
  albedo->SetName(vtkRefractaMedium::AlbedoName());
  extinction->SetNumberOfComponents(3);
  albedo->SetNumberOfComponents(3);
  extinction->SetNumberOfTuples(medium->GetNumberOfPoints());
  albedo->SetNumberOfTuples(medium->GetNumberOfPoints());
  for (vtkIdType id = 0; id < medium->GetNumberOfPoints(); ++id)
  {
    double p[3];
    medium->GetPoint(id, p);
    const double r2 =
      (p[0] - 0.5) * (p[0] - 0.5) + (p[1] - 0.5) * (p[1] - 0.5) + (p[2] - 0.5) * (p[2] - 0.5);
    const double sigma = (ball ? r2 < 0.35 * 0.35 : p[1] < 0.5) ? n : 0.0;
    for (int c = 0; c < 3; ++c)
    {
      extinction->SetComponent(id, c, sigma);
      albedo->SetComponent(id, c, 0.8);
    }
  }
  medium->GetPointData()->AddArray(extinction);
  medium->GetPointData()->AddArray(albedo);
  return medium;
}

// The light rays with and without box means at sharp voxels, medians of `repeats`.
void TimeBoxMeans(const std::vector<int>& sizes, int repeats)
{
  vtkNew<vtkLight> sun;
  sun->SetLightTypeToSceneLight();
  sun->PositionalOff();
  sun->SetPosition(1.5, 3.0, 1.0);
  sun->SetFocalPoint(0.5, 0.5, 0.5);
  std::printf("%5s %6s %12s %12s %8s %12s %14s\n", "grid", "medium", "centres [s]", "box means [s]",
    "ratio", "sharp voxels", "us per sharp");
  for (int n : sizes)
  {
    for (bool ball : { false, true })
    {
      auto medium = DenseMedium(n, ball);
      double seconds[2];
      long long sharp = 0;
      for (int boxMeans = 0; boxMeans < 2; ++boxMeans)
      {
        vtkNew<vtkLightRaySingleScattering> rays;
        rays->AddLight(sun);
        rays->SetSharpVoxelBoxMeans(boxMeans == 1);
        rays->SetInputData(medium);
        seconds[boxMeans] = refracta::bench::MedianSeconds(repeats,
          [&]
          {
            rays->Modified();
            rays->Update();
          });
        sharp = rays->GetNumberOfBoxMeanVoxels();
      }
      std::printf("%5d %6s %12.3f %12.3f %8.2f %12lld %14.1f\n", n, ball ? "ball" : "slab",
        seconds[0], seconds[1], seconds[1] / seconds[0], sharp,
        sharp ? 1e6 * (seconds[1] - seconds[0]) / sharp : 0.0);
      std::fflush(stdout);
    }
  }
}

// Seconds of one call of `work`.
double Timed(const std::function<void()>& work)
{
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double Median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// S1 in 1, 2 and 4 lobes: the light rays, the interpolation, the photons and the view pass, the
// three settings alternated within each repeat (so that a drift of the shared machine falls on
// all alike), medians of `repeats`, with the ratios to one lobe.
void TimeLobes(const std::vector<int>& sizes, const std::vector<int>& lightCounts, int repeats)
{
  std::printf("%5s %6s %6s %10s %12s %20s %10s   %s\n", "grid", "lights", "lobes", "rays [s]",
    "interp [s]", "photons (march) [s]", "view [s]", "vs 1 lobe: rays interp photons view");
  const int settings[3] = { 1, 2, 4 };
  for (int n : sizes)
  {
    refracta::scenes::Scene scene = refracta::scenes::HeterogeneousCloud(n);
    for (int count : lightCounts)
    {
      if (count < 2)
      {
        continue;
      }
      struct Setting
      {
        vtkNew<vtkLightRaySingleScattering> Rays, Interpolated;
        vtkNew<vtkPhotonTracer> Tracer;
        vtkNew<vtkRefractaImageRenderer> View;
        std::vector<double> Seconds[4], Marching;
      } runs[3];
      for (int s = 0; s < 3; ++s)
      {
        Setting& r = runs[s];
        r.Interpolated->SetMethodToInterpolated();
        for (auto& light : Lights(scene, count))
        {
          r.Rays->AddLight(light);
          r.Interpolated->AddLight(light);
          r.Tracer->AddLight(light);
        }
        r.Tracer->SetNumberOfPhotons(1 << 18);
        r.Tracer->SetMaximumRadianceLobes(settings[s]);
        for (vtkLightRaySingleScattering* pass : { r.Rays.Get(), r.Interpolated.Get() })
        {
          pass->SetMaximumRadianceLobes(settings[s]);
          pass->SetInputData(scene.Medium);
          pass->Update(); // untimed: the kernels' compilation
        }
        r.Tracer->SetInputData(scene.Medium);
        r.Tracer->Update(); // untimed
        r.View->SetInputData(scene.Medium);
        r.View->SetLightingData(r.Rays->GetOutput());
        r.View->SetCamera(scene.Camera);
        r.View->SetImageSize(512, 512);
        r.View->Update(); // untimed
      }
      for (int repeat = 0; repeat < repeats; ++repeat)
      {
        for (Setting& r : runs)
        {
          vtkAlgorithm* const passes[3] = { r.Rays, r.Interpolated, r.Tracer };
          for (vtkAlgorithm* pass : passes)
          {
            const int column = pass == r.Rays.Get() ? 0 : pass == r.Interpolated.Get() ? 1 : 3;
            r.Seconds[column].push_back(Timed(
              [&]
              {
                pass->Modified();
                pass->Update();
              }));
          }
          r.Marching.push_back(r.Tracer->GetMarchingSeconds());
          // A camera move: the view pass runs again (an unchanged render is reused).
          scene.Camera->Azimuth(repeat % 2 ? 1.0 : -1.0);
          r.Seconds[2].push_back(Timed([&] { r.View->Update(); }));
        }
      }
      double first[4];
      for (int s = 0; s < 3; ++s)
      {
        Setting& r = runs[s];
        double seconds[4];
        for (int c = 0; c < 4; ++c)
        {
          seconds[c] = Median(r.Seconds[c]);
          first[c] = s == 0 ? seconds[c] : first[c];
        }
        std::printf("%5d %6d %6d %10.3f %12.3f %11.3f (%6.3f) %10.3f   %.2f %.2f %.2f %.2f\n", n,
          count, r.Rays->GetLastNumberOfLobes(), seconds[0], seconds[1], seconds[3],
          Median(r.Marching), seconds[2], seconds[0] / first[0], seconds[1] / first[1],
          seconds[3] / first[3], seconds[2] / first[2]);
        std::fflush(stdout);
      }
    }
  }
}

int main(int argc, char* argv[])
{
  bool boxMeans = false, lobes = false;
  std::vector<int> sizes = { 64, 128 };
  std::vector<int> lightCounts = { 1, 8, 32, 64 };
  std::vector<int> photonLights = { 1 };
  int repeats = 3;
  int maxPhotons = 1 << 22;
  std::string csv;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--sizes")
      sizes = refracta::bench::ParseIntList(value);
    else if (key == "--lights")
      lightCounts = refracta::bench::ParseIntList(value);
    else if (key == "--photon-lights")
      photonLights = refracta::bench::ParseIntList(value);
    else if (key == "--repeats")
      repeats = std::max(1, std::atoi(value.c_str()));
    else if (key == "--max-photons")
      maxPhotons = std::atoi(value.c_str());
    else if (key == "--csv")
      csv = value;
    else if (key == "--box-means")
      boxMeans = std::atoi(value.c_str()) != 0;
    else if (key == "--lobes")
      lobes = std::atoi(value.c_str()) != 0;
    else
    {
      std::cerr << "Unknown option " << key << "\n";
      return 1;
    }
  }
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::cerr << "No OpenCL device: " << context->GetLastErrorMessage() << "\n";
    return 1;
  }
  std::cout << "Device: " << context->GetDeviceName() << " (" << context->GetPlatformName()
            << "), median of " << repeats << " runs\n";
  if (boxMeans)
  {
    TimeBoxMeans(sizes, repeats);
    return 0;
  }
  if (lobes)
  {
    TimeLobes(sizes, lightCounts, repeats);
    return 0;
  }
  std::ostringstream table;
  table << "size,lights,light_rays_s,interpolated_s,speedup,samples,rms,photons,photon_rms,"
           "photon_s,photon_speedup_vs_interpolated\n";
  std::printf("%5s %6s %12s %12s %8s %8s %8s %9s %9s %10s %8s\n", "grid", "lights", "rays [s]",
    "interp [s]", "speedup", "samples", "RMS", "photons", "ph RMS", "photon [s]", "interp/ph");
  for (int n : sizes)
  {
    refracta::scenes::Scene scene = refracta::scenes::HeterogeneousCloud(n);
    for (int count : lightCounts)
    {
      vtkNew<vtkLightRaySingleScattering> rays, interpolated;
      interpolated->SetMethodToInterpolated();
      auto lights = Lights(scene, count);
      for (auto& light : lights)
      {
        rays->AddLight(light);
        interpolated->AddLight(light);
      }
      rays->SetInputData(scene.Medium);
      interpolated->SetInputData(scene.Medium);
      const double raySeconds = refracta::bench::MedianSeconds(repeats,
        [&]
        {
          rays->Modified();
          rays->Update();
        });
      const double interpSeconds = refracta::bench::MedianSeconds(repeats,
        [&]
        {
          interpolated->Modified();
          interpolated->Update();
        });
      const double rms = RelativeRms(interpolated->GetOutput(), rays->GetOutput());
      int photons = 0;
      double photonRms = -1, photonSeconds = 0;
      if (std::find(photonLights.begin(), photonLights.end(), count) != photonLights.end())
      {
        vtkNew<vtkPhotonTracer> tracer;
        for (auto& light : lights)
        {
          tracer->AddLight(light);
        }
        tracer->SetInputData(scene.Medium);
        // Unsmoothed: the 3x3x3 filter is a bias of its own (9% RMS on this cloud) that no
        // photon count removes.
        tracer->SmoothingOff();
        for (photons = 1 << 14; photons <= maxPhotons; photons *= 2)
        {
          tracer->SetNumberOfPhotons(photons);
          photonSeconds = refracta::bench::MedianSeconds(1, [&] { tracer->Update(); });
          photonRms = RelativeRms(tracer->GetOutput(), rays->GetOutput());
          if (photonRms <= rms)
          {
            break;
          }
        }
        photons = std::min(photons, maxPhotons);
      }
      const double speedup = raySeconds / interpSeconds;
      std::printf("%5d %6d %12.3f %12.3f %8.2f %8d %8.4f %9d %9.4f %10.3f %8.2f\n", n, count,
        raySeconds, interpSeconds, speedup, interpolated->GetNumberOfSamples(), rms, photons,
        photonRms, photonSeconds, photons ? photonSeconds / interpSeconds : 0.0);
      std::fflush(stdout);
      table << n << "," << count << "," << raySeconds << "," << interpSeconds << "," << speedup
            << "," << interpolated->GetNumberOfSamples() << "," << rms << "," << photons << ","
            << photonRms << "," << photonSeconds << ","
            << (photons ? photonSeconds / interpSeconds : 0.0) << "\n";
    }
  }
  if (!csv.empty())
  {
    std::ofstream(csv) << table.str();
  }
  return 0;
}
