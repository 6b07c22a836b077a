// BenchmarkParticleRendering: how a particle medium lit by its illumination network becomes an
// image (issue 14: "splatting, or their deposit into the grid medium for the view rays: measure
// which is better"). vtkIlluminationNetwork (D = 128, converged) lights the paper's cloud
// (RefractaScenes.h, ParticleCloud) under a directional light; the network's single and multiple
// scattering then reach the image in two ways:
// - deposit (the shipping path): vtkParticleMediumDeposit on an n^3 grid, rendered by
//   vtkRefractaViewPass with the deposit's lighting volume, for several n;
// - splatting (implemented here, to measure it): per pixel, the spheres the pixel's ray crosses,
//   composited front to back by where the ray enters them, each with its exact chord l: its
//   transmittance exp(-sigma_t l) and its in-scattered radiance q (1 - exp(-sigma_t l)) / sigma_t,
//   with q the same per-volume sources the deposit spreads (single scattering through the HG
//   phase function of the light's direction, multiple scattering isotropic, emission).
// Both are compared with vtkReferenceRenderer's path-traced image of the cloud's exact deposit on
// a fine grid (the reference renders grids: the particles reach it as their sphere occupancy,
// sampled 4^3 per voxel), with the reference's noise taken out, over the pixels that see the
// cloud. Times are the rendering's alone (the deposit and its upload, or the splatting; medians
// of 3); the network is common to both. Then the network's own error: fewer directions D
// (--directions), rendered by splatting, with the network's time.
//
//   BenchmarkParticleRendering [--particles N] [--image W] [--grids 32,64,96]
//     [--directions 32,128,256] [--reference-grid G] [--reference-spp S] [--cache DIR]
//     [--csv FILE] [--smoke]
#include "RefractaBenchmark.h"
#include "RefractaReferenceImages.h"
#include "RefractaScenes.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkIlluminationNetwork.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkParticleMediumDeposit.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRefractaParticleMedium.h"
#include "vtkRefractaViewPass.h"
#include "vtkSMPTools.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace
{
using refracta::bench::Image;
using refracta::bench::Table;
using PM = vtkRefractaParticleMedium;

struct Settings
{
  int Particles = 1024;
  int ImageSize = 96;
  std::vector<int> Grids = { 32, 64, 96 };
  std::vector<int> Directions = { 32, 128, 256 };
  int ReferenceGrid = 128;
  int ReferenceSpp = 1024;
  std::string Cache;
  std::string Csv;
};

bool Parse(int argc, char* argv[], Settings& s)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string key = argv[i];
    if (key == "--smoke")
    {
      s.Particles = 128;
      s.ImageSize = 24;
      s.Grids = { 16 };
      s.Directions = { 16 };
      s.ReferenceGrid = 24;
      s.ReferenceSpp = 16;
      continue;
    }
    if (i + 1 >= argc)
    {
      std::cerr << key << " needs a value\n";
      return false;
    }
    const std::string value = argv[++i];
    if (key == "--particles")
      s.Particles = std::atoi(value.c_str());
    else if (key == "--image")
      s.ImageSize = std::atoi(value.c_str());
    else if (key == "--grids")
      s.Grids = refracta::bench::ParseIntList(value);
    else if (key == "--directions")
      s.Directions = refracta::bench::ParseIntList(value);
    else if (key == "--reference-grid")
      s.ReferenceGrid = std::atoi(value.c_str());
    else if (key == "--reference-spp")
      s.ReferenceSpp = std::atoi(value.c_str());
    else if (key == "--cache")
      s.Cache = value;
    else if (key == "--csv")
      s.Csv = value;
    else
    {
      std::cerr << "unknown option " << key
                << "; valid: --particles --image --grids --directions --reference-grid "
                   "--reference-spp --cache --csv --smoke\n";
      return false;
    }
  }
  const bool gridsValid = !s.Grids.empty() &&
    std::all_of(s.Grids.begin(), s.Grids.end(), [](int g) { return g >= 2; }) &&
    !s.Directions.empty() &&
    std::all_of(s.Directions.begin(), s.Directions.end(), [](int d) { return d >= 1; });
  if (s.Particles < 1 || s.ImageSize < 4 || !gridsValid || s.ReferenceGrid < 2 ||
    s.ReferenceSpp < 1)
  {
    std::cerr << "--particles, --reference-spp and every direction count must be >= 1, --image "
                 ">= 4, every grid and --reference-grid >= 2\n";
    return false;
  }
  return true;
}

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The particles' per-volume sources and extinction, as vtkParticleMediumDeposit spreads them.
struct Particle
{
  std::array<double, 3> Centre;
  double Radius;
  std::array<double, 3> SigmaT, Single, Multiple, Emission, Travel;
  double G;
};

