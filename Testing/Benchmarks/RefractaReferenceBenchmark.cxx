// Reference renderer benchmark: the price of accuracy of the ground truth itself.
//
// Scene: a semi-infinite isotropic medium (albedo 0.9, a slab of optical depth 100) under a normal
// directional beam, seen at normal incidence by a parallel camera; the exact radiance is
// Chandrasekhar's w E H(1)^2 / (8 pi). For samples per pixel N = 4 .. 256 it prints the median
// render time of several runs (seeds 1..runs), the error of the image mean against the exact value,
// the reported standard error of that mean, and the efficiency 1 / (SE^2 x time). A second table
// measures the cost of curved rays: the same scene with n = 1 (straight-line fast path) and with
// n = 1 + 1e-3 y (RK5(4) integration everywhere), ratios measured in the same run.
//
// Usage: RefractaReferenceBenchmark [--smoke] [--runs R] [--csv file]
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkReferenceRenderer.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace
{
const double Pi = 3.14159265358979323846;

double HFunction(double w, double mu)
{
  // H(mu) = 1 / (1 - (w/2) mu int_0^1 H(mu') / (mu + mu') dmu'), midpoint rule on 400 nodes
  // (w < 1: smooth enough for 1e-5).
  const int n = 400;
  std::vector<double> x(n), h(n, 1.0);
  for (int i = 0; i < n; ++i)
  {
    x[i] = (i + 0.5) / n;
  }
  auto inv = [&](double m)
  {
    double s = 0;
    for (int j = 0; j < n; ++j)
    {
      s += h[j] / (m + x[j]) / n;
    }
    return 1 - 0.5 * w * m * s;
  };
  for (int it = 0; it < 500; ++it)
  {
    std::vector<double> hn(n);
    for (int i = 0; i < n; ++i)
    {
      hn[i] = 1 / inv(x[i]);
    }
    h = hn;
  }
  return 1 / inv(mu);
}

vtkSmartPointer<vtkImageData> Medium(double albedo, double gradient)
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(3, 3, 3);
  img->SetSpacing(300, 300, 50);
  img->SetOrigin(-300, -300, 0);
  const char* names[3] = { "Extinction", "Albedo", "RefractiveIndex" };
  for (int a = 0; a < 3; ++a)
  {
    vtkNew<vtkDoubleArray> arr;
    arr->SetName(names[a]);
    arr->SetNumberOfComponents(a < 2 ? 3 : 1);
    arr->SetNumberOfTuples(27);
    for (int i = 0; i < 27; ++i)
    {
      const int j = (i / 3) % 3;
      for (int c = 0; c < arr->GetNumberOfComponents(); ++c)
      {
        arr->SetComponent(i, c, a == 0 ? 1.0 : (a == 1 ? albedo : 1.0 + gradient * 300 * j));
      }
    }
    img->GetPointData()->AddArray(arr);
  }
  return img;
}

struct Result
{
  double Seconds, Mean, Error;
};

Result Render(vtkImageData* medium, int size, int spp, unsigned int seed)
{
  vtkNew<vtkCamera> cam;
  cam->ParallelProjectionOn();
  cam->SetFocalPoint(0, 0, 125);
  cam->SetPosition(0, 0, 300);
  cam->SetViewUp(0, 1, 0);
  cam->SetParallelScale(1);
  vtkNew<vtkLight> light;
  light->PositionalOff();
  light->SetPosition(0, 0, 1);
  light->SetFocalPoint(0, 0, 0);
  vtkNew<vtkReferenceRenderer> r;
  r->SetInputData(medium);
  r->SetCamera(cam);
  r->AddLight(light);
  r->SetImageSize(size, size);
  r->SetSamplesPerPixel(spp);
  r->SetSeed(seed);
  const auto t0 = std::chrono::steady_clock::now();
  r->Update();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  vtkDataArray* hdr = r->GetOutput()->GetPointData()->GetArray("HDR");
  vtkDataArray* se = r->GetOutput()->GetPointData()->GetArray("StandardError");
  const vtkIdType n = hdr->GetNumberOfTuples();
  double s = 0, v = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    s += hdr->GetComponent(i, 0);
    v += se->GetComponent(i, 0) * se->GetComponent(i, 0);
  }
  return { secs, s / n, std::sqrt(v) / n };
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}
} // namespace

int main(int argc, char* argv[])
{
  bool smoke = false;
  int runs = 5;
  std::string csv = "reference_benchmark.csv";
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--smoke"))
    {
      smoke = true;
      runs = 1;
    }
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc)
    {
      runs = std::max(1, std::atoi(argv[++i]));
    }
    else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc)
    {
      csv = argv[++i];
    }
    else
    {
      std::fprintf(stderr, "usage: %s [--smoke] [--runs R] [--csv file]\n", argv[0]);
      return 2;
    }
  }
  const double w = 0.9;
  const double exact = w * HFunction(w, 1.0) * HFunction(w, 1.0) / (8 * Pi);
  const int size = smoke ? 4 : 16;
  std::ofstream out(csv);
  out << "table,samples_per_pixel,paths,median_seconds,abs_error,standard_error,efficiency\n";
  std::printf(
    "Reference renderer, semi-infinite albedo %.2f, %dx%d pixels, %d threads, exact %.6f\n", w,
    size, size, vtkSMPTools::GetEstimatedNumberOfThreads(), exact);
  std::printf("%6s %9s %10s %11s %11s %12s\n", "spp", "paths", "median s", "|error|", "std.err",
    "1/(SE^2 t)");
  auto medium = Medium(w, 0.0);
  const std::vector<int> spps = smoke ? std::vector<int>{ 2 } : std::vector<int>{ 4, 16, 64, 256 };
  for (int spp : spps)
  {
    std::vector<double> t, e, se;
    for (int r = 0; r < runs; ++r)
    {
      const Result res = Render(medium, size, spp, r + 1);
      t.push_back(res.Seconds);
      e.push_back(std::abs(res.Mean - exact));
      se.push_back(res.Error);
    }
    const double mt = Median(t), me = Median(e), mse = Median(se);
    const long paths = static_cast<long>(size) * size * spp;
    std::printf(
      "%6d %9ld %10.4f %11.2e %11.2e %12.3g\n", spp, paths, mt, me, mse, 1 / (mse * mse * mt));
    out << "spp," << spp << "," << paths << "," << mt << "," << me << "," << mse << ","
        << 1 / (mse * mse * mt) << "\n";
  }
  // Cost of curved rays (same samples, same seeds).
  const int spp = smoke ? 2 : 32;
  auto curved = Medium(w, 1e-3);
  std::vector<double> ts, tc;
  for (int r = 0; r < runs; ++r)
  {
    ts.push_back(Render(medium, size, spp, r + 1).Seconds);
    tc.push_back(Render(curved, size, spp, r + 1).Seconds);
  }
  std::printf("curved rays (RK5(4), n = 1 + 1e-3 y) vs straight (n = 1), %d spp: %.4f s vs %.4f "
              "s, ratio %.2f\n",
    spp, Median(tc), Median(ts), Median(tc) / Median(ts));
  out << "curved_vs_straight," << spp << "," << static_cast<long>(size) * size * spp << ","
      << Median(tc) << ",,," << Median(tc) / Median(ts) << "\n";
  return 0;
}
