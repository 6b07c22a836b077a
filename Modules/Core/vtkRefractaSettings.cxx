#include "vtkRefractaSettings.h"

#include "vtkObject.h"

#include <algorithm>
#include <cmath>

//------------------------------------------------------------------------------
bool vtkRefractaSettings::SetClamped(
  vtkObject* caller, const char* property, double& target, double value, double lo, double hi)
{
  if (std::isnan(value))
  {
    vtkErrorWithObjectMacro(caller,
      "Set" << property << "(nan): must be a number in [" << lo << ", " << hi << "]; " << property
            << " stays " << target);
    return false;
  }
  const double clamped = std::min(std::max(value, lo), hi);
  if (clamped == target)
  {
    return false;
  }
  target = clamped;
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractaSettings::SetClamped3(vtkObject* caller, const char* property, double target[3],
  const double value[3], double lo, double hi)
{
  if (!std::isfinite(value[0]) || !std::isfinite(value[1]) || !std::isfinite(value[2]))
  {
    vtkErrorWithObjectMacro(caller,
      "Set" << property << "(" << value[0] << ", " << value[1] << ", " << value[2]
            << "): every component must be a finite number in [" << lo << ", " << hi << "]; "
            << property << " stays (" << target[0] << ", " << target[1] << ", " << target[2]
            << ")");
    return false;
  }
  bool changed = false;
  for (int c = 0; c < 3; ++c)
  {
    const double clamped = std::min(std::max(value[c], lo), hi);
    changed = changed || clamped != target[c];
    target[c] = clamped;
  }
  return changed;
}