std::vector<Particle> SplatParticles(vtkPolyData* lit)
{
  vtkPointData* pd = lit->GetPointData();
  vtkDataArray* radius = pd->GetArray(PM::RadiusName());
  vtkDataArray* extinction = pd->GetArray(PM::ExtinctionName());
  vtkDataArray* albedo = pd->GetArray(PM::AlbedoName());
  vtkDataArray* g = pd->GetArray(PM::AnisotropyName());
  vtkDataArray* emission = pd->GetArray(PM::EmissionName());
  vtkDataArray* direct = pd->GetArray(PM::DirectFluenceName());
  vtkDataArray* travel = pd->GetArray(PM::DirectDirectionName());
  vtkDataArray* multiple = pd->GetArray(PM::MultipleFluenceName());
  std::vector<Particle> particles(static_cast<size_t>(lit->GetNumberOfPoints()));
  for (vtkIdType p = 0; p < lit->GetNumberOfPoints(); ++p)
  {
    Particle& q = particles[p];
    lit->GetPoint(p, q.Centre.data());
    q.Radius = radius->GetComponent(p, 0);
    q.G = g ? g->GetComponent(p, 0) : 0.0;
    for (int c = 0; c < 3; ++c)
    {
      q.SigmaT[c] = extinction->GetComponent(p, c);
      const double perVolume =
        PM::ScatteringPerVolume(q.SigmaT[c], albedo ? albedo->GetComponent(p, c) : 0.0, q.Radius);
      q.Single[c] = perVolume * direct->GetComponent(p, c);
      q.Multiple[c] = perVolume * multiple->GetComponent(p, c);
      q.Emission[c] = emission ? emission->GetComponent(p, c) : 0.0;
      q.Travel[c] = travel->GetComponent(p, c);
    }
  }
  return particles;
}

// Splats the particles for `camera` into size x size RGB values (row 0 at the bottom), one ray
// through each pixel's centre: the crossed spheres composited front to back by entry distance.
std::vector<double> Splat(const std::vector<Particle>& particles, vtkCamera* camera, int size)
{
  double eye[3], focal[3], up[3];
  camera->GetPosition(eye);
  camera->GetFocalPoint(focal);
  camera->GetViewUp(up);
  double forward[3] = { focal[0] - eye[0], focal[1] - eye[1], focal[2] - eye[2] };
  vtkMath::Normalize(forward);
  double right[3], trueUp[3];
  vtkMath::Cross(forward, up, right);
  vtkMath::Normalize(right);
  vtkMath::Cross(right, forward, trueUp);
  const double halfHeight = std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2);
  std::vector<double> rgb(3 * static_cast<size_t>(size) * size, 0.0);
  vtkSMPTools::For(0, size,
    [&](int row0, int row1)
    {
      std::vector<std::pair<double, size_t>> hits;
      for (int j = row0; j < row1; ++j)
      {
        for (int i = 0; i < size; ++i)
        {
          const double sx = (2 * (i + 0.5) / size - 1) * halfHeight;
          const double sy = (2 * (j + 0.5) / size - 1) * halfHeight;
          double d[3];
          for (int a = 0; a < 3; ++a)
          {
            d[a] = forward[a] + sx * right[a] + sy * trueUp[a];
          }
          vtkMath::Normalize(d);
          hits.clear();
          for (size_t p = 0; p < particles.size(); ++p)
          {
            const Particle& q = particles[p];
            const double oc[3] = { q.Centre[0] - eye[0], q.Centre[1] - eye[1],
              q.Centre[2] - eye[2] };
            const double b = vtkMath::Dot(oc, d);
            const double miss2 = vtkMath::Dot(oc, oc) - b * b;
            if (miss2 < q.Radius * q.Radius && b > 0)
            {
              hits.emplace_back(b - std::sqrt(q.Radius * q.Radius - miss2), p);
            }
          }
          std::sort(hits.begin(), hits.end());
          double radiance[3] = { 0, 0, 0 }, transmittance[3] = { 1, 1, 1 };
          for (const auto& hit : hits)
          {
            const Particle& q = particles[hit.second];
            const double oc[3] = { q.Centre[0] - eye[0], q.Centre[1] - eye[1],
              q.Centre[2] - eye[2] };
            const double b = vtkMath::Dot(oc, d);
            const double chord =
              2 * std::sqrt(std::max(0.0, q.Radius * q.Radius - (vtkMath::Dot(oc, oc) - b * b)));
            // HG phase between the light's travel direction and the way back to the camera.
            const double cosine = -(q.Travel[0] * d[0] + q.Travel[1] * d[1] + q.Travel[2] * d[2]);
            const double g2 = q.G * q.G;
            const double phase = (1 - g2) /
              (4 * vtkMath::Pi() * std::pow(std::max(1e-12, 1 + g2 - 2 * q.G * cosine), 1.5));
            for (int c = 0; c < 3; ++c)
            {
              const double source =
                q.Emission[c] + phase * q.Single[c] + q.Multiple[c] / (4 * vtkMath::Pi());
              const double tau = q.SigmaT[c] * chord;
              const double weight = tau > 1e-9 ? -std::expm1(-tau) / q.SigmaT[c] : chord;
              radiance[c] += transmittance[c] * source * weight;
              transmittance[c] *= std::exp(-tau);
            }
          }
          const size_t pixel = static_cast<size_t>(j) * size + i;
          for (int c = 0; c < 3; ++c)
          {
            rgb[3 * pixel + c] = radiance[c];
          }
        }
      }
    });
  return rgb;
}

