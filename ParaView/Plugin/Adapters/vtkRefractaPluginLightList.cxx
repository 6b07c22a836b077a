#include "vtkRefractaPluginLightList.h"

#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkObjectFactory.h"

#include <cmath>
#include <string>

vtkStandardNewMacro(vtkRefractaPluginLightList);

//------------------------------------------------------------------------------
vtkRefractaPluginLightList::vtkRefractaPluginLightList() = default;

//------------------------------------------------------------------------------
vtkRefractaPluginLightList::~vtkRefractaPluginLightList() = default;

namespace
{
// Whether a row can be a light; `why` says what is wrong otherwise.
bool CheckRow(const double values[vtkRefractaPluginLightList::LIGHT_VALUES], std::string& why)
{
  for (int i = 0; i < vtkRefractaPluginLightList::LIGHT_VALUES; ++i)
  {
    if (!std::isfinite(values[i]))
    {
      why = "value " + std::to_string(i) + " is not finite";
      return false;
    }
  }
  const double type = values[0];
  if (type != 0.0 && type != 1.0 && type != 2.0)
  {
    why = "the type must be 0 (directional), 1 (point) or 2 (spot)";
    return false;
  }
  if (values[7] < 0 || values[8] < 0 || values[9] < 0 || values[10] < 0)
  {
    why = "colour and intensity must be >= 0";
    return false;
  }
  if (type == 2.0 && (values[11] <= 0 || values[11] >= 90))
  {
    why = "a spot light's cone angle must be in (0, 90) degrees (90 and above is a point light)";
    return false;
  }
  if (values[1] == values[4] && values[2] == values[5] && values[3] == values[6] && type != 1.0)
  {
    why = "the position and the focal point coincide, so the light has no direction";
    return false;
  }
  return true;
}
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLightList::SetLight(int index, double type, double px, double py, double pz,
  double fx, double fy, double fz, double r, double g, double b, double intensity, double coneAngle)
{
  if (index < 0 || index > 1023)
  {
    vtkErrorMacro("SetLight: light index " << index << " is out of range [0, 1023].");
    return;
  }
  while (static_cast<int>(this->Lights.size()) <= index)
  {
    vtkNew<vtkLight> light;
    light->SwitchOff();
    this->Lights.emplace_back(light);
  }
  const double row[LIGHT_VALUES] = { type, px, py, pz, fx, fy, fz, r, g, b, intensity, coneAngle };
  vtkLight* light = this->Lights[index];
  std::string why;
  if (!CheckRow(row, why))
  {
    vtkErrorMacro("Light " << index << " is switched off: " << why
                           << ". A light row is: type (0 directional, 1 point, 2 spot), position "
                              "x y z, focal point x y z, colour r g b, intensity, cone angle.");
    light->SwitchOff();
    this->Modified();
    return;
  }
  light->SwitchOn();
  light->SetPositional(type != DIRECTIONAL);
  light->SetPosition(px, py, pz);
  light->SetFocalPoint(fx, fy, fz);
  light->SetColor(r, g, b);
  light->SetIntensity(intensity);
  // A point light radiates in every direction: VTK's positional light with a 180 degree cone.
  light->SetConeAngle(type == SPOT ? coneAngle : 180.0);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLightList::RemoveAllLights()
{
  if (!this->Lights.empty())
  {
    this->Lights.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkLightCollection> vtkRefractaPluginLightList::GetLights() const
{
  auto lights = vtkSmartPointer<vtkLightCollection>::New();
  for (const auto& light : this->Lights)
  {
    lights->AddItem(light);
  }
  return lights;
}

//------------------------------------------------------------------------------
vtkLight* vtkRefractaPluginLightList::GetLight(int index) const
{
  return index >= 0 && index < this->GetNumberOfLights() ? this->Lights[index].Get() : nullptr;
}

//------------------------------------------------------------------------------
void vtkRefractaPluginLightList::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfLights: " << this->Lights.size() << "\n";
  for (size_t i = 0; i < this->Lights.size(); ++i)
  {
    vtkLight* l = this->Lights[i];
    const double* p = l->GetPosition();
    const double* f = l->GetFocalPoint();
    os << indent << "Light " << i << ": " << (l->GetSwitch() ? "on" : "off")
       << (l->GetPositional() ? " positional" : " directional") << " position (" << p[0] << ", "
       << p[1] << ", " << p[2] << ") focal point (" << f[0] << ", " << f[1] << ", " << f[2]
       << ") intensity " << l->GetIntensity() << " cone " << l->GetConeAngle() << "\n";
  }
}
