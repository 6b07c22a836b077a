// Tests of vtkMediumValidator and vtkRefractaMedium: every kind of bad medium is rejected with a
// message naming the array, the voxel and the value; a good medium passes.
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace
{
constexpr int Nx = 4, Ny = 5, Nz = 6;

vtkIdType PointId(int i, int j, int k)
{
  return i + Nx * (j + Ny * k);
}

// A valid medium with every array, filled with in-range values that vary per voxel.
vtkSmartPointer<vtkImageData> MakeMedium()
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(Nx, Ny, Nz);
  image->SetSpacing(0.5, 0.25, 1.0);
  image->SetOrigin(-1, -1, -1);
  for (int id = 0; id < vtkRefractaMedium::NUMBER_OF_ARRAYS; ++id)
  {
    vtkNew<vtkFloatArray> array;
    array->SetName(vtkRefractaMedium::GetArrayName(id));
    array->SetNumberOfComponents(vtkRefractaMedium::GetNumberOfComponents(id));
    array->SetNumberOfTuples(image->GetNumberOfPoints());
    for (vtkIdType v = 0; v < array->GetNumberOfValues(); ++v)
    {
      const double t = (v % 7) / 7.0; // in [0, 1)
      double value = 0.0;
      switch (id)
      {
        case vtkRefractaMedium::REFRACTIVE_INDEX:
          value = 1.0 + 0.5 * t;
          break;
        case vtkRefractaMedium::REFRACTIVE_INDEX_GRADIENT:
          value = t - 0.5;
          break;
        case vtkRefractaMedium::ANISOTROPY:
          value = 1.8 * t - 0.9;
          break;
        default:
          value = t;
      }
      array->SetValue(v, static_cast<float>(value));
    }
    image->GetPointData()->AddArray(array);
  }
  return image;
}

void SetValue(vtkImageData* image, const char* name, vtkIdType point, int comp, double value)
{
  vtkDataArray* array = image->GetPointData()->GetArray(name);
  array->SetComponent(point, comp, value);
  array->Modified(); // VTK's contract for writes that other objects must notice
}

std::string Validate(vtkImageData* image, bool expectValid = false)
{
  vtkNew<vtkMediumValidator> validator;
  const bool valid = validator->Validate(image);
  EXPECT_EQ(valid, expectValid) << validator->GetErrorMessage();
  EXPECT_EQ(valid, validator->GetNumberOfErrors() == 0);
  return validator->GetErrorMessage();
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}
}

TEST(RefractaMedium, ConventionsMatchSpec)
{
  EXPECT_STREQ(vtkRefractaMedium::GetArrayName(vtkRefractaMedium::EXTINCTION), "Extinction");
  EXPECT_EQ(vtkRefractaMedium::GetArrayId("RefractiveIndexGradient"),
    vtkRefractaMedium::REFRACTIVE_INDEX_GRADIENT);
  EXPECT_EQ(vtkRefractaMedium::GetArrayId("Density"), -1);
  EXPECT_EQ(vtkRefractaMedium::GetArrayName(99), nullptr);
  const int comps[] = { 1, 3, 3, 3, 1, 3, 1 };
  for (int id = 0; id < vtkRefractaMedium::NUMBER_OF_ARRAYS; ++id)
  {
    EXPECT_EQ(vtkRefractaMedium::GetNumberOfComponents(id), comps[id]) << id;
  }
  EXPECT_EQ(vtkRefractaMedium::GetDefaultValue(vtkRefractaMedium::REFRACTIVE_INDEX), 1.0);
  EXPECT_EQ(vtkRefractaMedium::GetDefaultValue(vtkRefractaMedium::OCCUPANCY), 1.0);
  EXPECT_EQ(vtkRefractaMedium::GetDefaultValue(vtkRefractaMedium::EXTINCTION), 0.0);
  EXPECT_FALSE(vtkRefractaMedium::IsValueValid(vtkRefractaMedium::ANISOTROPY, 1.0));
  EXPECT_TRUE(vtkRefractaMedium::IsValueValid(vtkRefractaMedium::ANISOTROPY, 0.999));
  EXPECT_TRUE(vtkRefractaMedium::IsValueValid(vtkRefractaMedium::ALBEDO, 1.0));
  EXPECT_FALSE(vtkRefractaMedium::IsValueValid(vtkRefractaMedium::REFRACTIVE_INDEX, 0.99));
  EXPECT_TRUE(vtkRefractaMedium::IsValueValid(vtkRefractaMedium::REFRACTIVE_INDEX, 100.0));
  EXPECT_FALSE(vtkRefractaMedium::IsValueValid(vtkRefractaMedium::REFRACTIVE_INDEX, 100.5));
}