// The deposit on an n^3 grid rendered by the view pass: RGB values, row 0 at the bottom.
std::vector<double> DepositAndView(vtkPolyData* lit, vtkCamera* camera, int size, int n)
{
  vtkNew<vtkParticleMediumDeposit> deposit;
  deposit->SetInputData(lit);
  deposit->SetSampleDimensions(n, n, n);
  deposit->Update();
  vtkNew<vtkRefractaViewPass> view;
  std::vector<float> hdr;
  std::vector<double> rgb;
  if (!view->SetMedium(deposit->GetMediumOutput()) ||
    !view->SetLighting(deposit->GetLightingOutput()) ||
    !view->Render(camera, size, size, nullptr, nullptr, hdr))
  {
    return rgb;
  }
  for (size_t p = 0; p < hdr.size() / 4; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      rgb.push_back(hdr[4 * p + c]);
    }
  }
  return rgb;
}

// The reference image: the cloud's deposit on a fine grid, path traced (read from the cache
// directory when an earlier run left it there).
Image Reference(vtkPolyData* lit, const refracta::scenes::Scene& view, const Settings& s)
{
  std::ostringstream name;
  name << s.Cache << "/particles_" << s.Particles << "_" << s.ReferenceGrid << "_" << s.ImageSize
       << "_" << s.ReferenceSpp << ".vti";
  struct stat info;
  if (!s.Cache.empty() && stat(name.str().c_str(), &info) == 0)
  {
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(name.str().c_str());
    reader->Update();
    Image image = refracta::bench::ReadImage(reader->GetOutput());
    if (image.Value.size() == 3u * s.ImageSize * s.ImageSize)
    {
      std::cout << "reference read from " << name.str() << "\n";
      return image;
    }
  }
  vtkNew<vtkParticleMediumDeposit> deposit;
  deposit->SetInputData(lit);
  deposit->SetSampleDimensions(s.ReferenceGrid, s.ReferenceGrid, s.ReferenceGrid);
  deposit->SetSamplesPerAxis(4);
  deposit->Update();
  refracta::scenes::Scene scene = view;
  scene.Medium = deposit->GetMediumOutput();
  vtkNew<vtkImageData> output;
  const Image image =
    refracta::bench::RenderReference(scene, s.ImageSize, s.ReferenceSpp, 1, output);
  std::cout << "reference: " << s.ReferenceSpp << " samples per pixel on the " << s.ReferenceGrid
            << "^3 deposit in " << image.Seconds << " s\n";
  if (!s.Cache.empty())
  {
    vtkNew<vtkXMLImageDataWriter> writer;
    writer->SetInputData(output);
    writer->SetFileName(name.str().c_str());
    writer->Write();
  }
  return image;
}

double Brightness(
  const std::vector<double>& image, const Image& reference, const std::vector<bool>& seen)
{
  double a = 0, r = 0;
  for (size_t v = 0; v < reference.Value.size(); ++v)
  {
    if (seen[v / 3])
    {
      a += image[v];
      r += reference.Value[v];
    }
  }
  return r > 0 ? a / r : 0.0;
}
}

