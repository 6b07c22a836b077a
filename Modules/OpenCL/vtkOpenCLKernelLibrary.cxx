#include "vtkOpenCLKernelLibrary.h"

#include "vtkObjectFactory.h"

#include <cstring>

vtkStandardNewMacro(vtkOpenCLKernelLibrary);

//------------------------------------------------------------------------------
int vtkOpenCLKernelLibrary::GetNumberOfKernelFiles()
{
  int n = 0;
  for (const Entry* e = GetEntries(); e->Name; ++e)
  {
    ++n;
  }
  return n;
}

//------------------------------------------------------------------------------
const char* vtkOpenCLKernelLibrary::GetKernelFileName(int i)
{
  return (i >= 0 && i < GetNumberOfKernelFiles()) ? GetEntries()[i].Name : nullptr;
}

//------------------------------------------------------------------------------
const char* vtkOpenCLKernelLibrary::GetKernelSource(const char* fileName)
{
  if (!fileName)
  {
    return nullptr;
  }
  for (const Entry* e = GetEntries(); e->Name; ++e)
  {
    if (std::strcmp(e->Name, fileName) == 0)
    {
      return e->Source;
    }
  }
  return nullptr;
}

//------------------------------------------------------------------------------
void vtkOpenCLKernelLibrary::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (const Entry* e = GetEntries(); e->Name; ++e)
  {
    os << indent << e->Name << " (" << std::strlen(e->Source) << " characters)\n";
  }
}
