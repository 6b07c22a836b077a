// Frames per second of the illumination network (vtkIlluminationNetwork, papers/002) for N
// particles and D directions, as the paper runs it: one network iteration per frame with a warm
// start while the light moves. Per (N, D) it prints the preprocessing time (reading the
// particles, the visibility network, the phase matrices, the first E), the median time of a frame
// (light move: new E on the host, one iteration on the device, read-back of the fluence and the
// power books), the iterations and time a warm start needs to reach tolerance 1e-3 after a small
// light move, and the cold start's.
//
// Usage: BenchmarkIlluminationNetwork [--sizes 1024,16384] [--directions 32,128] [--frames 5]
//        [--csv file]
#include "RefractaBenchmark.h"
#include "RefractaScenes.h"

#include "vtkIlluminationNetwork.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPolyData.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
using refracta::bench::Table;

double Seconds(const std::function<void()>& work)
{
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}

int main(int argc, char* argv[])
{
  std::vector<int> sizes = { 1024, 16384 };
  std::vector<int> directions = { 32, 128 };
  int frames = 5;
  std::string csv;
  for (int i = 1; i + 1 < argc; i += 2)
  {
    const std::string key = argv[i];
    if (key == "--sizes")
    {
      sizes = refracta::bench::ParseIntList(argv[i + 1]);
    }
    else if (key == "--directions")
    {
      directions = refracta::bench::ParseIntList(argv[i + 1]);
    }
    else if (key == "--frames")
    {
      frames = std::max(1, std::atoi(argv[i + 1]));
    }
    else if (key == "--csv")
    {
      csv = argv[i + 1];
    }
    else
    {
      std::fprintf(stderr, "usage: BenchmarkIlluminationNetwork [--sizes 1024,16384] "
                           "[--directions 32,128] [--frames 5] [--csv FILE]\n");
      return 2;
    }
  }
  if (argc % 2 == 0)
  {
    std::fprintf(stderr, "option %s needs a value\n", argv[argc - 1]);
    return 2;
  }
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::fprintf(stderr, "no OpenCL device\n");
    return 1;
  }
  std::printf("device: %s / %s\n", context->GetPlatformName(), context->GetDeviceName());
  Table table({ "N", "D", "preprocess s", "frame s (median)", "frames/s", "warm iterations",
    "warm s", "cold iterations", "cold s" });
  for (int n : sizes)
  {
    vtkSmartPointer<vtkPolyData> cloud = refracta::scenes::ParticleCloud(n);
    for (int d : directions)
    {
      vtkNew<vtkIlluminationNetwork> network;
      network->SetInputData(cloud);
      network->SetNumberOfDirections(d);
      network->SetLightType(vtkIlluminationNetwork::POINT_LIGHT);
      network->SetLightPosition(2.0, 0.0, 0.0);
      network->SetTolerance(0.0);
      network->SetMaximumIterations(1);
      network->SetCheckInterval(1024);
      const double preprocess = Seconds([&] { network->Update(); });
      // Frames: the light circles the cloud; one iteration each, from the previous state.
      std::vector<double> frameTimes;
      for (int f = 0; f < frames; ++f)
      {
        const double angle = 0.05 * (f + 1);
        network->SetLightPosition(2.0 * std::cos(angle), 2.0 * std::sin(angle), 0.0);
        frameTimes.push_back(Seconds([&] { network->Update(); }));
      }
      const double frame = refracta::bench::Median(frameTimes);
      // Convergence to 1e-3 after a small move: warm (from the converged previous light) vs cold.
      network->SetTolerance(1e-3);
      network->SetMaximumIterations(5000);
      network->SetCheckInterval(1);
      network->Update();
      network->SetLightPosition(2.0, 0.1, 0.0);
      const double warmSeconds = Seconds([&] { network->Update(); });
      const int warm = network->GetIterations();
      network->ResetState();
      const double coldSeconds = Seconds([&] { network->Update(); });
      const int cold = network->GetIterations();
      table.AddRow({ Table::Format(n), Table::Format(d), Table::Format(preprocess),
        Table::Format(frame), Table::Format(1.0 / frame), Table::Format(warm),
        Table::Format(warmSeconds), Table::Format(cold), Table::Format(coldSeconds) });
      std::fflush(stdout);
    }
  }
  table.Print("Illumination network: one iteration per frame (warm start), and time to 1e-3");
  if (!csv.empty())
  {
    table.WriteCsv(csv);
  }
  return 0;
}
