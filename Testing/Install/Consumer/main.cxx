// A program outside the Refracta tree that finds the installed package with find_package(Refracta)
// and uses one class of each module.
#include "vtkMediumMaterial.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"

#include <cstring>

int main()
{
  vtkNew<vtkMediumMaterial> glass;
  glass->SetRefractiveIndex(1.5);
  const bool ok = glass->GetRefractiveIndex() == 1.5 &&
    std::strcmp(vtkOpenCLContext::GetErrorName(-30), "CL_INVALID_VALUE") == 0;
  return ok ? 0 : 1;
}
