// vtkTransferFunctionMedium: the mapping (Beer-Lambert extinction from opacity, albedo from
// colour, index, emission) on a small image, and every rejected input with its message. The
// rejected inputs were found by fuzzing (Testing/Fuzz/Corpus/FuzzTransferFunctionMedium): before,
// they gave NaN or infinite medium arrays.
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTestErrorObserver.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolumeProperty.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
const double NaN = std::numeric_limits<double>::quiet_NaN();

// A 2 x 2 x 2 image of scalars 0..7 / 7 and a property: opacity 0 -> 0, 1 -> 0.5; colour white
// to red; unit distance 0.5.
struct Fixture
{
  vtkNew<vtkImageData> Image;
  vtkNew<vtkPiecewiseFunction> Opacity;
  vtkNew<vtkColorTransferFunction> Colour;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkPiecewiseFunction> Index;
  vtkNew<vtkTransferFunctionMedium> Mapping;
  vtkNew<vtkTest::ErrorObserver> Observer;

  Fixture()
  {
    this->Image->SetDimensions(2, 2, 2);
    vtkNew<vtkDoubleArray> s;
    s->SetName("density");
    s->SetNumberOfTuples(8);
    for (int i = 0; i < 8; ++i)
    {
      s->SetValue(i, i / 7.0);
    }
    this->Image->GetPointData()->SetScalars(s);
    this->Opacity->AddPoint(0, 0);
    this->Opacity->AddPoint(1, 0.5);
    this->Colour->AddRGBPoint(0, 1, 1, 1);
    this->Colour->AddRGBPoint(1, 1, 0, 0);
    this->Property->SetScalarOpacity(this->Opacity);
    this->Property->SetColor(this->Colour);
    this->Property->SetScalarOpacityUnitDistance(0.5);
    this->Index->AddPoint(0, 1);
    this->Index->AddPoint(1, 1.5);
    this->Mapping->SetInputData(this->Image);
    this->Mapping->SetVolumeProperty(this->Property);
    this->Mapping->SetRefractiveIndexFunction(this->Index);
    this->Mapping->SetEmissionScale(1.0);
    this->Mapping->AddObserver(vtkCommand::ErrorEvent, this->Observer);
  }

  // Runs the mapping and expects it to fail with `message` and an empty output.
  void ExpectError(const std::string& message)
  {
    this->Mapping->Update();
    EXPECT_EQ(this->Observer->CheckErrorMessage(message), 0) << message;
    EXPECT_EQ(this->Mapping->GetOutput()->GetNumberOfPoints(), 0) << message;
  }
};
}

TEST(TransferFunctionMedium, MapsOpacityColourIndexAndEmission)
{
  Fixture f;
  f.Mapping->Update();
  EXPECT_FALSE(f.Observer->GetError()) << f.Observer->GetErrorMessage();
  vtkImageData* out = f.Mapping->GetOutput();
  vtkNew<vtkMediumValidator> validator;
  EXPECT_TRUE(validator->Validate(out)) << validator->GetErrorMessage();
  vtkPointData* pd = out->GetPointData();
  // The last point: s = 1, opacity 0.5 over 0.5 world units -> sigma = ln 2 / 0.5.
  const double sigma = std::log(2.0) / 0.5;
  EXPECT_NEAR(pd->GetArray(vtkRefractaMedium::ExtinctionName())->GetComponent(7, 0), sigma, 1e-6);
  EXPECT_NEAR(pd->GetArray(vtkRefractaMedium::AlbedoName())->GetComponent(7, 1), 0.0, 1e-6);
  EXPECT_NEAR(
    pd->GetArray(vtkRefractaMedium::RefractiveIndexName())->GetComponent(7, 0), 1.5, 1e-6);
  EXPECT_NEAR(pd->GetArray(vtkRefractaMedium::EmissionName())->GetComponent(7, 0), sigma, 1e-5);
  EXPECT_NEAR(pd->GetArray(vtkRefractaMedium::ExtinctionName())->GetComponent(0, 0), 0.0, 1e-9);
}

