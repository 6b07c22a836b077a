#include "vtkRefractaHostThreads.h"

#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"

#include <cstdlib>
#include <mutex>
#include <string>

vtkStandardNewMacro(vtkRefractaHostThreads);

//------------------------------------------------------------------------------
bool vtkRefractaHostThreads::UseThreadedBackend()
{
  static std::once_flag once;
  std::call_once(once,
    []
    {
      const char* chosen = std::getenv("VTK_SMP_BACKEND_IN_USE");
      if ((!chosen || !*chosen) && std::string(vtkSMPTools::GetBackend()) == "Sequential")
      {
        vtkSMPTools::SetBackend("STDThread"); // false (and no change) where VTK lacks it
      }
    });
  return vtkSMPTools::GetEstimatedNumberOfThreads() > 1;
}

//------------------------------------------------------------------------------
std::string vtkRefractaHostThreads::GetBackendDescription()
{
  return std::string(vtkSMPTools::GetBackend()) + ", " +
    std::to_string(vtkSMPTools::GetEstimatedNumberOfThreads()) + " thread(s)";
}

//------------------------------------------------------------------------------
void vtkRefractaHostThreads::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Backend: " << GetBackendDescription() << "\n";
}
