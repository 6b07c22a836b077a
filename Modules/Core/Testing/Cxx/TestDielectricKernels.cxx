// Tests of the interface optics of Kernels/refracta_surfaces.cl on the OpenCL device (float):
// Fresnel against the analytic formula (1e-3), total internal reflection for n = 1.5 from 42 to 89
// degrees, and the same choices and directions as the host's vtkRefractaDielectric.
#include "vtkOpenCLContext.h"
#include "vtkRefractaDielectric.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace
{
const double Pi = 3.14159265358979323846;

struct Case
{
  double D[3], Ng[3], Ns[3], NInside, NOutside, Xi;
};

struct Result
{
  std::vector<float> Out; // direction xyz, reflectance
  std::vector<int> Transmitted;
};

Result RunOnDevice(const std::vector<Case>& cases)
{
  Result result;
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  EXPECT_TRUE(context->Initialize());
  cl_program program =
    context->GetProgram({ "refracta_surfaces.cl", "refracta_surfaces_tests.cl" }, "");
  EXPECT_NE(program, nullptr) << context->GetLastErrorMessage();
  if (!program)
  {
    return result;
  }
  const cl_uint n = static_cast<cl_uint>(cases.size());
  std::vector<float> in(12 * size_t(n));
  for (cl_uint i = 0; i < n; ++i)
  {
    const Case& c = cases[i];
    float* p = &in[12 * size_t(i)];
    for (int a = 0; a < 3; ++a)
    {
      p[a] = float(c.D[a]);
      p[4 + a] = float(c.Ng[a]);
      p[8 + a] = float(c.Ns[a]);
    }
    p[3] = float(c.NInside);
    p[7] = float(c.NOutside);
    p[11] = float(c.Xi);
  }
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_test_dielectric");
  vtkOpenCLBuffer ib = context->CreateBuffer(CL_MEM_READ_ONLY, in.size() * 4, in.data(), "in");
  vtkOpenCLBuffer ob = context->CreateBuffer(CL_MEM_WRITE_ONLY, n * 16, nullptr, "out");
  vtkOpenCLBuffer tb = context->CreateBuffer(CL_MEM_WRITE_ONLY, n * 4, nullptr, "transmitted");
  EXPECT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), ib.Get(), ob.Get(), tb.Get(), n), CL_SUCCESS);
  const size_t global = n;
  EXPECT_TRUE(context->RunKernel(kernel.Get(), 1, &global, nullptr, "dielectric"));
  result.Out.resize(4 * size_t(n));
  result.Transmitted.resize(n);
  EXPECT_TRUE(context->ReadBuffer(ob.Get(), result.Out.size() * 4, result.Out.data()));
  EXPECT_TRUE(context->ReadBuffer(tb.Get(), n * 4, result.Transmitted.data()));
  return result;
}

double Analytic(double i, double n1, double n2)
{
  if (i == 0.0)
  {
    return std::pow((n1 - n2) / (n1 + n2), 2);
  }
  const double t = std::asin(n1 / n2 * std::sin(i));
  return 0.5 *
    (std::pow(std::sin(i - t) / std::sin(i + t), 2) +
      std::pow(std::tan(i - t) / std::tan(i + t), 2));
}
}

TEST(DielectricKernels, FresnelAndTotalInternalReflection)
{
  std::vector<Case> cases;
  std::vector<double> angles, expected;
  for (int a = 0; a <= 89; ++a)
  {
    const double i = a * Pi / 180;
    // From outside into n = 1.5 (entering, d . ng < 0), and from inside out.
    cases.push_back({ { std::sin(i), 0, -std::cos(i) }, { 0, 0, 1 }, { 0, 0, 1 }, 1.5, 1.0, 0.5 });
    angles.push_back(a);
    expected.push_back(Analytic(i, 1.0, 1.5));
    cases.push_back({ { std::sin(i), 0, std::cos(i) }, { 0, 0, 1 }, { 0, 0, 1 }, 1.5, 1.0, 0.999 });
    angles.push_back(-a);
    expected.push_back(a >= 42 ? 1.0 : Analytic(i, 1.5, 1.0));
  }
  const Result r = RunOnDevice(cases);
  ASSERT_EQ(r.Transmitted.size(), cases.size());
  for (size_t k = 0; k < cases.size(); ++k)
  {
    EXPECT_NEAR(r.Out[4 * k + 3], expected[k], 1e-3) << angles[k];
    if (angles[k] <= -42)
    {
      // Total internal reflection: nothing transmitted even with xi = 0.999, the exact mirror.
      EXPECT_EQ(r.Out[4 * k + 3], 1.0f) << angles[k];
      EXPECT_EQ(r.Transmitted[k], 0) << angles[k];
      EXPECT_NEAR(r.Out[4 * k + 2], -cases[k].D[2], 1e-6);
    }
  }
}

TEST(DielectricKernels, SameChoicesAsHost)
{
  std::mt19937 rng(11);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Case> cases;
  for (int k = 0; k < 20000; ++k)
  {
    Case c;
    double l = 0, m = 0;
    for (int a = 0; a < 3; ++a)
    {
      c.D[a] = gauss(rng);
      c.Ng[a] = gauss(rng);
      l += c.D[a] * c.D[a];
      m += c.Ng[a] * c.Ng[a];
    }
    double s = 0;
    for (int a = 0; a < 3; ++a)
    {
      c.D[a] /= std::sqrt(l);
      c.Ng[a] /= std::sqrt(m);
      c.Ns[a] = c.Ng[a] + 0.2 * gauss(rng); // a shading normal near the geometric one
      s += c.Ns[a] * c.Ns[a];
    }
    for (double& v : c.Ns)
    {
      v /= std::sqrt(s);
    }
    c.NInside = 1.0 + 1.5 * unit(rng);
    c.NOutside = 1.0 + 0.5 * unit(rng);
    c.Xi = unit(rng);
    cases.push_back(c);
  }
  const Result r = RunOnDevice(cases);
  ASSERT_EQ(r.Transmitted.size(), cases.size());
  int compared = 0;
  for (size_t k = 0; k < cases.size(); ++k)
  {
    const Case& c = cases[k];
    const auto e = vtkRefractaDielectric::Sample(c.D, c.Ng, c.Ns, c.NInside, c.NOutside, c.Xi);
    if (std::fabs(c.Xi - e.Reflectance) < 1e-4)
    {
      continue; // a float/double tie between the branches
    }
    ++compared;
    EXPECT_EQ(r.Transmitted[k], e.Transmitted ? 1 : 0) << k;
    EXPECT_NEAR(r.Out[4 * k + 3], e.Reflectance, 1e-4) << k;
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_NEAR(r.Out[4 * k + a], e.Direction[a], 2e-3) << k; // float near grazing refraction
    }
  }
  EXPECT_GT(compared, 19000);
}