TEST(TransferFunctionMedium, BadUnitDistanceIsRejected)
{
  for (double unit : { 0.0, -1.0, NaN })
  {
    Fixture f;
    f.Property->SetScalarOpacityUnitDistance(unit);
    f.ExpectError("ScalarOpacityUnitDistance is");
  }
}

TEST(TransferFunctionMedium, NaNFromTheFunctionsIsRejected)
{
  {
    Fixture f;
    f.Opacity->AddPoint(0.5, NaN);
    f.ExpectError("the scalar opacity function is NaN at scalar");
  }
  {
    Fixture f;
    f.Colour->AddRGBPoint(0.5, NaN, 0, 0);
    f.ExpectError("the colour transfer function is NaN at scalar");
  }
  {
    Fixture f;
    f.Index->AddPoint(0.5, NaN);
    f.ExpectError("the refractive index function gives nan");
  }
  {
    Fixture f; // refused by the setter, which keeps g
    f.Mapping->SetAnisotropy(0.25);
    f.Mapping->SetAnisotropy(NaN);
    EXPECT_EQ(f.Observer->CheckErrorMessage("SetAnisotropy(nan): must be a number in [-0.9999"), 0);
    EXPECT_EQ(f.Mapping->GetAnisotropy(), 0.25);
  }
  {
    Fixture f;
    f.Index->AddPoint(0.5, 1e30);
    f.ExpectError("indices must be finite numbers in [1, 100]");
  }
}

TEST(TransferFunctionMedium, InfiniteScalarsAreRejected)
{
  Fixture f;
  vtkDataArray* scalars = f.Image->GetPointData()->GetScalars();
  scalars->SetComponent(3, 0, std::numeric_limits<double>::infinity());
  f.ExpectError("Cannot map the input scalar inf at point 3: every scalar must be finite");
}

// A NaN scalar is missing data: its voxel is empty space (extinction, albedo and emission 0,
// n = 1), the others map as before, and one warning counts them (one NaN blanked the whole
// volume with an error before; an outside review).
TEST(TransferFunctionMedium, NaNScalarsAreEmptySpace)
{
  Fixture f;
  vtkDataArray* scalars = f.Image->GetPointData()->GetScalars();
  scalars->SetComponent(3, 0, NaN);
  scalars->SetComponent(5, 0, NaN);
  vtkNew<vtkTest::ErrorObserver> warnings;
  f.Mapping->AddObserver(vtkCommand::WarningEvent, warnings);
  f.Mapping->Update();
  vtkImageData* out = f.Mapping->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), f.Image->GetNumberOfPoints());
  ASSERT_TRUE(warnings->GetWarning());
  EXPECT_NE(warnings->GetWarningMessage().find("2 of"), std::string::npos)
    << warnings->GetWarningMessage();
  EXPECT_NE(warnings->GetWarningMessage().find("are NaN (missing data)"), std::string::npos);
  vtkDataArray* extinction = out->GetPointData()->GetArray("Extinction");
  vtkDataArray* albedo = out->GetPointData()->GetArray("Albedo");
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_EQ(extinction->GetComponent(3, c), 0.0);
    EXPECT_EQ(albedo->GetComponent(5, c), 0.0);
  }
  if (vtkDataArray* index = out->GetPointData()->GetArray("RefractiveIndex"))
  {
    EXPECT_EQ(index->GetComponent(3, 0), 1.0);
  }
  // A neighbour with a finite scalar keeps its mapping.
  EXPECT_GT(extinction->GetComponent(4, 0) + extinction->GetComponent(2, 0), 0.0);
}

