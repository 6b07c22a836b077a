#include "vtkRefractaParticleMedium.h"

#include "vtkDataArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"

#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkRefractaParticleMedium);

namespace
{
// One array's contract: name, components, whether required, valid range and its description.
struct ParticleArraySpec
{
  const char* Name;
  int Components;
  bool Required;
  double Low;
  double High;
  bool OpenLow;  // Low itself is invalid
  bool OpenHigh; // High itself is invalid
  const char* Range;
};

bool InRange(const ParticleArraySpec& spec, double v)
{
  if (!std::isfinite(v))
  {
    return false;
  }
  const bool lowOk = spec.OpenLow ? v > spec.Low : v >= spec.Low;
  const bool highOk = spec.OpenHigh ? v < spec.High : v <= spec.High;
  return lowOk && highOk;
}

bool CheckArray(vtkPointSet* particles, const ParticleArraySpec& spec, std::string& message)
{
  vtkDataArray* array = particles->GetPointData()->GetArray(spec.Name);
  std::ostringstream out;
  if (!array)
  {
    if (spec.Required)
    {
      out << "the particles have no point-data array '" << spec.Name << "' (" << spec.Components
          << " component(s), " << spec.Range << ")";
      message = out.str();
      return false;
    }
    return true;
  }
  if (array->GetNumberOfComponents() != spec.Components)
  {
    out << "point-data array '" << spec.Name << "' has " << array->GetNumberOfComponents()
        << " components; it needs " << spec.Components;
    message = out.str();
    return false;
  }
  const vtkIdType n = particles->GetNumberOfPoints();
  if (array->GetNumberOfTuples() != n)
  {
    out << "point-data array '" << spec.Name << "' has " << array->GetNumberOfTuples()
        << " tuples for " << n << " particles";
    message = out.str();
    return false;
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < spec.Components; ++c)
    {
      const double v = array->GetComponent(i, c);
      if (!InRange(spec, v))
      {
        out << "point-data array '" << spec.Name << "' of particle " << i << " is " << v
            << "; it must be " << spec.Range;
        message = out.str();
        return false;
      }
    }
  }
  return true;
}
}

//------------------------------------------------------------------------------
bool vtkRefractaParticleMedium::Validate(vtkPointSet* particles, std::string& message)
{
  if (!particles || particles->GetNumberOfPoints() == 0)
  {
    message = "the particle set is empty (a vtkPointSet with at least one point is needed)";
    return false;
  }
  const double inf = HUGE_VAL;
  const ParticleArraySpec specs[] = {
    { RadiusName(), 1, true, 0.0, inf, true, true, "finite and > 0 (world units)" },
    { ExtinctionName(), 3, true, 0.0, inf, false, true, "finite and >= 0 (per world unit)" },
    { AlbedoName(), 3, false, 0.0, 1.0, false, false, "in [0, 1]" },
    { AnisotropyName(), 1, false, -1.0, 1.0, true, true, "in (-1, 1) (Henyey-Greenstein g)" },
    { EmissionName(), 3, false, 0.0, inf, false, true, "finite and >= 0" },
  };
  for (const ParticleArraySpec& spec : specs)
  {
    if (!CheckArray(particles, spec, message))
    {
      return false;
    }
  }
  double x[3];
  for (vtkIdType i = 0; i < particles->GetNumberOfPoints(); ++i)
  {
    particles->GetPoint(i, x);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      std::ostringstream out;
      out << "particle " << i << " has a non-finite position";
      message = out.str();
      return false;
    }
  }
  message.clear();
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractaParticleMedium::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Arrays: " << RadiusName() << ", " << ExtinctionName() << ", " << AlbedoName()
     << ", " << AnisotropyName() << ", " << EmissionName() << "\n";
}
