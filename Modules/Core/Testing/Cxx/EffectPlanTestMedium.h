// The effect-plan tests' media: a box of voxels whose values a function of (i, j, k) sets.
#ifndef EffectPlanTestMedium_h
#define EffectPlanTestMedium_h

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <functional>

namespace refracta_test
{
// A box of nx x ny x nz voxels of the given spacing; fill(i, j, k) gives each voxel's values.
struct Voxel
{
  double N = 1.0;
  double SigmaT = 0.0;
  double Albedo = 0.0;
  double Emission = 0.0;
  double Anisotropy = 0.0;
};

inline vtkSmartPointer<vtkImageData> MakeMedium(
  int nx, int ny, int nz, double spacing, const std::function<Voxel(int, int, int)>& fill)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(spacing, spacing, spacing);
  auto make = [&](const char* name, int comps)
  {
    vtkNew<vtkFloatArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(comps);
    a->SetNumberOfTuples(image->GetNumberOfPoints());
    image->GetPointData()->AddArray(a);
    return a.GetPointer();
  };
  vtkFloatArray* n = make("RefractiveIndex", 1);
  vtkFloatArray* ext = make("Extinction", 3);
  vtkFloatArray* alb = make("Albedo", 3);
  vtkFloatArray* emi = make("Emission", 3);
  vtkFloatArray* ani = make("Anisotropy", 1);
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const vtkIdType p = i + nx * (j + ny * k);
        const Voxel v = fill(i, j, k);
        n->SetValue(p, v.N);
        ani->SetValue(p, v.Anisotropy);
        for (int c = 0; c < 3; ++c)
        {
          ext->SetComponent(p, c, v.SigmaT);
          alb->SetComponent(p, c, v.Albedo);
          emi->SetComponent(p, c, v.Emission);
        }
      }
    }
  }
  return image;
}
} // namespace refracta_test

#endif