// A clear voxel (no extinction) next to scattering ones takes their extinction-weighted albedo,
// per channel, in a new array (the input's is not written); a clear voxel with no scattering
// neighbour, and every voxel with extinction, keeps its own.
TEST(RefractaMedium, FillAlbedoWithoutExtinction)
{
  vtkNew<vtkImageData> medium;
  medium->SetDimensions(4, 1, 1);
  vtkNew<vtkFloatArray> sigma, albedo;
  sigma->SetName(vtkRefractaMedium::ExtinctionName());
  albedo->SetName(vtkRefractaMedium::AlbedoName());
  for (vtkFloatArray* a : { sigma.Get(), albedo.Get() })
  {
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(4);
    medium->GetPointData()->AddArray(a);
  }
  // Voxels 0, 1 clear; 2: sigma 2, albedo 1; 3: sigma 6, albedo 0.5. Channel 2 of voxel 2 clear.
  const float s[4][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 2, 2, 0 }, { 6, 6, 6 } };
  const float a[4][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 1, 1, 1 }, { 0.5f, 0.5f, 0.5f } };
  for (int v = 0; v < 4; ++v)
  {
    sigma->SetTypedTuple(v, s[v]);
    albedo->SetTypedTuple(v, a[v]);
  }
  EXPECT_EQ(vtkRefractaMedium::FillAlbedoWithoutExtinction(medium), 3);
  auto* filled =
    vtkFloatArray::SafeDownCast(medium->GetPointData()->GetArray(vtkRefractaMedium::AlbedoName()));
  ASSERT_NE(filled, albedo.Get());
  EXPECT_EQ(albedo->GetValue(3), 0.0f);               // the input's array is untouched
  EXPECT_EQ(filled->GetComponent(0, 0), 0.0);         // no scattering neighbour
  EXPECT_NEAR(filled->GetComponent(1, 0), 1.0, 1e-7); // voxel 2 alone
  EXPECT_NEAR(filled->GetComponent(2, 2), 0.5, 1e-7); // voxel 3 alone (channel 2)
  EXPECT_NEAR(filled->GetComponent(2, 0), 1.0, 1e-7); // has extinction: its own
  EXPECT_NEAR(filled->GetComponent(3, 1), 0.5, 1e-7);
  // Nothing to do: a second call changes nothing, nor does a medium without extinction.
  EXPECT_EQ(vtkRefractaMedium::FillAlbedoWithoutExtinction(medium), 0);
  sigma->Fill(0.0);
  EXPECT_EQ(vtkRefractaMedium::FillAlbedoWithoutExtinction(medium), 0);
  EXPECT_EQ(vtkRefractaMedium::FillAlbedoWithoutExtinction(nullptr), 0);
}

TEST(MediumValidator, AcceptsGoodMedium)
{
  auto image = MakeMedium();
  Validate(image, true);
  // Optional arrays may be missing, and double arrays are as good as float ones.
  image->GetPointData()->RemoveArray("Anisotropy");
  image->GetPointData()->RemoveArray("Emission");
  vtkNew<vtkDoubleArray> n;
  n->DeepCopy(image->GetPointData()->GetArray("RefractiveIndex"));
  image->GetPointData()->AddArray(n);
  Validate(image, true);
  // A single voxel is a valid (if small) medium.
  vtkNew<vtkImageData> one;
  one->SetDimensions(1, 1, 1);
  vtkNew<vtkFloatArray> ext;
  ext->SetName("Extinction");
  ext->SetNumberOfComponents(3);
  ext->SetNumberOfTuples(1);
  ext->Fill(2.0);
  one->GetPointData()->AddArray(ext);
  Validate(one, true);
}

TEST(MediumValidator, RejectsNaNAndInfinity)
{
  auto image = MakeMedium();
  SetValue(image, "Extinction", PointId(1, 2, 3), 2, std::numeric_limits<double>::quiet_NaN());
  const std::string msg = Validate(image);
  EXPECT_TRUE(Contains(msg, "'Extinction'")) << msg;
  EXPECT_TRUE(Contains(msg, "voxel (1, 2, 3)")) << msg;
  EXPECT_TRUE(Contains(msg, "component 2")) << msg;
  EXPECT_TRUE(Contains(msg, "nan")) << msg;

  image = MakeMedium();
  SetValue(image, "RefractiveIndex", PointId(3, 4, 5), 0, std::numeric_limits<double>::infinity());
  const std::string inf = Validate(image);
  EXPECT_TRUE(Contains(inf, "'RefractiveIndex'") && Contains(inf, "voxel (3, 4, 5)")) << inf;
  EXPECT_TRUE(Contains(inf, "inf")) << inf;
}

