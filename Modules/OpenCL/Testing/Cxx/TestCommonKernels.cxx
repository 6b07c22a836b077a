// Tests of the shared device helpers in Kernels/refracta_common.cl: trilinear sampling agrees
// with a double-precision host evaluation (edge clamping included), the Henyey-Greenstein phase
// function integrates to one over the sphere, and the random streams are uniform and
// reproducible.
#include "vtkOpenCLContext.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace
{
const std::vector<std::string> Files = { "refracta_common.cl", "refracta_common_tests.cl" };

double HostTrilinear(const std::vector<float>& f, const int d[3], const double u[3])
{
  int i0[3], i1[3];
  double w[3];
  for (int a = 0; a < 3; ++a)
  {
    const double c = std::min(std::max(u[a], 0.0), double(d[a] - 1));
    i0[a] = static_cast<int>(std::floor(c));
    i1[a] = std::min(i0[a] + 1, d[a] - 1);
    w[a] = c - i0[a];
  }
  auto at = [&](int i, int j, int k) { return double(f[i + d[0] * (j + d[1] * k)]); };
  double result = 0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const int i = (corner & 1) ? i1[0] : i0[0];
    const int j = (corner & 2) ? i1[1] : i0[1];
    const int k = (corner & 4) ? i1[2] : i0[2];
    const double weight = ((corner & 1) ? w[0] : 1 - w[0]) * ((corner & 2) ? w[1] : 1 - w[1]) *
      ((corner & 4) ? w[2] : 1 - w[2]);
    result += weight * at(i, j, k);
  }
  return result;
}

std::vector<float> RunPhase(vtkOpenCLContext* context, const std::vector<float>& mu, float g)
{
  cl_program program = context->GetProgram(Files, "");
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_test_phase");
  const cl_uint n = static_cast<cl_uint>(mu.size());
  vtkOpenCLBuffer in = context->CreateBuffer(CL_MEM_READ_ONLY, n * 4, mu.data(), "mu");
  vtkOpenCLBuffer out = context->CreateBuffer(CL_MEM_WRITE_ONLY, n * 4, nullptr, "phase");
  EXPECT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), in.Get(), g, out.Get(), n), CL_SUCCESS);
  const size_t global = n;
  EXPECT_TRUE(context->RunKernel(kernel.Get(), 1, &global, nullptr, "phase"));
  std::vector<float> result(n);
  EXPECT_TRUE(context->ReadBuffer(out.Get(), n * 4, result.data()));
  return result;
}

std::vector<float> RunRng(vtkOpenCLContext* context, cl_uint seed, cl_uint count, cl_uint n)
{
  cl_program program = context->GetProgram(Files, "");
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_test_rng");
  vtkOpenCLBuffer out =
    context->CreateBuffer(CL_MEM_WRITE_ONLY, size_t(n) * count * 4, nullptr, "u");
  EXPECT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), seed, count, out.Get(), n), CL_SUCCESS);
  const size_t global = n;
  EXPECT_TRUE(context->RunKernel(kernel.Get(), 1, &global, nullptr, "rng"));
  std::vector<float> result(size_t(n) * count);
  EXPECT_TRUE(context->ReadBuffer(out.Get(), result.size() * 4, result.data()));
  return result;
}
}

TEST(CommonKernels, TrilinearMatchesHost)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize());
  const int d[3] = { 5, 4, 3 };
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> value(-2.0f, 3.0f);
  std::uniform_real_distribution<float> coordinate(-1.5f, 6.0f); // inside and outside the grid
  std::vector<float> field(d[0] * d[1] * d[2]);
  std::generate(field.begin(), field.end(), [&] { return value(rng); });
  const cl_uint n = 4096;
  std::vector<float> points(3 * n);
  std::generate(points.begin(), points.end(), [&] { return coordinate(rng); });

  cl_program program = context->GetProgram(Files, "");
  ASSERT_NE(program, nullptr) << context->GetLastErrorMessage();
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_test_sample");
  vtkOpenCLBuffer f = context->CreateBuffer(CL_MEM_READ_ONLY, field.size() * 4, field.data(), "f");
  vtkOpenCLBuffer p =
    context->CreateBuffer(CL_MEM_READ_ONLY, points.size() * 4, points.data(), "points");
  vtkOpenCLBuffer out = context->CreateBuffer(CL_MEM_WRITE_ONLY, n * 4, nullptr, "out");
  const cl_int4 dims = { { d[0], d[1], d[2], 0 } };
  ASSERT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), f.Get(), dims, p.Get(), out.Get(), n), CL_SUCCESS);
  const size_t global = n;
  ASSERT_TRUE(context->RunKernel(kernel.Get(), 1, &global, nullptr, "sample"));
  std::vector<float> result(n);
  ASSERT_TRUE(context->ReadBuffer(out.Get(), n * 4, result.data()));
  for (cl_uint i = 0; i < n; ++i)
  {
    const double u[3] = { points[3 * i], points[3 * i + 1], points[3 * i + 2] };
    ASSERT_NEAR(result[i], HostTrilinear(field, d, u), 2e-5) << "point " << i;
  }
}

