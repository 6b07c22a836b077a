// refracta-render: Refracta's command-line entry point.
//
// Until the rendering pipeline lands, the default job checks the OpenCL device end to end: it
// builds the embedded self-test kernels, runs a saxpy and a fixed-point accumulation on the
// selected device, verifies both results exactly, and prints the device and the timings.
#include "vtkOpenCLContext.h"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <vector>

namespace
{
void PrintUsage(std::ostream& os)
{
  os << "usage: refracta-render [--list-devices] [--help]\n"
        "  Runs the OpenCL device check on the device chosen by REFRACTA_OPENCL_DEVICE\n"
        "  ('gpu', 'cpu', 'P:D' or part of a device name; default: first GPU, else CPU).\n";
}

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool CheckSaxpy(vtkOpenCLContext* context, cl_program program)
{
  const unsigned int n = 1u << 22;
  std::vector<float> x(n), y(n);
  for (unsigned int i = 0; i < n; ++i)
  {
    x[i] = static_cast<float>(i % 4096);
    y[i] = static_cast<float>(i % 3);
  }
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_saxpy");
  vtkOpenCLBuffer xb = context->CreateBuffer(CL_MEM_READ_ONLY, n * 4, x.data(), "x");
  vtkOpenCLBuffer yb = context->CreateBuffer(CL_MEM_READ_WRITE, n * 4, y.data(), "y");
  const float a = 0.5f;
  if (!kernel || !xb || !yb ||
    vtkOpenCLSetKernelArgs(kernel.Get(), a, xb.Get(), yb.Get(), n) != CL_SUCCESS)
  {
    return false;
  }
  const size_t global = n;
  const auto start = std::chrono::steady_clock::now();
  if (!context->RunKernel(kernel.Get(), 1, &global, nullptr, "refracta_saxpy") ||
    !context->Finish())
  {
    return false;
  }
  const double seconds = Seconds(start);
  std::vector<float> result(n);
  if (!context->ReadBuffer(yb.Get(), n * 4, result.data()))
  {
    return false;
  }
  for (unsigned int i = 0; i < n; ++i)
  {
    if (result[i] != a * x[i] + y[i])
    {
      std::cerr << "saxpy result wrong at " << i << ": " << result[i] << "\n";
      return false;
    }
  }
  std::cout << "  saxpy over " << n << " floats: " << seconds * 1e3 << " ms ("
            << 3.0 * n * 4 / seconds / 1e9 << " GB/s)\n";
  return true;
}

bool CheckFixedPointAccumulation(vtkOpenCLContext* context, cl_program program, double scale)
{
  const unsigned int n = 1u << 20;
  std::vector<float> values(n);
  std::int64_t expected = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    values[i] = static_cast<float>((i * 2654435761u) % 1000u) / 1000.0f;
    expected += std::llrint(static_cast<double>(values[i]) * scale);
  }
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_atomic_fixed_contention");
  vtkOpenCLBuffer in = context->CreateBuffer(CL_MEM_READ_ONLY, n * 4, values.data(), "values");
  vtkOpenCLBuffer sum = context->CreateBuffer(CL_MEM_READ_WRITE, 8, nullptr, "sum");
  const unsigned int targets = 1;
  if (!kernel || !in || !sum || !context->ZeroBuffer(sum.Get(), 8) ||
    vtkOpenCLSetKernelArgs(kernel.Get(), in.Get(), sum.Get(), targets) != CL_SUCCESS)
  {
    return false;
  }
  const size_t global = n;
  const auto start = std::chrono::steady_clock::now();
  if (!context->RunKernel(kernel.Get(), 1, &global, nullptr, "accumulate") || !context->Finish())
  {
    return false;
  }
  const double seconds = Seconds(start);
  std::int64_t result = 0;
  if (!context->ReadBuffer(sum.Get(), 8, &result) || result != expected)
  {
    std::cerr << "fixed-point sum " << result << " differs from the exact " << expected << "\n";
    return false;
  }
  std::cout << "  fixed-point accumulation of " << n << " deposits into one address: exact, "
            << n / seconds / 1e6 << " M deposits/s\n";
  return true;
}
}

int main(int argc, char* argv[])
{
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h"))
    {
      PrintUsage(std::cout);
      return 0;
    }
    if (!std::strcmp(argv[i], "--list-devices"))
    {
      std::cout << vtkOpenCLContext::ListDevices();
      return 0;
    }
    std::cerr << "refracta-render: unknown option '" << argv[i] << "'\n";
    PrintUsage(std::cerr);
    return 2;
  }

  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::cerr << "refracta-render: " << context->GetLastErrorMessage() << "\n";
    return 1;
  }
  std::cout << "Refracta device: " << context->GetDeviceName() << " (" << context->GetPlatformName()
            << ", " << context->GetDeviceVersion() << ", " << context->GetNumberOfComputeUnits()
            << " compute units)\n";
  const double scale = vtkOpenCLContext::ChooseFixedPointScale(1u << 20);
  const auto start = std::chrono::steady_clock::now();
  cl_program program = context->GetProgram({ "refracta_atomics.cl", "selftest.cl" },
    "-DREFRACTA_FIXED_SCALE=" + std::to_string(scale) + "f");
  if (!program)
  {
    return 1;
  }
  std::cout << "  program ready in " << Seconds(start) * 1e3 << " ms ("
            << (context->GetNumberOfBinaryLoads() ? "cached binary" : "compiled from source")
            << ")\n";
  if (!CheckSaxpy(context, program) || !CheckFixedPointAccumulation(context, program, scale))
  {
    std::cerr << "refracta-render: device check FAILED\n";
    return 1;
  }
  std::cout << "device check passed\n";
  return 0;
}
