// Tests of vtkMediumMaterial: defaults, clamping to the valid ranges, derived quantities.
#include "vtkCommand.h"
#include "vtkMediumMaterial.h"
#include "vtkNew.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>

TEST(MediumMaterial, DefaultsAreVacuum)
{
  vtkNew<vtkMediumMaterial> m;
  EXPECT_EQ(m->GetRefractiveIndex(), 1.0);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_EQ(m->GetExtinction()[c], 0.0);
    EXPECT_EQ(m->GetAlbedo()[c], 0.0);
    EXPECT_EQ(m->GetEmission()[c], 0.0);
  }
  EXPECT_EQ(m->GetAnisotropy(), 0.0);
}

TEST(MediumMaterial, SettersClampToValidRanges)
{
  vtkNew<vtkMediumMaterial> m;
  m->SetRefractiveIndex(0.5);
  EXPECT_EQ(m->GetRefractiveIndex(), 1.0);
  m->SetRefractiveIndex(2.4);
  EXPECT_EQ(m->GetRefractiveIndex(), 2.4);
  m->SetExtinction(-1.0, 2.0, 1e40);
  EXPECT_EQ(m->GetExtinction()[0], 0.0);
  EXPECT_EQ(m->GetExtinction()[1], 2.0);
  EXPECT_EQ(m->GetExtinction()[2], vtkMediumMaterial::MaximumCoefficient);
  m->SetAlbedo(1.5, 0.25, -3.0);
  EXPECT_EQ(m->GetAlbedo()[0], 1.0);
  EXPECT_EQ(m->GetAlbedo()[1], 0.25);
  EXPECT_EQ(m->GetAlbedo()[2], 0.0);
  m->SetAnisotropy(1.0);
  EXPECT_LT(m->GetAnisotropy(), 1.0);
  EXPECT_GE(m->GetAnisotropy(), 0.999);
  m->SetAnisotropy(-7.0);
  EXPECT_GT(m->GetAnisotropy(), -1.0);
  m->SetEmission(-1, 0, 3);
  EXPECT_EQ(m->GetEmission()[0], 0.0);
  EXPECT_EQ(m->GetEmission()[2], 3.0);
}

// NaN values (and infinite colour channels) are errors that name the property and leave it
// unchanged (clamping NaN to a bound, as before, silently turned a broken computation into a
// plausible material).
TEST(MediumMaterial, NonFiniteValuesAreRejected)
{
  vtkNew<vtkMediumMaterial> m;
  m->SetRefractiveIndex(1.5);
  m->SetExtinction(1, 2, 3);
  m->SetAnisotropy(0.3);
  vtkNew<vtkTest::ErrorObserver> errors;
  m->AddObserver(vtkCommand::ErrorEvent, errors);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  m->SetRefractiveIndex(nan);
  EXPECT_EQ(m->GetRefractiveIndex(), 1.5);
  EXPECT_NE(errors->GetErrorMessage().find("SetRefractiveIndex(nan)"), std::string::npos)
    << errors->GetErrorMessage();
  errors->Clear();
  m->SetExtinction(1, inf, 3);
  EXPECT_EQ(m->GetExtinction()[1], 2.0);
  EXPECT_NE(errors->GetErrorMessage().find("finite"), std::string::npos);
  errors->Clear();
  m->SetAnisotropy(nan);
  EXPECT_EQ(m->GetAnisotropy(), 0.3);
  EXPECT_TRUE(errors->GetError());
  errors->Clear();
  m->SetAnisotropy(-inf); // a range's end: clamped, as vtkSetClampMacro does
  EXPECT_EQ(m->GetAnisotropy(), -0.9999);
  EXPECT_FALSE(errors->GetError());
  errors->Clear();
  m->SetEmission(nan, 0, 0);
  m->SetAlbedo(0, nan, 0);
  EXPECT_NE(errors->GetErrorMessage().find("SetEmission"), std::string::npos);
  EXPECT_NE(errors->GetErrorMessage().find("SetAlbedo"), std::string::npos);
  EXPECT_EQ(m->GetEmission()[0], 0.0);
}

TEST(MediumMaterial, ScatteringAndCopy)
{
  vtkNew<vtkMediumMaterial> m;
  m->SetExtinction(2.0, 4.0, 8.0);
  m->SetAlbedo(0.5, 0.25, 1.0);
  double s[3];
  m->GetScattering(s);
  EXPECT_DOUBLE_EQ(s[0], 1.0);
  EXPECT_DOUBLE_EQ(s[1], 1.0);
  EXPECT_DOUBLE_EQ(s[2], 8.0);

  vtkNew<vtkMediumMaterial> copy;
  const vtkMTimeType before = copy->GetMTime();
  copy->DeepCopy(m);
  EXPECT_GT(copy->GetMTime(), before);
  EXPECT_EQ(copy->GetExtinction()[2], 8.0);
  EXPECT_EQ(copy->GetAlbedo()[1], 0.25);

  // Setting an equal value must not bump the modification time (pipelines would re-execute).
  const vtkMTimeType after = copy->GetMTime();
  copy->SetExtinction(2.0, 4.0, 8.0);
  EXPECT_EQ(copy->GetMTime(), after);

  std::ostringstream printed;
  m->Print(printed);
  EXPECT_NE(printed.str().find("Extinction: (2, 4, 8)"), std::string::npos);
}
