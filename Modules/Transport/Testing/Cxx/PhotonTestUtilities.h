// Helpers shared by the photon tracer tests: media built voxel by voxel, lights, field data.
#ifndef PhotonTestUtilities_h
#define PhotonTestUtilities_h

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkSmartPointer.h"

#include <array>
#include <functional>
#include <string>

namespace photontest
{
struct Voxel
{
  double N = 1.0;
  std::array<double, 3> Extinction{ 0, 0, 0 };
  std::array<double, 3> Albedo{ 0, 0, 0 };
};

// A medium whose arrays are given by f(x, y, z) at the voxel centres (grid-local coordinates).
inline vtkSmartPointer<vtkImageData> MakeMedium(int nx, int ny, int nz, double spacing,
  const std::function<Voxel(double, double, double)>& f, bool withN = true)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(spacing, spacing, spacing);
  vtkNew<vtkFloatArray> n, e, a;
  n->SetName("RefractiveIndex");
  e->SetName("Extinction");
  e->SetNumberOfComponents(3);
  a->SetName("Albedo");
  a->SetNumberOfComponents(3);
  const vtkIdType count = static_cast<vtkIdType>(nx) * ny * nz;
  n->SetNumberOfTuples(count);
  e->SetNumberOfTuples(count);
  a->SetNumberOfTuples(count);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const vtkIdType id = i + static_cast<vtkIdType>(nx) * (j + static_cast<vtkIdType>(ny) * k);
        const Voxel v = f(i * spacing, j * spacing, k * spacing);
        n->SetValue(id, static_cast<float>(v.N));
        e->SetTuple(id, v.Extinction.data());
        a->SetTuple(id, v.Albedo.data());
      }
    }
  }
  if (withN)
  {
    image->GetPointData()->AddArray(n);
  }
  image->GetPointData()->AddArray(e);
  image->GetPointData()->AddArray(a);
  return image;
}

inline vtkSmartPointer<vtkLight> Directional(std::array<double, 3> from, std::array<double, 3> to,
  double intensity, std::array<double, 3> colour = { 1, 1, 1 })
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(false);
  light->SetPosition(from.data());
  light->SetFocalPoint(to.data());
  light->SetIntensity(intensity);
  light->SetDiffuseColor(colour.data());
  return light;
}

inline vtkSmartPointer<vtkLight> Positional(std::array<double, 3> at, std::array<double, 3> to,
  double coneAngle, double exponent, double intensity, std::array<double, 3> colour = { 1, 1, 1 })
{
  auto light = vtkSmartPointer<vtkLight>::New();
  light->SetPositional(true);
  light->SetPosition(at.data());
  light->SetFocalPoint(to.data());
  light->SetConeAngle(coneAngle);
  light->SetExponent(exponent);
  light->SetIntensity(intensity);
  light->SetDiffuseColor(colour.data());
  return light;
}

inline double Field(vtkImageData* image, const char* name, int component = 0)
{
  vtkDataArray* a = image->GetFieldData()->GetArray(name);
  return a ? a->GetComponent(0, component) : -1e300;
}

inline std::array<double, 3> Energy(vtkImageData* image, const char* name)
{
  return { Field(image, name, 0), Field(image, name, 1), Field(image, name, 2) };
}

inline const float* Radiance(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(
    image->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceName()))
    ->GetPointer(0);
}

inline const float* Direction(vtkImageData* image)
{
  return vtkFloatArray::SafeDownCast(
    image->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceDirectionName()))
    ->GetPointer(0);
}
}

#endif
// VTK-HeaderTest-Exclude: PhotonTestUtilities.h