// A passed value scan is remembered by array and modification time: a second validation of the
// same arrays passes, and a value written afterwards (with Modified(), as VTK requires) is caught,
// also for a new validator, an array of another role and a replaced array.
TEST(MediumValidator, RescansArraysChangedSinceTheyPassed)
{
  auto image = MakeMedium();
  Validate(image, true);
  Validate(image, true);
  SetValue(image, "Albedo", PointId(2, 1, 0), 1, 1.5);
  const std::string msg = Validate(image);
  EXPECT_TRUE(Contains(msg, "'Albedo'") && Contains(msg, "voxel (2, 1, 0)")) << msg;

  image = MakeMedium();
  Validate(image, true);
  vtkNew<vtkFloatArray> replaced;
  replaced->DeepCopy(image->GetPointData()->GetArray("Extinction"));
  replaced->SetValue(5, -1.0f);
  image->GetPointData()->AddArray(replaced); // same name: replaces the one that passed
  EXPECT_TRUE(Contains(Validate(image), "'Extinction'"));
}

TEST(MediumValidator, RejectsOutOfRangeValues)
{
  struct Case
  {
    const char* Array;
    int Component;
    double Value;
    const char* Rule;
  };
  const Case cases[] = {
    { "Extinction", 0, -0.5, ">= 0" },
    { "Emission", 1, -1e-3, ">= 0" },
    { "RefractiveIndex", 0, 0.9, "[1, 100]" },
    { "RefractiveIndex", 0, 1e30, "[1, 100]" },
    { "Albedo", 1, 1.2, "[0, 1]" },
    { "Albedo", 0, -0.1, "[0, 1]" },
    { "Anisotropy", 0, 1.0, "(-1, 1)" },
    { "Anisotropy", 0, -1.5, "(-1, 1)" },
    { "Occupancy", 0, 1.01, "[0, 1]" },
  };
  for (const Case& c : cases)
  {
    auto image = MakeMedium();
    SetValue(image, c.Array, PointId(2, 0, 1), c.Component, c.Value);
    SetValue(image, c.Array, PointId(3, 3, 3), c.Component, c.Value);
    const std::string msg = Validate(image);
    EXPECT_TRUE(Contains(msg, std::string("'") + c.Array + "'")) << msg;
    EXPECT_TRUE(Contains(msg, "has 2 invalid value(s)")) << msg;
    EXPECT_TRUE(Contains(msg, "voxel (2, 0, 1)")) << msg;
    EXPECT_TRUE(Contains(msg, c.Rule)) << msg;
  }
}

TEST(MediumValidator, RejectsWrongLayout)
{
  auto image = MakeMedium();
  vtkNew<vtkFloatArray> oneComponent;
  oneComponent->SetName("Albedo");
  oneComponent->SetNumberOfTuples(image->GetNumberOfPoints());
  oneComponent->Fill(0.5);
  image->GetPointData()->AddArray(oneComponent);
  std::string msg = Validate(image);
  EXPECT_TRUE(Contains(msg, "'Albedo' has 1 component(s); it must have 3")) << msg;

  image = MakeMedium();
  vtkNew<vtkFloatArray> shortArray;
  shortArray->SetName("RefractiveIndex");
  shortArray->SetNumberOfTuples(7);
  shortArray->Fill(1.0);
  image->GetPointData()->AddArray(shortArray);
  msg = Validate(image);
  EXPECT_TRUE(Contains(msg, "has 7 tuples but the grid has 120 points")) << msg;

  image = MakeMedium();
  vtkNew<vtkStringArray> text;
  text->SetName("Occupancy");
  text->SetNumberOfValues(image->GetNumberOfPoints());
  image->GetPointData()->AddArray(text);
  msg = Validate(image);
  EXPECT_TRUE(Contains(msg, "'Occupancy' is a vtkStringArray")) << msg;

  image = MakeMedium();
  vtkNew<vtkFloatArray> cells;
  cells->SetName("Emission");
  cells->SetNumberOfComponents(3);
  cells->SetNumberOfTuples(image->GetNumberOfCells());
  cells->Fill(0.0);
  image->GetPointData()->RemoveArray("Emission");
  image->GetCellData()->AddArray(cells);
  msg = Validate(image);
  EXPECT_TRUE(Contains(msg, "'Emission' is cell data")) << msg;
}