int main(int argc, char* argv[])
{
  Settings s;
  if (!Parse(argc, argv, s))
  {
    return 1;
  }
  // The cloud, lit by a directional light from above and the side.
  vtkSmartPointer<vtkPolyData> cloud = refracta::scenes::ParticleCloud(s.Particles);
  const double* travel = refracta::scenes::ParticleLightTravel;
  auto light = [&](int directions, double& seconds)
  {
    vtkNew<vtkIlluminationNetwork> network;
    network->SetInputData(cloud);
    network->SetLightType(vtkIlluminationNetwork::DIRECTIONAL_LIGHT);
    network->SetLightDirection(travel[0], travel[1], travel[2]);
    network->SetLightIntensity(1, 1, 1);
    network->SetNumberOfDirections(directions);
    network->SetNumberOfRotations(4);
    network->SetTolerance(1e-4);
    const auto start = std::chrono::steady_clock::now();
    network->Update();
    seconds = Seconds(start);
    std::cout << "network, D = " << directions << ": " << network->GetIterations()
              << " iterations, " << seconds << " s\n";
    auto lit = vtkSmartPointer<vtkPolyData>::New();
    lit->ShallowCopy(network->GetOutput());
    return lit;
  };
  // The rendering comparison uses the largest D.
  const int finest = *std::max_element(s.Directions.begin(), s.Directions.end());
  double networkSeconds = 0;
  vtkSmartPointer<vtkPolyData> lit = light(finest, networkSeconds);
  if (!lit->GetPointData()->GetArray(PM::MultipleFluenceName()))
  {
    std::cerr << "the illumination network failed\n";
    return 1;
  }

  const refracta::scenes::Scene view = refracta::scenes::ParticleCloudView();
  const Image reference = Reference(lit, view, s);
  std::vector<bool> seen(reference.Value.size() / 3, false);
  for (size_t v = 0; v < reference.Value.size(); ++v)
  {
    seen[v / 3] = seen[v / 3] || reference.Error[v] > 1e-6 * reference.Value[v];
  }
  std::cout << "reference noise: " << refracta::bench::NoiseLevel(reference, seen) << "\n";

  Table table({ "method", "directions D", "grid", "seconds", "error vs reference", "brightness",
    "difference from splatting" });
  auto measure = [&](const std::function<std::vector<double>()>& render)
  {
    Image image;
    render(); // warm: kernel compilation, allocations
    image.Seconds = refracta::bench::MedianSeconds(3, [&] { image.Value = render(); });
    image.Error.assign(image.Value.size(), 0.0);
    return image;
  };
  const std::vector<Particle> particles = SplatParticles(lit);
  const Image splat = measure([&] { return Splat(particles, view.Camera, s.ImageSize); });
  auto addRow =
    [&](const std::string& method, int directions, const std::string& grid, const Image& image)
  {
    if (image.Value.size() != reference.Value.size())
    {
      std::cerr << method << " " << grid << " failed\n";
      return false;
    }
    Image splatAsReference = splat;
    splatAsReference.Error.assign(splat.Value.size(), 0.0);
    table.AddRow({ method, std::to_string(directions), grid, Table::Format(image.Seconds),
      Table::Format(refracta::bench::RelativeError(image, reference, seen)),
      Table::Format(Brightness(image.Value, reference, seen)),
      Table::Format(refracta::bench::RelativeError(image, splatAsReference, seen)) });
    return true;
  };
  bool ok = addRow("splatting", finest, "-", splat);
  for (int n : s.Grids)
  {
    const Image deposit = measure([&] { return DepositAndView(lit, view.Camera, s.ImageSize, n); });
    ok = addRow("deposit + view pass", finest, std::to_string(n), deposit) && ok;
  }
  // The network's own error: fewer directions, the same (splatted) rendering; seconds are the
  // network's.
  for (int d : s.Directions)
  {
    if (d == finest)
    {
      continue;
    }
    double seconds = 0;
    vtkSmartPointer<vtkPolyData> coarse = light(d, seconds);
    Image image;
    image.Value = Splat(SplatParticles(coarse), view.Camera, s.ImageSize);
    image.Error.assign(image.Value.size(), 0.0);
    image.Seconds = seconds;
    ok = addRow("network (splatted)", d, "-", image) && ok;
  }
  table.Print("Particle rendering: " + std::to_string(s.Particles) + " particles, " +
    std::to_string(s.ImageSize) + "^2 pixels, against the path-traced " +
    std::to_string(s.ReferenceGrid) + "^3 deposit");
  if (!s.Csv.empty() && !table.WriteCsv(s.Csv))
  {
    std::cerr << "cannot write " << s.Csv << "\n";
    return 1;
  }
  return ok ? 0 : 1;
}