// The mapping runs in parallel blocks: with two bad scalars far apart, the error still names the
// first one in index order (what a serial loop reports).
TEST(TransferFunctionMedium, TheFirstBadScalarIsReported)
{
  Fixture f;
  f.Image->SetDimensions(64, 64, 64);
  vtkNew<vtkDoubleArray> s;
  s->SetName("density");
  s->SetNumberOfTuples(64 * 64 * 64);
  s->Fill(0.5);
  s->SetValue(200000, -std::numeric_limits<double>::infinity());
  s->SetValue(50000, std::numeric_limits<double>::infinity());
  f.Image->GetPointData()->SetScalars(s);
  f.ExpectError("Cannot map the input scalar inf at point 50000: every scalar must be finite");
}

// Neighbours with equal scalars reuse one evaluation of the functions: every voxel must still
// get its own scalar's values (opacity 0.5 s over the unit distance 0.5, colour (1, 1 - s, 1 - s)).
TEST(TransferFunctionMedium, RunsOfEqualScalarsMapLikeSingleOnes)
{
  Fixture f;
  vtkDataArray* scalars = f.Image->GetPointData()->GetScalars();
  const double values[8] = { 0.5, 0.5, 0.5, 0.2, 0.2, 0.5, 1.0, 0.2 };
  for (int i = 0; i < 8; ++i)
  {
    scalars->SetComponent(i, 0, values[i]);
  }
  f.Mapping->Update();
  vtkImageData* out = f.Mapping->GetOutput();
  vtkDataArray* extinction = out->GetPointData()->GetArray("Extinction");
  vtkDataArray* albedo = out->GetPointData()->GetArray("Albedo");
  ASSERT_TRUE(extinction && albedo);
  for (int i = 0; i < 8; ++i)
  {
    const double sigma = -std::log1p(-0.5 * values[i]) / 0.5;
    EXPECT_NEAR(extinction->GetComponent(i, 0), sigma, 1e-6 * sigma) << "voxel " << i;
    EXPECT_NEAR(albedo->GetComponent(i, 0), 1.0, 1e-6) << "voxel " << i;
    EXPECT_NEAR(albedo->GetComponent(i, 1), 1.0 - values[i], 1e-6) << "voxel " << i;
  }
}

TEST(TransferFunctionMedium, ValuesBeyondFloatAreRejected)
{
  Fixture f;
  f.Property->SetScalarOpacityUnitDistance(1e-30);
  f.Mapping->SetEmissionScale(1e30);
  f.ExpectError("exceeds the float range");
}

TEST(TransferFunctionMedium, ScalarsThatDoNotFitTheGridAreRejected)
{
  {
    Fixture f;
    f.Image->GetPointData()->GetScalars()->SetNumberOfTuples(6);
    f.ExpectError("have 6 values but the image has 8 points");
  }
  {
    Fixture f;
    f.Image->SetDimensions(0, 2, 2);
    f.Image->GetPointData()->GetScalars()->SetNumberOfTuples(0);
    f.ExpectError("a non-empty image with one scalar per point");
  }
}

