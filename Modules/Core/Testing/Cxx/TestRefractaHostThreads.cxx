// vtkRefractaHostThreads: Sequential becomes STDThread unless the user chose a backend. Run twice
// by ctest: RefractaCore.HostThreads (VTK_SMP_BACKEND_IN_USE unset) and
// RefractaCore.HostThreadsUserChoice (VTK_SMP_BACKEND_IN_USE=Sequential, which must be kept).
#include "vtkRefractaHostThreads.h"
#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

TEST(RefractaHostThreads, ThreadsUnlessTheUserChose)
{
  const char* chosen = std::getenv("VTK_SMP_BACKEND_IN_USE");
  const std::string before = vtkSMPTools::GetBackend();
  const bool threaded = vtkRefractaHostThreads::UseThreadedBackend();
  const std::string after = vtkSMPTools::GetBackend();
  std::cout << "backend " << before << " -> " << vtkRefractaHostThreads::GetBackendDescription()
            << " (VTK_SMP_BACKEND_IN_USE " << (chosen ? chosen : "unset") << ")\n";
  if (chosen && *chosen)
  {
    EXPECT_EQ(after, before) << "the user's choice is kept";
    EXPECT_EQ(after, chosen);
  }
  else if (before == "Sequential")
  {
    EXPECT_EQ(after, "STDThread"); // ParaView 5.11's VTK on Debian is built with it
  }
  else
  {
    EXPECT_EQ(after, before) << "a threaded default is left alone";
  }
  EXPECT_EQ(threaded, vtkSMPTools::GetEstimatedNumberOfThreads() > 1);
  // Idempotent: a second call changes nothing.
  vtkRefractaHostThreads::UseThreadedBackend();
  EXPECT_EQ(std::string(vtkSMPTools::GetBackend()), after);
}
