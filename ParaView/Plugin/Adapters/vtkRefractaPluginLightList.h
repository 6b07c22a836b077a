/**
 * @class   vtkRefractaPluginLightList
 * @brief   vtkLights built from flat numbers, so that ParaView properties can describe lights.
 *
 * A ParaView property is a list of numbers; a light here is one row of LIGHT_VALUES numbers,
 * set by SetLight(index, ...) (the XML's repeat_command with use_index) and cleared by
 * RemoveAllLights(). The row, in world units:
 *   type (0 directional, 1 point, 2 spot), position (x, y, z), focal point (x, y, z),
 *   colour (r, g, b, linear, each >= 0), intensity (>= 0), spot cone half angle (degrees, in (0,
 * 90); ignored for the other types). A directional light shines from its position towards its focal
 * point (only the direction counts); a point light sits at its position; a spot light sits at its
 * position, points at its focal point and lights a cone of the given half angle. Intensity x colour
 * is read as vtkRefractaRenderPipeline reads a light (RADIOMETRIC_LIGHT_UNITS: irradiance in W m^-2
 * for a directional light, radiant intensity in W sr^-1 for point and spot lights).
 *
 * Rows that are not finite or name an unknown type are reported (vtkErrorMacro naming the row
 * and what would be valid) and switched off. The lights are owned here; GetLights() hands them
 * to a vtkRefractaRenderPipeline or a vtkRefractaImageRenderer. Modified() on every change.
 */
#ifndef vtkRefractaPluginLightList_h
#define vtkRefractaPluginLightList_h

#include "RefractaParaViewAdaptersModule.h" // for export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // for members

#include <vector> // for std::vector

class vtkLight;
class vtkLightCollection;

class REFRACTAPARAVIEWADAPTERS_EXPORT vtkRefractaPluginLightList : public vtkObject
{
public:
  static vtkRefractaPluginLightList* New();
  vtkTypeMacro(vtkRefractaPluginLightList, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum LightTypes
  {
    DIRECTIONAL = 0,
    POINT = 1,
    SPOT = 2
  };

  /**
   * Numbers per light row (type, position 3, focal point 3, colour 3, intensity, cone angle).
   */
  static constexpr int LIGHT_VALUES = 12;

  /**
   * Set (or add) light `index` (0-based; rows in between are added switched off).
   */
  void SetLight(int index, double type, double px, double py, double pz, double fx, double fy,
    double fz, double r, double g, double b, double intensity, double coneAngle);

  /**
   * Remove every light.
   */
  void RemoveAllLights();

  /**
   * Number of light rows set.
   */
  int GetNumberOfLights() const { return static_cast<int>(this->Lights.size()); }

  /**
   * The lights (a new collection each call, holding this list's vtkLights).
   */
  vtkSmartPointer<vtkLightCollection> GetLights() const;

  /**
   * Light `index`, or nullptr.
   */
  vtkLight* GetLight(int index) const;

protected:
  vtkRefractaPluginLightList();
  ~vtkRefractaPluginLightList() override;

  std::vector<vtkSmartPointer<vtkLight>> Lights;

private:
  vtkRefractaPluginLightList(const vtkRefractaPluginLightList&) = delete;
  void operator=(const vtkRefractaPluginLightList&) = delete;
};

#endif
