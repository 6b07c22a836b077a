/**
 * @file    vtkOpenCLHandle.h
 * @brief   Move-only owners of OpenCL objects and a variadic kernel-argument setter.
 *
 * vtkOpenCLHandle<cl_mem> (alias vtkOpenCLBuffer), vtkOpenCLHandle<cl_kernel>
 * (vtkOpenCLKernel) and vtkOpenCLHandle<cl_event> (vtkOpenCLEvent) release their object when
 * they go out of scope, so an early return on an error path leaks nothing. Each kind is counted
 * while owned (vtkOpenCLLiveHandles()), so tests can check that nothing leaks.
 */
#ifndef vtkOpenCLHandle_h
#define vtkOpenCLHandle_h

#ifndef __VTK_WRAP__

#include "RefractaOpenCLModule.h" // for export macro

#include <CL/cl.h>

#include <utility> // for std::exchange

/**
 * Number of OpenCL objects of each kind owned by live vtkOpenCLHandle objects in this process
 * (0: cl_mem, 1: cl_kernel, 2: cl_event). For leak checks: a pass that has released everything
 * leaves the counts where they were.
 */
REFRACTAOPENCL_EXPORT long long vtkOpenCLLiveHandles(int kind);
REFRACTAOPENCL_EXPORT void vtkOpenCLCountHandle(int kind, int change);

template <typename T>
struct vtkOpenCLReleaser;
template <>
struct vtkOpenCLReleaser<cl_mem>
{
  static constexpr int Kind = 0;
  static void Release(cl_mem h) { clReleaseMemObject(h); }
};
template <>
struct vtkOpenCLReleaser<cl_kernel>
{
  static constexpr int Kind = 1;
  static void Release(cl_kernel h) { clReleaseKernel(h); }
};
template <>
struct vtkOpenCLReleaser<cl_event>
{
  static constexpr int Kind = 2;
  static void Release(cl_event h) { clReleaseEvent(h); }
};

template <typename T>
class vtkOpenCLHandle
{
public:
  vtkOpenCLHandle() = default;
  explicit vtkOpenCLHandle(T handle)
    : Handle(handle)
  {
    if (handle)
    {
      vtkOpenCLCountHandle(vtkOpenCLReleaser<T>::Kind, +1);
    }
  }
  ~vtkOpenCLHandle() { this->Reset(); }
  vtkOpenCLHandle(vtkOpenCLHandle&& other) noexcept
    : Handle(std::exchange(other.Handle, nullptr))
  {
  }
  vtkOpenCLHandle& operator=(vtkOpenCLHandle&& other) noexcept
  {
    if (this != &other)
    {
      this->Reset();
      this->Handle = std::exchange(other.Handle, nullptr); // already counted
    }
    return *this;
  }
  vtkOpenCLHandle(const vtkOpenCLHandle&) = delete;
  vtkOpenCLHandle& operator=(const vtkOpenCLHandle&) = delete;

  T Get() const { return this->Handle; }
  explicit operator bool() const { return this->Handle != nullptr; }
  void Reset(T handle = nullptr)
  {
    if (this->Handle)
    {
      vtkOpenCLReleaser<T>::Release(this->Handle);
      vtkOpenCLCountHandle(vtkOpenCLReleaser<T>::Kind, -1);
    }
    if (handle)
    {
      vtkOpenCLCountHandle(vtkOpenCLReleaser<T>::Kind, +1);
    }
    this->Handle = handle;
  }

private:
  T Handle = nullptr;
};

using vtkOpenCLBuffer = vtkOpenCLHandle<cl_mem>;
using vtkOpenCLKernel = vtkOpenCLHandle<cl_kernel>;
using vtkOpenCLEvent = vtkOpenCLHandle<cl_event>;

/**
 * The size of a buffer in bytes (CL_MEM_SIZE); 0 for a null buffer or where the query fails.
 */
inline size_t vtkOpenCLBufferBytes(cl_mem buffer)
{
  size_t bytes = 0;
  if (!buffer ||
    clGetMemObjectInfo(buffer, CL_MEM_SIZE, sizeof(bytes), &bytes, nullptr) != CL_SUCCESS)
  {
    return 0;
  }
  return bytes;
}

/**
 * Sets kernel arguments first, first + 1, ... from the values given (each passed by address with
 * its size; pass cl_mem for buffers). Returns the first error, or CL_SUCCESS.
 */
template <typename... Args>
cl_int vtkOpenCLSetKernelArgsFrom(cl_kernel kernel, cl_uint first, const Args&... args)
{
  cl_int status = CL_SUCCESS;
  cl_uint index = first;
  // Fold over the arguments; stop setting once one call has failed.
  ((status = (status == CL_SUCCESS ? clSetKernelArg(kernel, index, sizeof(Args), &args) : status),
     ++index),
    ...);
  return status;
}

/**
 * Sets kernel arguments index, index + 1, ... and advances index past them: kernels whose
 * arguments come in groups (each set by its own code) are set group after group, with no
 * argument index written down twice.
 */
template <typename... Args>
cl_int vtkOpenCLAppendKernelArgs(cl_kernel kernel, cl_uint& index, const Args&... args)
{
  const cl_int status = vtkOpenCLSetKernelArgsFrom(kernel, index, args...);
  index += static_cast<cl_uint>(sizeof...(Args));
  return status;
}

/**
 * Sets kernel arguments 0, 1, ... (vtkOpenCLSetKernelArgsFrom from 0).
 */
template <typename... Args>
cl_int vtkOpenCLSetKernelArgs(cl_kernel kernel, const Args&... args)
{
  return vtkOpenCLSetKernelArgsFrom(kernel, 0, args...);
}

#endif // __VTK_WRAP__
#endif
// VTK-HeaderTest-Exclude: vtkOpenCLHandle.h
