/**
 * @class   vtkOpenCLKernelLibrary
 * @brief   The OpenCL C sources of Kernels/, embedded into the library at build time.
 *
 * Every `Kernels/*.cl` file is compiled into RefractaOpenCL as a string (see
 * CMake/RefractaEmbedKernels.cmake), so no kernel source is read from disk at run time. A file
 * is looked up by its name, e.g. "selftest.cl"; vtkOpenCLContext::GetProgram() concatenates the
 * files a program needs in the order given.
 */
#ifndef vtkOpenCLKernelLibrary_h
#define vtkOpenCLKernelLibrary_h

#include "RefractaOpenCLModule.h" // for export macro
#include "vtkObject.h"

class REFRACTAOPENCL_EXPORT vtkOpenCLKernelLibrary : public vtkObject
{
public:
  static vtkOpenCLKernelLibrary* New();
  vtkTypeMacro(vtkOpenCLKernelLibrary, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Number of embedded kernel files.
   */
  static int GetNumberOfKernelFiles();

  /**
   * Name of the i-th embedded file (e.g. "selftest.cl"), or nullptr when out of range.
   */
  static const char* GetKernelFileName(int i);

  /**
   * OpenCL C source of the named file, or nullptr when no such file was embedded.
   */
  static const char* GetKernelSource(const char* fileName);

#ifndef __VTK_WRAP__
  struct Entry
  {
    const char* Name;
    const char* Source;
  };
  /** The generated table, terminated by an entry whose Name is nullptr. */
  static const Entry* GetEntries();
#endif

protected:
  vtkOpenCLKernelLibrary() = default;
  ~vtkOpenCLKernelLibrary() override = default;

private:
  vtkOpenCLKernelLibrary(const vtkOpenCLKernelLibrary&) = delete;
  void operator=(const vtkOpenCLKernelLibrary&) = delete;
};

#endif
