#include "vtkReferenceLights.h"

#include "vtkCamera.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkReferenceMedium.h"

#include <sstream>

namespace refracta
{
namespace reference
{
// True when a switched-on light of the collection is positional (point or spot).
bool HasPositionalLight(vtkLightCollection* lights)
{
  if (!lights)
  {
    return false;
  }
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* l = lights->GetNextLight(it))
  {
    if (l->GetSwitch() && l->GetPositional())
    {
      return true;
    }
  }
  return false;
}

// Converts the renderer's lights to the grid-local frame. Returns an error message for a light
// whose direction is undefined or whose intensity is invalid (empty when all are usable).
std::string BuildLights(const Medium& m, vtkLightCollection* lights, vtkCamera* camera,
  double deltaDeg, double radius, std::vector<Light>& out)
{
  out.clear();
  if (!lights)
  {
    return std::string();
  }
  lights->InitTraversal();
  int index = -1;
  while (vtkLight* vl = lights->GetNextItem())
  {
    ++index;
    if (!vl->GetSwitch())
    {
      continue;
    }
    double pos[3], foc[3];
    if (vl->LightTypeIsHeadlight() && camera)
    {
      camera->GetPosition(pos);
      camera->GetFocalPoint(foc);
    }
    else
    {
      vl->GetTransformedPosition(pos);
      vl->GetTransformedFocalPoint(foc);
    }
    const bool needsDirection = !vl->GetPositional() || vl->GetConeAngle() < 90;
    const double sep[3] = { pos[0] - foc[0], pos[1] - foc[1], pos[2] - foc[2] };
    if (needsDirection && !(vtkMath::Norm(sep) > 0))
    {
      std::ostringstream msg;
      msg << "Light " << index << " is " << (vl->GetPositional() ? "a spot" : "a directional")
          << " light whose position equals its focal point, so its direction is undefined; give "
             "it a position different from its focal point.";
      return msg.str();
    }
    if (!std::isfinite(vl->GetIntensity()) || vl->GetIntensity() < 0)
    {
      std::ostringstream msg;
      msg << "Light " << index << " has intensity " << vl->GetIntensity()
          << "; it must be finite and >= 0.";
      return msg.str();
    }
    double col[3];
    vl->GetDiffuseColor(col);
    Light l;
    l.Colour = vl->GetIntensity() * ToVec3(col);
    const Vec3 p = m.ToLocalPoint(pos), f = m.ToLocalPoint(foc);
    if (!vl->GetPositional())
    {
      l.Directional = true;
      l.Towards = Normalized(p - f);
      const double delta = vtkMath::RadiansFromDegrees(deltaDeg);
      const double s = std::sin(delta);
      l.OmcDelta = 2 * std::sin(0.5 * delta) * std::sin(0.5 * delta);
      l.Radiance = 1.0 / (Pi * s * s);
    }
    else
    {
      l.Directional = false;
      l.Centre = p;
      l.Radius = radius;
      l.Radiance = 1.0 / (Pi * radius * radius);
      if (vl->GetConeAngle() < 90)
      {
        l.Spot = true;
        l.Axis = Normalized(f - p);
        l.CosCone = std::cos(vtkMath::RadiansFromDegrees(vl->GetConeAngle()));
        l.Exponent = vl->GetExponent();
      }
    }
    out.push_back(l);
  }
  return std::string();
}
} // namespace reference
} // namespace refracta
