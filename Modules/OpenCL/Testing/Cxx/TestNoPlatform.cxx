// With no OpenCL platform at all (the ICD loader pointed at an empty vendor directory by this
// test's environment), the context reports one clear error and everything fails without a crash.
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <string>

TEST(OpenCLContext, NoPlatformFailsCleanly)
{
  vtkNew<vtkOpenCLContext> context;
  vtkNew<vtkTest::ErrorObserver> observer;
  context->AddObserver(vtkCommand::ErrorEvent, observer);
  EXPECT_FALSE(context->Initialize());
  ASSERT_TRUE(observer->GetError());
  const std::string msg = observer->GetErrorMessage();
  EXPECT_NE(msg.find("No OpenCL platform"), std::string::npos) << msg;
  EXPECT_NE(msg.find("pocl-opencl-icd"), std::string::npos) << msg;
  observer->Clear();
  EXPECT_EQ(context->GetProgram({ "selftest.cl" }, ""), nullptr);
  EXPECT_TRUE(observer->GetError());
  EXPECT_FALSE(context->CreateBuffer(CL_MEM_READ_WRITE, 64, nullptr, "probe"));
  EXPECT_NE(vtkOpenCLContext::ListDevices().find("no OpenCL device"), std::string::npos);
}