TEST(HenyeyGreenstein, Normalized)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize());
  // Integrate 2 pi p(mu) and 2 pi mu p(mu) over mu in [-1, 1] with the trapezoid rule on nodes
  // graded towards the forward (or backward) peak, whose width is about (1 - |g|)^2.
  const int intervals = 200000;
  for (float g : { -0.999f, -0.7f, 0.0f, 0.3f, 0.9f, 0.99f, 0.999f })
  {
    std::vector<float> mu(intervals + 1);
    for (int i = 0; i <= intervals; ++i)
    {
      const double t = std::pow(double(intervals - i) / intervals, 4.0);
      mu[i] = static_cast<float>(g >= 0 ? 1.0 - 2.0 * t : -1.0 + 2.0 * t);
    }
    std::sort(mu.begin(), mu.end());
    const std::vector<float> p = RunPhase(context, mu, g);
    double integral = 0, meanCos = 0;
    for (int i = 0; i < intervals; ++i)
    {
      ASSERT_TRUE(std::isfinite(p[i]));
      const double h = double(mu[i + 1]) - mu[i];
      integral += 0.5 * h * (double(p[i]) + p[i + 1]);
      meanCos += 0.5 * h * (double(p[i]) * mu[i] + double(p[i + 1]) * mu[i + 1]);
    }
    integral *= 2.0 * M_PI;
    meanCos *= 2.0 * M_PI;
    EXPECT_NEAR(integral, 1.0, 2e-3) << "g = " << g;
    // The mean cosine is g: the definition of the anisotropy.
    EXPECT_NEAR(meanCos, g, 2e-3) << "g = " << g;
  }
  // Isotropic case is exactly 1 / (4 pi).
  const std::vector<float> iso = RunPhase(context, { -1.0f, 0.0f, 1.0f }, 0.0f);
  for (float v : iso)
  {
    EXPECT_NEAR(v, 1.0 / (4.0 * M_PI), 1e-7);
  }
}

TEST(CommonKernels, RandomStreamsAreUniformAndReproducible)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize());
  const cl_uint n = 1 << 16, count = 16;
  const std::vector<float> a = RunRng(context, 42, count, n);
  const std::vector<float> b = RunRng(context, 42, count, n);
  const std::vector<float> c = RunRng(context, 43, count, n);
  ASSERT_EQ(a, b);
  size_t same = 0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    same += a[i] == c[i];
  }
  EXPECT_LT(same, a.size() / 1000);

  // Chi-square over 64 bins; 63 degrees of freedom, p = 0.001 critical value about 103.4.
  std::vector<double> bins(64, 0.0);
  double mean = 0;
  for (float u : a)
  {
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    bins[static_cast<int>(u * 64)] += 1;
    mean += u;
  }
  mean /= a.size();
  const double expected = a.size() / 64.0;
  double chi2 = 0;
  for (double count64 : bins)
  {
    chi2 += (count64 - expected) * (count64 - expected) / expected;
  }
  EXPECT_LT(chi2, 103.4);
  EXPECT_NEAR(mean, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / a.size()));
  // Successive numbers of one stream are uncorrelated.
  double corr = 0;
  for (cl_uint i = 0; i < n; ++i)
  {
    for (cl_uint k = 0; k + 1 < count; ++k)
    {
      corr += (a[i * count + k] - 0.5) * (a[i * count + k + 1] - 0.5);
    }
  }
  corr /= (double(n) * (count - 1) / 12.0);
  EXPECT_LT(std::abs(corr), 0.01);
}