// Cell scalars sit at the cells' centres (as VTK's volume mappers read them): the medium's grid
// is those centres, through a rotated direction matrix and from a non-zero extent, and each
// medium point holds its cell's mapping; the pipeline announces that grid before it runs.
TEST(TransferFunctionMedium, CellScalarsMapAtTheCellCentres)
{
  Fixture f;
  vtkNew<vtkImageData> image;
  image->SetExtent(2, 6, -1, 2, 0, 2); // 5 x 4 x 3 points, 4 x 3 x 2 cells
  image->SetOrigin(10, -5, 3);
  image->SetSpacing(0.5, 0.25, 2.0);
  image->SetDirectionMatrix(0, -1, 0, 1, 0, 0, 0, 0, 1); // 90 degrees about z
  vtkNew<vtkDoubleArray> s;
  s->SetName("density");
  s->SetNumberOfTuples(image->GetNumberOfCells());
  for (vtkIdType c = 0; c < s->GetNumberOfTuples(); ++c)
  {
    s->SetValue(c, static_cast<double>(c) / (s->GetNumberOfTuples() - 1));
  }
  image->GetCellData()->AddArray(s);
  f.Mapping->SetInputData(image);
  f.Mapping->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "density");
  f.Mapping->UpdateInformation();
  int announced[6];
  double announcedOrigin[3];
  vtkInformation* outInfo = f.Mapping->GetOutputInformation(0);
  outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), announced);
  outInfo->Get(vtkDataObject::ORIGIN(), announcedOrigin);
  f.Mapping->Update();
  EXPECT_FALSE(f.Observer->GetError()) << f.Observer->GetErrorMessage();
  vtkImageData* out = f.Mapping->GetOutput();
  int extent[6];
  out->GetExtent(extent);
  const int expected[6] = { 2, 5, -1, 1, 0, 1 };
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_EQ(extent[i], expected[i]) << "extent " << i;
    EXPECT_EQ(announced[i], expected[i]) << "announced extent " << i;
  }
  // The announced origin is the data's (through the direction matrix, which an image
  // algorithm's output information may lack).
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(announcedOrigin[a], out->GetOrigin()[a], 1e-12) << "announced origin " << a;
  }
  // Medium point (i, j, k) is the centre of cell (i, j, k): the mean of its 8 corners.
  vtkDataArray* extinction = out->GetPointData()->GetArray(vtkRefractaMedium::ExtinctionName());
  ASSERT_NE(extinction, nullptr);
  ASSERT_EQ(extinction->GetNumberOfTuples(), s->GetNumberOfTuples());
  for (int k = 0; k < 2; ++k)
  {
    for (int j = -1; j < 2; ++j)
    {
      for (int i = 2; i < 6; ++i)
      {
        int ijk[3] = { i, j, k };
        const vtkIdType cell = image->ComputeCellId(ijk);
        double centre[3] = { 0, 0, 0 }, x[3];
        for (int corner = 0; corner < 8; ++corner)
        {
          double p[3];
          image->TransformIndexToPhysicalPoint(
            i + (corner & 1), j + ((corner >> 1) & 1), k + (corner >> 2), p);
          for (int a = 0; a < 3; ++a)
          {
            centre[a] += p[a] / 8;
          }
        }
        const vtkIdType point = out->FindPoint(centre);
        ASSERT_GE(point, 0);
        out->GetPoint(point, x);
        EXPECT_NEAR(std::hypot(x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]), 0.0, 1e-9);
        const double a = 0.5 * s->GetValue(cell); // the opacity function: 0 -> 0, 1 -> 0.5
        EXPECT_NEAR(extinction->GetComponent(point, 0), -std::log1p(-a) / 0.5, 1e-5)
          << "cell " << cell;
      }
    }
  }
  // Cell data found through FIELD_ASSOCIATION_POINTS_THEN_CELLS: the grid announced was the
  // points'; an error says how to select it.
  f.Mapping->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS_THEN_CELLS, "density");
  f.ExpectError("select it with FIELD_ASSOCIATION_CELLS");
  // A missing array is named with the arrays there are.
  f.Mapping->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "nope");
  f.ExpectError("no cell array 'nope' to map; its arrays: cell 'density'");
  // A cell array of the wrong size is named as cells.
  f.Mapping->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "density");
  s->SetNumberOfTuples(5);
  image->Modified();
  f.ExpectError("have 5 values but the image has 24 cells");
}

namespace
{
// An image of `components`-component tuples, every point the same tuple.
vtkSmartPointer<vtkImageData> TupleImage(vtkDataArray* values, const std::vector<double>& tuple)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(3, 3, 3);
  values->SetName("channels");
  values->SetNumberOfComponents(static_cast<int>(tuple.size()));
  values->SetNumberOfTuples(27);
  for (vtkIdType i = 0; i < 27; ++i)
  {
    for (size_t c = 0; c < tuple.size(); ++c)
    {
      values->SetComponent(i, static_cast<int>(c), tuple[c]);
    }
  }
  image->GetPointData()->SetScalars(values);
  return image;
}
}

