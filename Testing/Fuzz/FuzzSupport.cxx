#include "FuzzSupport.h"

#include "vtkImageData.h"
#include "vtkLogger.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>

namespace refracta_fuzz
{
namespace
{
int ErrorCount = 0;
std::string LastError;
bool Verbose = false;

// Counts VTK's errors; prints them (and warnings) only when asked to.
class QuietOutputWindow : public vtkOutputWindow
{
public:
  static QuietOutputWindow* New();
  vtkTypeMacro(QuietOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override { this->Print(text); }
  void DisplayErrorText(const char* text) override
  {
    ++ErrorCount;
    LastError = text ? text : "";
    this->Print(text);
  }
  void DisplayWarningText(const char* text) override { this->Print(text); }
  void DisplayGenericWarningText(const char* text) override { this->Print(text); }
  void DisplayDebugText(const char* text) override { this->Print(text); }

  bool Verbose = false;

private:
  void Print(const char* text) const
  {
    if (this->Verbose && text)
    {
      std::cerr << text;
    }
  }
};
vtkStandardNewMacro(QuietOutputWindow);
}

//------------------------------------------------------------------------------
uint8_t FuzzBytes::Byte()
{
  return this->Pos < this->Size ? this->Data[this->Pos++] : 0;
}

int FuzzBytes::Int(int lo, int hi)
{
  if (hi <= lo)
  {
    return lo;
  }
  const unsigned span = static_cast<unsigned>(hi - lo) + 1u;
  const unsigned raw = span > 256u ? (this->Byte() << 8 | this->Byte()) : this->Byte();
  return lo + static_cast<int>(raw % span);
}

double FuzzBytes::Double()
{
  static const double edge[] = { 0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e-300,
    std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
    std::numeric_limits<double>::min(), 1e-45, 1e-30, 1e30, -1e30, 1e300, -1e300, DBL_MAX, -DBL_MAX,
    FLT_MAX, -FLT_MAX, 3.5e38, std::numeric_limits<double>::quiet_NaN(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 1e9, 16384.0,
    2147483648.0, 0.9999, 1.0000001 };
  const uint8_t selector = this->Byte();
  switch (selector % 8)
  {
    case 5:
      return edge[this->Byte() % (sizeof(edge) / sizeof(edge[0]))];
    case 6:
    {
      uint64_t bits = 0;
      for (int b = 0; b < 8; ++b)
      {
        bits = bits << 8 | this->Byte();
      }
      double d;
      std::memcpy(&d, &bits, sizeof d);
      return d;
    }
    case 7:
    {
      uint32_t bits = 0;
      for (int b = 0; b < 4; ++b)
      {
        bits = bits << 8 | this->Byte();
      }
      float f;
      std::memcpy(&f, &bits, sizeof f);
      return f;
    }
    default:
      return this->Lattice();
  }
}

//------------------------------------------------------------------------------
void InstallQuietOutput()
{
  static bool installed = false;
  if (installed)
  {
    return;
  }
  installed = true;
  vtkNew<QuietOutputWindow> window;
  const char* verbose = std::getenv("REFRACTA_FUZZ_VERBOSE");
  window->Verbose = verbose && *verbose && std::strcmp(verbose, "0") != 0;
  Verbose = window->Verbose;
  vtkOutputWindow::SetInstance(window);
  // VTK also logs errors through vtkLogger (stderr): keep the fuzzer's output readable.
  vtkLogger::SetStderrVerbosity(
    window->Verbose ? vtkLogger::VERBOSITY_WARNING : vtkLogger::VERBOSITY_OFF);
}

void Print(const std::string& text)
{
  if (Verbose)
  {
    std::cerr << text << std::endl;
  }
}

int GetErrorCount()
{
  return ErrorCount;
}

void ResetErrorCount()
{
  ErrorCount = 0;
  LastError.clear();
}

const std::string& GetLastError()
{
  return LastError;
}

void Require(bool condition, const char* what)
{
  if (!condition)
  {
    std::fprintf(stderr, "refracta fuzz: contract broken: %s\n", what);
    std::abort();
  }
}

bool IsValidMedium(vtkImageData* image)
{
  vtkNew<vtkMediumValidator> validator;
  if (validator->Validate(image))
  {
    return true;
  }
  std::fprintf(stderr, "refracta fuzz: invalid medium:\n%s\n", validator->GetErrorMessage());
  return false;
}
}
