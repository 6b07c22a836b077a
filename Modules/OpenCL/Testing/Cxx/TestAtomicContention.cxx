// The accumulation method of the transport passes under heavy contention: millions of
// work-items adding into one address (and into a few). 64-bit fixed point must give exactly the
// sum of the rounded increments, independent of arrival order (bit-identical on a rerun); the
// compare-and-swap float add must stay within the a-priori bound of recursive float summation.
#include "vtkOpenCLContext.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace
{
std::vector<float> RandomValues(size_t n)
{
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> dist(-0.25f, 1.0f); // signed deposits too
  std::vector<float> values(n);
  for (auto& v : values)
  {
    v = dist(rng);
  }
  return values;
}

struct Accumulation
{
  std::vector<std::int64_t> Sums;
  double Seconds = 0;
};

Accumulation RunFixed(
  vtkOpenCLContext* context, const std::vector<float>& values, unsigned int targets, double scale)
{
  Accumulation out;
  const std::string options = "-DREFRACTA_FIXED_SCALE=" + std::to_string(scale) + "f";
  cl_program program = context->GetProgram({ "refracta_atomics.cl", "selftest.cl" }, options);
  EXPECT_NE(program, nullptr);
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_atomic_fixed_contention");
  vtkOpenCLBuffer in =
    context->CreateBuffer(CL_MEM_READ_ONLY, values.size() * sizeof(float), values.data(), "values");
  vtkOpenCLBuffer sums =
    context->CreateBuffer(CL_MEM_READ_WRITE, targets * sizeof(std::int64_t), nullptr, "sums");
  EXPECT_TRUE(context->ZeroBuffer(sums.Get(), targets * sizeof(std::int64_t)));
  EXPECT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), in.Get(), sums.Get(), targets), CL_SUCCESS);
  const size_t global = values.size();
  context->Finish();
  const auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(context->RunKernel(kernel.Get(), 1, &global, nullptr, "contention"));
  context->Finish();
  out.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.Sums.resize(targets);
  EXPECT_TRUE(context->ReadBuffer(sums.Get(), targets * sizeof(std::int64_t), out.Sums.data()));
  return out;
}
}

TEST(AtomicAdd, FixedPointIsExactUnderContention)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize());
  const size_t n = size_t(1) << 22;
  const std::vector<float> values = RandomValues(n);
  const double scale = vtkOpenCLContext::ChooseFixedPointScale(static_cast<double>(n));
  ASSERT_EQ(scale, std::ldexp(1.0, 40));

  for (unsigned int targets : { 1u, 7u, 64u })
  {
    // The exact answer: the sum of the same round-to-nearest-even increments, on the host.
    std::vector<std::int64_t> expected(targets, 0);
    std::vector<double> exactSums(targets, 0.0);
    for (size_t i = 0; i < n; ++i)
    {
      expected[i % targets] += std::llrint(static_cast<double>(values[i]) * scale);
      exactSums[i % targets] += values[i];
    }
    const Accumulation first = RunFixed(context, values, targets, scale);
    const Accumulation second = RunFixed(context, values, targets, scale);
    for (unsigned int t = 0; t < targets; ++t)
    {
      ASSERT_EQ(first.Sums[t], expected[t]) << "target " << t << " of " << targets;
      ASSERT_EQ(second.Sums[t], first.Sums[t]) << "not deterministic";
      // Rounding each deposit costs at most half a unit of 1/scale.
      const double perTarget = static_cast<double>(n / targets + 1);
      EXPECT_LE(std::abs(first.Sums[t] / scale - exactSums[t]), perTarget * 0.5 / scale + 1e-9);
    }
    std::cout << "fixed point, " << n << " deposits into " << targets
              << " address(es): " << n / first.Seconds / 1e6 << " M deposits/s\n";
  }
}

TEST(AtomicAdd, CompareAndSwapFloatIsBounded)
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize());
  const size_t n = size_t(1) << 20;
  const std::vector<float> values = RandomValues(n);
  cl_program program = context->GetProgram({ "refracta_atomics.cl", "selftest.cl" }, "");
  ASSERT_NE(program, nullptr);
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_atomic_float_cas_contention");
  vtkOpenCLBuffer in =
    context->CreateBuffer(CL_MEM_READ_ONLY, n * sizeof(float), values.data(), "values");
  vtkOpenCLBuffer sum = context->CreateBuffer(CL_MEM_READ_WRITE, sizeof(float), nullptr, "sum");
  ASSERT_TRUE(context->ZeroBuffer(sum.Get(), sizeof(float)));
  const unsigned int targets = 1;
  ASSERT_EQ(vtkOpenCLSetKernelArgs(kernel.Get(), in.Get(), sum.Get(), targets), CL_SUCCESS);
  const size_t global = n;
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(context->RunKernel(kernel.Get(), 1, &global, nullptr, "cas"));
  ASSERT_TRUE(context->Finish());
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  float result = 0;
  ASSERT_TRUE(context->ReadBuffer(sum.Get(), sizeof(float), &result));

  double exact = 0.0, absolute = 0.0;
  for (float v : values)
  {
    exact += v;
    absolute += std::abs(v);
  }
  // Recursive summation in any order: |error| <= (n - 1) u sum|x_i| / (1 - (n - 1) u), u = 2^-24.
  const double u = std::ldexp(1.0, -24);
  const double bound = (n - 1) * u * absolute / (1.0 - (n - 1) * u);
  const double error = std::abs(static_cast<double>(result) - exact);
  EXPECT_LE(error, bound);
  EXPECT_TRUE(std::isfinite(result));
  // Nothing was lost to a race: a lost update would remove a whole value (about 0.4 on average).
  EXPECT_LT(error, 0.01 * exact);
  std::cout << "CAS float, " << n << " deposits into one address: " << n / seconds / 1e6
            << " M deposits/s, relative error " << error / exact << " (bound " << bound / exact
            << ")\n";
}
