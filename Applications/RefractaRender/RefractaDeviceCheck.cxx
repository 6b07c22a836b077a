#include "RefractaDeviceCheck.h"

#include "vtkOpenCLContext.h"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

namespace RefractaRender
{
bool DeviceCheck()
{
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  if (!context->Initialize())
  {
    std::cerr << "refracta-render: " << context->GetLastErrorMessage() << "\n";
    return false;
  }
  std::cout << "Refracta device: " << context->GetDeviceName() << " (" << context->GetPlatformName()
            << ", " << context->GetDeviceVersion() << ")\n";
  const double scale = vtkOpenCLContext::ChooseFixedPointScale(1u << 20);
  cl_program program = context->GetProgram({ "refracta_atomics.cl", "selftest.cl" },
    "-DREFRACTA_FIXED_SCALE=" + std::to_string(scale) + "f");
  if (!program)
  {
    return false;
  }
  const unsigned int n = 1u << 20;
  std::vector<float> values(n);
  std::int64_t expected = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    values[i] = static_cast<float>((i * 2654435761u) % 1000u) / 1000.0f;
    expected += std::llrint(static_cast<double>(values[i]) * scale);
  }
  vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_atomic_fixed_contention");
  vtkOpenCLBuffer in =
    context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * 4, values.data(), "values");
  vtkOpenCLBuffer sum = context->CreateBuffer(CL_MEM_READ_WRITE, 8, nullptr, "sum");
  const unsigned int targets = 1;
  const size_t global = n;
  std::int64_t result = 0;
  if (!kernel || !in || !sum || !context->ZeroBuffer(sum.Get(), 8) ||
    vtkOpenCLSetKernelArgs(kernel.Get(), in.Get(), sum.Get(), targets) != CL_SUCCESS ||
    !context->RunKernel(kernel.Get(), 1, &global, nullptr, "accumulate") ||
    !context->ReadBuffer(sum.Get(), 8, &result) || result != expected)
  {
    std::cerr << "refracta-render: device check FAILED\n";
    return false;
  }
  std::cout << "device check passed\n";
  return true;
}
}