TEST(MediumValidator, RejectsDegenerateGrids)
{
  EXPECT_TRUE(Contains(Validate(nullptr), "null"));

  vtkNew<vtkImageData> empty;
  EXPECT_TRUE(Contains(Validate(empty), "empty"));

  auto image = MakeMedium();
  image->SetSpacing(1.0, 0.0, 1.0);
  EXPECT_TRUE(Contains(Validate(image), "axis 1"));
  image->SetSpacing(1.0, 1.0, -2.0);
  EXPECT_TRUE(Contains(Validate(image), "axis 2"));
  image->SetSpacing(1.0, 1.0, std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(Contains(Validate(image), "finite and > 0"));
  // Outside the float arithmetic's range (the photon pass deposited nothing at 1e-16).
  image->SetSpacing(1e-16, 1e-16, 1e-16);
  EXPECT_TRUE(Contains(Validate(image), "other units"));
  image->SetSpacing(1.0, 1e19, 1.0);
  EXPECT_TRUE(Contains(Validate(image), "axis 1"));
  image->SetSpacing(1e-12, 1e-12, 1e-12);
  Validate(image, true);
  image->SetSpacing(1.0, 1.0, 1.0);
  image->SetOrigin(0.0, std::numeric_limits<double>::infinity(), 0.0);
  EXPECT_TRUE(Contains(Validate(image), "origin"));
  image->SetOrigin(1e6, 1e6, 1e6); // far from the origin is fine
  Validate(image, true);
  image->SetDirectionMatrix(1, 0, 0, 1, 0, 0, 0, 0, 1);
  EXPECT_TRUE(Contains(Validate(image), "direction matrix"));
  // Non-singular but not orthonormal (a scale belongs in the spacing).
  image->SetDirectionMatrix(2, 0, 0, 0, 1, 0, 0, 0, 1);
  EXPECT_TRUE(Contains(Validate(image), "not orthonormal"));
}

TEST(MediumValidator, RejectsImageWithoutMediumArrays)
{
  vtkNew<vtkImageData> ct;
  ct->SetDimensions(3, 3, 3);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetName("Density");
  scalars->SetNumberOfTuples(27);
  scalars->Fill(1.0);
  ct->GetPointData()->SetScalars(scalars);
  EXPECT_TRUE(Contains(Validate(ct), "none of the medium point arrays"));

  vtkNew<vtkMediumValidator> lenient;
  lenient->RequireMediumArrayOff();
  EXPECT_TRUE(lenient->Validate(ct));
}

TEST(MediumValidator, ReportsEveryBadArray)
{
  auto image = MakeMedium();
  SetValue(image, "Albedo", 0, 0, 2.0);
  SetValue(image, "Anisotropy", 5, 0, 1.0);
  vtkNew<vtkMediumValidator> validator;
  EXPECT_FALSE(validator->Validate(image));
  EXPECT_EQ(validator->GetNumberOfErrors(), 2);
  EXPECT_TRUE(Contains(validator->GetError(0), "'Albedo'"));
  EXPECT_TRUE(Contains(validator->GetError(1), "'Anisotropy'"));
  EXPECT_EQ(validator->GetError(2), nullptr);
}

// Every light pass checks its lights with CheckLight: a light that cannot emit is named, and an
// ordinary one passes.
TEST(MediumValidator, ChecksLights)
{
  vtkNew<vtkLight> light;
  light->SetPosition(1, 2, 3);
  light->SetIntensity(0.5);
  std::string error;
  EXPECT_TRUE(vtkMediumValidator::CheckLight(light, 0, error)) << error;
  EXPECT_TRUE(error.empty());

  light->SetPosition(std::nan(""), 2, 3);
  EXPECT_FALSE(vtkMediumValidator::CheckLight(light, 4, error));
  EXPECT_NE(error.find("Light 4"), std::string::npos) << error;
  EXPECT_NE(error.find("non-finite"), std::string::npos) << error;

  light->SetPosition(1, 2, 3);
  light->SetIntensity(-1.0);
  error.clear();
  EXPECT_FALSE(vtkMediumValidator::CheckLight(light, 1, error));
  EXPECT_NE(error.find(">= 0"), std::string::npos) << error;

  light->SetIntensity(1.0);
  light->SetDiffuseColor(1.0, -0.1, 1.0);
  error.clear();
  EXPECT_FALSE(vtkMediumValidator::CheckLight(light, 1, error));
}
