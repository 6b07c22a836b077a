// Tests of vtkMediumMaterial's density fields: an implicit function and an image array scale
// extinction and emission (and n - 1 when asked), trilinear interpolation is exact for a linear
// field, and an unusable image is reported instead of evaluated.
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMediumMaterial.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <string>

TEST(MediumMaterialDensity, HomogeneousIsOne)
{
  vtkNew<vtkMediumMaterial> m;
  const double x[3] = { 3, -2, 7 };
  EXPECT_FALSE(m->IsHeterogeneous());
  EXPECT_EQ(m->EvaluateDensity(x), 1.0);
}

TEST(MediumMaterialDensity, ImplicitFunctionScalesExtinctionAndEmission)
{
  vtkNew<vtkMediumMaterial> m;
  m->SetRefractiveIndex(1.5);
  m->SetExtinction(1, 2, 3);
  m->SetAlbedo(0.5, 0.5, 0.5);
  m->SetEmission(4, 5, 6);
  m->SetAnisotropy(0.25);
  vtkNew<vtkPlane> plane; // f(x) = x (normal +x through the origin)
  plane->SetOrigin(0, 0, 0);
  plane->SetNormal(1, 0, 0);
  m->SetDensityFunction(plane);
  EXPECT_TRUE(m->IsHeterogeneous());
  const double x[3] = { 0.25, 9, 9 };
  const double d = m->EvaluateDensity(x);
  EXPECT_DOUBLE_EQ(d, 0.25);
  const double xneg[3] = { -1, 0, 0 };
  EXPECT_EQ(m->EvaluateDensity(xneg), 0.0); // negative density counts as 0
  double n, ext[3], alb[3], g, em[3];
  m->GetPropertiesAtDensity(d, n, ext, alb, g, em);
  EXPECT_DOUBLE_EQ(n, 1.5); // n unaffected by default
  EXPECT_DOUBLE_EQ(ext[2], 0.75);
  EXPECT_DOUBLE_EQ(em[0], 1.0);
  EXPECT_DOUBLE_EQ(alb[1], 0.5);
  EXPECT_DOUBLE_EQ(g, 0.25);
  m->DensityScalesRefractiveIndexOn();
  m->GetPropertiesAtDensity(d, n, ext, alb, g, em);
  EXPECT_DOUBLE_EQ(n, 1.125); // Gladstone-Dale: 1 + 0.25 * 0.5
}

TEST(MediumMaterialDensity, ImageArrayIsTrilinear)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(5, 4, 3);
  image->SetOrigin(-1, 0, 2);
  image->SetSpacing(0.5, 1, 2);
  vtkNew<vtkFloatArray> rho;
  rho->SetName("rho");
  rho->SetNumberOfTuples(image->GetNumberOfPoints());
  for (vtkIdType id = 0; id < image->GetNumberOfPoints(); ++id)
  {
    double p[3];
    image->GetPoint(id, p);
    rho->SetValue(id, static_cast<float>(1 + p[0] + 2 * p[1] + 0.5 * p[2])); // linear, >= 0
  }
  image->GetPointData()->AddArray(rho);
  vtkNew<vtkMediumMaterial> m;
  m->SetDensityImage(image);
  std::string why;
  EXPECT_FALSE(m->CheckDensity(why)); // no array name yet
  EXPECT_NE(why.find("DensityArrayName"), std::string::npos);
  m->SetDensityArrayName("nope");
  EXPECT_FALSE(m->CheckDensity(why));
  EXPECT_NE(why.find("nope"), std::string::npos);
  m->SetDensityArrayName("rho");
  EXPECT_TRUE(m->CheckDensity(why)) << why;
  const double x[3] = { -0.3, 1.7, 4.9 };
  EXPECT_NEAR(m->EvaluateDensity(x), 1 - 0.3 + 3.4 + 2.45, 1e-5);
  const double outside[3] = { 5, 1, 3 };
  EXPECT_EQ(m->EvaluateDensity(outside), 0.0);
}