// Multi-component scalars as VTK's volume mappers read them (vtkVolumeProperty::
// IndependentComponents): independent components are species whose extinctions add and whose
// albedo is the mixture's; two dependent components are colour and opacity, four are RGB and
// opacity.
TEST(TransferFunctionMedium, MultiComponentScalarsFollowVTKsLayouts)
{
  const double unit = 0.5;
  auto sigmaOf = [unit](double a) { return -std::log1p(-a) / unit; };
  {
    // Independent: component 0 through opacity 0.4, red; component 1 through opacity 0.2, blue,
    // weight 0.5.
    Fixture f;
    vtkNew<vtkPiecewiseFunction> opacity1;
    opacity1->AddPoint(0, 0.2);
    opacity1->AddPoint(10, 0.2);
    vtkNew<vtkColorTransferFunction> blue;
    blue->AddRGBPoint(0, 0, 0, 1);
    vtkNew<vtkPiecewiseFunction> opacity0;
    opacity0->AddPoint(0, 0.4);
    opacity0->AddPoint(10, 0.4);
    vtkNew<vtkColorTransferFunction> red;
    red->AddRGBPoint(0, 1, 0, 0);
    f.Property->SetScalarOpacity(0, opacity0);
    f.Property->SetColor(0, red);
    f.Property->SetScalarOpacity(1, opacity1);
    f.Property->SetColor(1, blue);
    f.Property->SetScalarOpacityUnitDistance(1, unit);
    f.Property->SetComponentWeight(1, 0.5);
    f.Mapping->SetRefractiveIndexFunction(nullptr);
    f.Mapping->SetEmissionScale(0.0);
    vtkNew<vtkDoubleArray> values;
    f.Mapping->SetInputData(TupleImage(values, { 3.0, 7.0 }));
    f.Mapping->Update();
    EXPECT_FALSE(f.Observer->GetError()) << f.Observer->GetErrorMessage();
    vtkPointData* pd = f.Mapping->GetOutput()->GetPointData();
    const double s0 = sigmaOf(0.4), s1 = 0.5 * sigmaOf(0.2);
    EXPECT_NEAR(
      pd->GetArray(vtkRefractaMedium::ExtinctionName())->GetComponent(13, 0), s0 + s1, 1e-5);
    vtkDataArray* a = pd->GetArray(vtkRefractaMedium::AlbedoName());
    EXPECT_NEAR(a->GetComponent(13, 0), s0 / (s0 + s1), 1e-6);
    EXPECT_NEAR(a->GetComponent(13, 1), 0.0, 1e-9);
    EXPECT_NEAR(a->GetComponent(13, 2), s1 / (s0 + s1), 1e-6);
  }
  {
    // Two dependent components: colour of component 0 (white at 0 to red at 1), opacity of
    // component 1 (0 -> 0, 1 -> 0.5), index of component 1.
    Fixture f;
    f.Property->IndependentComponentsOff();
    vtkNew<vtkFloatArray> values;
    f.Mapping->SetInputData(TupleImage(values, { 1.0, 0.5 }));
    f.Mapping->Update();
    EXPECT_FALSE(f.Observer->GetError()) << f.Observer->GetErrorMessage();
    vtkPointData* pd = f.Mapping->GetOutput()->GetPointData();
    EXPECT_NEAR(
      pd->GetArray(vtkRefractaMedium::ExtinctionName())->GetComponent(0, 0), sigmaOf(0.25), 1e-5);
    EXPECT_NEAR(pd->GetArray(vtkRefractaMedium::AlbedoName())->GetComponent(0, 1), 0.0, 1e-6);
    EXPECT_NEAR(pd->GetArray(vtkRefractaMedium::AlbedoName())->GetComponent(0, 0), 1.0, 1e-6);
    EXPECT_NEAR(
      pd->GetArray(vtkRefractaMedium::RefractiveIndexName())->GetComponent(0, 0), 1.25, 1e-6);
  }
  {
    // Four dependent unsigned char components: RGB / 255 directly, opacity of component 3.
    Fixture f;
    f.Property->IndependentComponentsOff();
    f.Opacity->AddPoint(255, 0.5);
    vtkNew<vtkUnsignedCharArray> values;
    f.Mapping->SetInputData(TupleImage(values, { 255, 51, 0, 255 }));
    f.Mapping->Update();
    EXPECT_FALSE(f.Observer->GetError()) << f.Observer->GetErrorMessage();
    vtkPointData* pd = f.Mapping->GetOutput()->GetPointData();
    vtkDataArray* a = pd->GetArray(vtkRefractaMedium::AlbedoName());
    EXPECT_NEAR(a->GetComponent(5, 0), 1.0, 1e-6);
    EXPECT_NEAR(a->GetComponent(5, 1), 0.2, 1e-6);
    EXPECT_NEAR(a->GetComponent(5, 2), 0.0, 1e-6);
    EXPECT_NEAR(
      pd->GetArray(vtkRefractaMedium::ExtinctionName())->GetComponent(5, 0), sigmaOf(0.5), 1e-5);
  }
  {
    // Layouts VTK does not define are errors naming the alternatives; a NaN component is
    // missing data.
    Fixture f;
    f.Property->IndependentComponentsOff();
    vtkNew<vtkFloatArray> values;
    f.Mapping->SetInputData(TupleImage(values, { 0.1, 0.2, 0.3 }));
    f.ExpectError("have 3 components; the transfer-function mapping takes 1, 2 to 4 independent");
  }
  {
    Fixture f;
    vtkNew<vtkFloatArray> values;
    f.Mapping->SetInputData(TupleImage(values, { 0.1, 0.2, 0.3, 0.4, 0.5 }));
    f.ExpectError("have 5 components");
  }
  {
    // Independent species: a NaN species is left out of the mix (the other one stays), a
    // species of weight 0 is never evaluated (its unit distance may be anything).
    Fixture f;
    f.Property->SetComponentWeight(2, 0.0);
    f.Property->SetScalarOpacityUnitDistance(2, 0.0);
    f.Property->SetScalarOpacity(1, f.Opacity);
    f.Property->SetScalarOpacityUnitDistance(1, unit);
    f.Mapping->SetRefractiveIndexFunction(nullptr);
    vtkNew<vtkFloatArray> values;
    f.Mapping->SetInputData(TupleImage(values, { NaN, 1.0, 7.0 }));
    f.Mapping->Update();
    EXPECT_FALSE(f.Observer->GetError()) << f.Observer->GetErrorMessage();
    EXPECT_NEAR(f.Mapping->GetOutput()
                  ->GetPointData()
                  ->GetArray(vtkRefractaMedium::ExtinctionName())
                  ->GetComponent(0, 0),
      sigmaOf(0.5), 1e-5);
  }
  {
    // Which component's function failed is named.
    Fixture f;
    vtkNew<vtkPiecewiseFunction> bad;
    bad->AddPoint(0, NaN);
    bad->AddPoint(10, NaN);
    f.Property->SetScalarOpacity(1, bad);
    vtkNew<vtkFloatArray> values;
    f.Mapping->SetInputData(TupleImage(values, { 0.5, 2.0 }));
    f.ExpectError("the scalar opacity function of component 1 is NaN at scalar 2");
  }
  {
    Fixture f;
    f.Property->IndependentComponentsOff();
    vtkNew<vtkFloatArray> values;
    f.Mapping->SetInputData(TupleImage(values, { 0.5, NaN }));
    f.Mapping->Update();
    EXPECT_FALSE(f.Observer->GetError()) << f.Observer->GetErrorMessage();
    EXPECT_EQ(f.Mapping->GetOutput()
                ->GetPointData()
                ->GetArray(vtkRefractaMedium::ExtinctionName())
                ->GetComponent(0, 0),
      0.0);
  }
}
