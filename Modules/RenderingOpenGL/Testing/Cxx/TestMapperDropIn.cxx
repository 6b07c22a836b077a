// vtkRefractiveVolumeMapper as a drop-in for vtkGPUVolumeRayCastMapper: the same scene (VTK's
// wavelet, extent -10..10, a transfer function, the renderer's default headlight) is exposed
// alike by both mappers; SelectScalarArray, clipping planes and cropping are honoured; cell
// scalars render as point scalars at the cells' centres; independent components mix as species;
// a missing array and a blend mode it does not render are reported once, not on every Render.
#include "MapperTestUtilities.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageAppendComponents.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRefractiveVolumeMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>

namespace
{
const int Size = 80;

// Counts the events of one kind and keeps the last message.
class EventCounter : public vtkCommand
{
public:
  static EventCounter* New() { return new EventCounter; }
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    ++this->Count;
    this->Message = callData ? static_cast<const char*>(callData) : "";
  }
  int Count = 0;
  std::string Message;
};

// A VTK scene as a VTK user sets it up: wavelet, colour and opacity transfer functions, a white
// background, the renderer's automatic headlight, ResetCamera.
struct WaveletScene
{
  vtkSmartPointer<vtkRenderWindow> Window = refracta_test::SharedWindow(Size);
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkRTAnalyticSource> Wavelet;

  WaveletScene()
  {
    this->Wavelet->SetWholeExtent(-10, 10, -10, 10, -10, 10);
    this->Wavelet->Update();
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(37, 0.0);
    opacity->AddPoint(150, 0.05);
    opacity->AddPoint(277, 0.3);
    vtkNew<vtkColorTransferFunction> colour;
    colour->AddRGBPoint(37, 0.2, 0.3, 0.9);
    colour->AddRGBPoint(160, 0.9, 0.9, 0.9);
    colour->AddRGBPoint(277, 0.9, 0.4, 0.1);
    vtkVolumeProperty* property = this->Volume->GetProperty();
    property->SetScalarOpacity(opacity);
    property->SetColor(colour);
    property->SetScalarOpacityUnitDistance(1.0);
    property->SetInterpolationTypeToLinear();
    this->Window->GetRenderers()->RemoveAllItems();
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(0, 0, 0);
    this->Renderer->AddVolume(this->Volume);
  }

  void Use(vtkVolumeMapper* mapper)
  {
    mapper->SetInputConnection(this->Wavelet->GetOutputPort());
    this->Volume->SetMapper(mapper);
    this->Renderer->ResetCamera();
  }

  // Refracta's mapper on the wavelet with few photons (these tests look at geometry, exposure
  // and array selection, not at the lighting's noise).
  void UseRefracta(vtkRefractiveVolumeMapper* mapper)
  {
    mapper->SetNumberOfPhotons(1 << 12);
    this->Use(mapper);
  }

  vtkSmartPointer<vtkImageData> Capture() { return refracta_test::Capture(this->Window); }
};

// Mean brightness (0..255, mean of RGB) over the pixels where the volume shows (any channel
// above 2 on the black background), and the number of those pixels.
double MeanBrightness(vtkImageData* image, int* covered = nullptr)
{
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  double sum = 0;
  int n = 0;
  for (vtkIdType p = 0; p < rgb->GetNumberOfTuples(); ++p)
  {
    const double r = rgb->GetComponent(p, 0), g = rgb->GetComponent(p, 1),
                 b = rgb->GetComponent(p, 2);
    if (r > 2 || g > 2 || b > 2)
    {
      sum += (r + g + b) / 3.0;
      ++n;
    }
  }
  if (covered)
  {
    *covered = n;
  }
  return n ? sum / n : 0.0;
}

// The number of channel values (0..255) that differ between two captures of the same size.
int DifferingValues(vtkImageData* a, vtkImageData* b)
{
  auto* x = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetScalars());
  auto* y = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetScalars());
  int count = 0;
  for (vtkIdType v = 0; v < x->GetNumberOfValues(); ++v)
  {
    count += x->GetValue(v) != y->GetValue(v) ? 1 : 0;
  }
  return count;
}

// Brightness of the pixel column x = i, summed over rows.
double ColumnSum(vtkImageData* image, int i)
{
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  double sum = 0;
  for (int j = 0; j < Size; ++j)
  {
    for (int c = 0; c < 3; ++c)
    {
      sum += rgb->GetComponent(i + Size * j, c);
    }
  }
  return sum;
}
}

TEST(MapperDropIn, ExposedLikeVTKsGPUMapper)
{
  WaveletScene scene;
  vtkNew<vtkGPUVolumeRayCastMapper> gpu;
  scene.Use(gpu);
  int gpuCovered = 0;
  const double gpuMean = MeanBrightness(scene.Capture(), &gpuCovered);

  vtkNew<vtkRefractiveVolumeMapper> refracta;
  refracta->SetNumberOfPhotons(1 << 16);
  scene.Use(refracta);
  int ourCovered = 0;
  const double ourMean = MeanBrightness(scene.Capture(), &ourCovered);
  std::cout << "mean brightness over the volume's pixels: vtkGPUVolumeRayCastMapper " << gpuMean
            << " (" << gpuCovered << " px), vtkRefractiveVolumeMapper " << ourMean << " ("
            << ourCovered << " px), ratio " << ourMean / gpuMean << "\n";
  ASSERT_GT(gpuCovered, Size * Size / 10) << "the GPU mapper drew the wavelet";
  // The same footprint (placement of a medium with extent -10..10) within 25% ...
  EXPECT_NEAR(static_cast<double>(ourCovered) / gpuCovered, 1.0, 0.25);
  // ... and a comparable exposure (within a factor 1.5) through automatic exposure.
  EXPECT_GT(ourMean / gpuMean, 1.0 / 1.5);
  EXPECT_LT(ourMean / gpuMean, 1.5);

  // Radiometric output (VTK light units, no metering) for the record: the light the headlight
  // actually scatters is dimmer than VTK's glowing transfer-function colour.
  refracta->AutomaticExposureOff();
  const double radiometric = MeanBrightness(scene.Capture());
  std::cout << "without automatic exposure: " << radiometric << " (ratio " << radiometric / gpuMean
            << ")\n";
  EXPECT_LT(radiometric, ourMean);
}

TEST(MapperDropIn, SelectScalarArrayIsHonouredAndAMissingArrayIsReportedOnce)
{
  WaveletScene scene;
  vtkNew<vtkRefractiveVolumeMapper> mapper;
  scene.UseRefracta(mapper);
  vtkNew<EventCounter> errors;
  mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectScalarArray("NoSuchArray");
  scene.Window->Render();
  scene.Window->Render();
  scene.Window->Render();
  EXPECT_EQ(errors->Count, 1) << "said once, not on every Render";
  EXPECT_NE(errors->Message.find("'NoSuchArray'"), std::string::npos) << errors->Message;
  EXPECT_NE(errors->Message.find("SelectScalarArray"), std::string::npos) << errors->Message;

  // The wavelet's array by name: it renders, and the message is not repeated.
  mapper->SelectScalarArray("RTData");
  const double mean = MeanBrightness(scene.Capture());
  EXPECT_GT(mean, 1.0);
  EXPECT_EQ(errors->Count, 1);

  // A scalar the transfer functions cannot map (infinite): the mapping filter's own words reach
  // the mapper's observer, once (the filter and its executive used to print on every Render, and
  // the mapper's event only pointed at them).
  vtkNew<vtkImageData> bad;
  bad->DeepCopy(scene.Wavelet->GetOutput());
  bad->GetPointData()->GetArray("RTData")->SetComponent(
    7, 0, std::numeric_limits<double>::infinity());
  mapper->SetInputData(bad);
  scene.Window->Render();
  scene.Window->Render();
  scene.Window->Render();
  EXPECT_EQ(errors->Count, 2) << "said once, not on every Render";
  EXPECT_NE(errors->Message.find("Cannot map the input scalar inf at point 7"), std::string::npos)
    << errors->Message;
}

TEST(MapperDropIn, ClippingPlanesAndCroppingCutTheMediumAway)
{
  WaveletScene scene;
  vtkNew<vtkRefractiveVolumeMapper> mapper;
  scene.UseRefracta(mapper);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetPosition(0, 0, 80);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(12);
  scene.Renderer->ResetCameraClippingRange();
  auto full = scene.Capture();
  const int left = Size / 4, right = 3 * Size / 4; // x = -6 and x = +6 in world units
  ASSERT_GT(ColumnSum(full, left), 0.0);
  ASSERT_GT(ColumnSum(full, right), 0.0);

  // Keep x >= 0 (the normal points to what stays, as in VTK's mappers).
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(0, 0, 0);
  plane->SetNormal(1, 0, 0);
  mapper->AddClippingPlane(plane);
  // What is cut away shows the background, up to the photon pass's 3x3x3 smoothing and the
  // trilinear lookup, which carry in-scattered light up to two voxels past a cut (made visible by
  // the automatic exposure): below 1% of the brightest column, at least 2.85 voxels away.
  auto dark = [](vtkImageData* image, int column)
  {
    double brightest = 0;
    for (int i = 0; i < Size; ++i)
    {
      brightest = std::max(brightest, ColumnSum(image, i));
    }
    return ColumnSum(image, column) <= 0.01 * brightest;
  };
  auto clipped = scene.Capture();
  EXPECT_TRUE(dark(clipped, left)) << "the cut-away half shows the background";
  EXPECT_GT(ColumnSum(clipped, right), 0.0);
  const int builds = mapper->GetNumberOfMediumBuilds();
  scene.Capture();
  EXPECT_EQ(mapper->GetNumberOfMediumBuilds(), builds) << "unchanged planes: no new cut";
  plane->SetNormal(-1, 0, 0);
  auto flipped = scene.Capture();
  EXPECT_GT(ColumnSum(flipped, left), 0.0);
  EXPECT_TRUE(dark(flipped, right));
  mapper->RemoveAllClippingPlanes();

  // Cropping: keep the centre region |x|, |y|, |z| <= 3 only.
  mapper->SetCroppingRegionPlanes(-3, 3, -3, 3, -3, 3);
  mapper->SetCroppingRegionFlagsToSubVolume();
  mapper->CroppingOn();
  auto cropped = scene.Capture();
  EXPECT_TRUE(dark(cropped, left));
  EXPECT_TRUE(dark(cropped, right));
  EXPECT_GT(ColumnSum(cropped, Size / 2), 0.0);
}

TEST(MapperDropIn, UnsupportedBlendModeIsRefusedOnce)
{
  WaveletScene scene;
  vtkNew<vtkRefractiveVolumeMapper> mapper;
  scene.UseRefracta(mapper);
  vtkNew<EventCounter> warnings;
  mapper->AddObserver(vtkCommand::WarningEvent, warnings);
  mapper->SetBlendModeToMaximumIntensity();
  scene.Window->Render();
  scene.Window->Render();
  EXPECT_EQ(warnings->Count, 1);
  EXPECT_NE(warnings->Message.find("COMPOSITE"), std::string::npos) << warnings->Message;
}

// Two volumes in one renderer cannot composite with this mapper (it replaces the pixels its
// medium covers and writes no depth: found erasing an emitting volume drawn before it, or
// ignoring an absorbing one drawn after). That is said once, naming the other mapper, and again
// only after the other volume went away and came back.
TEST(MapperDropIn, AnotherVolumeInTheRendererIsWarnedAboutOnce)
{
  WaveletScene scene;
  vtkNew<vtkRefractiveVolumeMapper> mapper;
  scene.UseRefracta(mapper);
  vtkNew<EventCounter> warnings;
  mapper->AddObserver(vtkCommand::WarningEvent, warnings);
  scene.Window->Render();
  EXPECT_EQ(warnings->Count, 0);
  // A prop drawing through this same mapper is this volume, not another: ParaView's
  // vtkPVLODVolume sits in the renderer and hands the mapper an internal vtkVolume.
  vtkNew<vtkVolume> wrapper;
  wrapper->SetMapper(mapper);
  wrapper->SetProperty(scene.Volume->GetProperty());
  scene.Renderer->AddVolume(wrapper);
  scene.Window->Render();
  EXPECT_EQ(warnings->Count, 0) << warnings->Message;
  scene.Renderer->RemoveVolume(wrapper);
  vtkNew<vtkVolume> other;
  vtkNew<vtkRefractiveVolumeMapper> otherMapper;
  otherMapper->SetNumberOfPhotons(1 << 12);
  otherMapper->SetInputConnection(scene.Wavelet->GetOutputPort());
  other->SetMapper(otherMapper);
  other->SetProperty(scene.Volume->GetProperty());
  other->SetPosition(25, 0, 0);
  scene.Renderer->AddVolume(other);
  scene.Window->Render();
  scene.Window->Render();
  EXPECT_EQ(warnings->Count, 1);
  EXPECT_NE(warnings->Message.find("another visible volume (mapper vtkRefractiveVolumeMapper)"),
    std::string::npos)
    << warnings->Message;
  other->VisibilityOff();
  scene.Window->Render();
  other->VisibilityOn();
  scene.Window->Render();
  EXPECT_EQ(warnings->Count, 2);
}

TEST(MapperDropIn, CellScalarsRenderAsPointScalarsAtTheCellCentres)
{
  // The wavelet's values as the cell data of a grid one point larger, half a spacing lower: its
  // cells' centres are the wavelet's points, so with SetScalarModeToUseCellData the medium (and
  // the image) is the point-data wavelet's, as VTK's own mappers read cell data.
  WaveletScene scene;
  vtkNew<vtkRefractiveVolumeMapper> mapper;
  scene.UseRefracta(mapper);
  vtkSmartPointer<vtkImageData> viaPoints = scene.Capture();
  vtkImageData* wavelet = scene.Wavelet->GetOutput();
  vtkNew<vtkImageData> cells;
  cells->SetExtent(-10, 11, -10, 11, -10, 11);
  cells->SetSpacing(wavelet->GetSpacing());
  const double* origin = wavelet->GetOrigin();
  const double* spacing = wavelet->GetSpacing();
  cells->SetOrigin(
    origin[0] - 0.5 * spacing[0], origin[1] - 0.5 * spacing[1], origin[2] - 0.5 * spacing[2]);
  vtkNew<vtkFloatArray> values;
  values->DeepCopy(wavelet->GetPointData()->GetArray("RTData"));
  values->SetName("RTDataCells");
  cells->GetCellData()->SetScalars(values);
  ASSERT_EQ(cells->GetNumberOfCells(), wavelet->GetNumberOfPoints());
  vtkNew<EventCounter> errors;
  mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  mapper->SetInputData(cells);
  mapper->SetScalarModeToUseCellData();
  vtkSmartPointer<vtkImageData> viaCells = scene.Capture();
  EXPECT_EQ(errors->Count, 0) << errors->Message;
  const int differing = DifferingValues(viaPoints, viaCells);
  std::cout << "cell scalars against point scalars: " << differing << " values differ, mean "
            << "brightness " << MeanBrightness(viaCells) << "\n";
  EXPECT_GT(MeanBrightness(viaCells), 1.0);
  EXPECT_EQ(differing, 0);
}

TEST(MapperDropIn, IndependentComponentsMixAsSpecies)
{
  // The wavelet twice as two independent components, the second of weight 0: the same species
  // as the one-component wavelet, so the same image. Weight 1 adds the second species (the
  // property's default functions for component 1): more extinction, a different image.
  WaveletScene scene;
  vtkNew<vtkRefractiveVolumeMapper> mapper;
  scene.UseRefracta(mapper);
  vtkSmartPointer<vtkImageData> single = scene.Capture();
  vtkNew<vtkImageAppendComponents> twice;
  twice->AddInputConnection(scene.Wavelet->GetOutputPort());
  twice->AddInputConnection(scene.Wavelet->GetOutputPort());
  mapper->SetInputConnection(twice->GetOutputPort());
  vtkVolumeProperty* property = scene.Volume->GetProperty();
  vtkNew<vtkPiecewiseFunction> opacity1;
  opacity1->AddPoint(37, 0.0);
  opacity1->AddPoint(277, 0.3);
  property->SetScalarOpacity(1, opacity1);
  property->SetScalarOpacityUnitDistance(1, 1.0);
  property->SetComponentWeight(1, 0.0);
  vtkNew<EventCounter> errors;
  mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  vtkSmartPointer<vtkImageData> mixed = scene.Capture();
  EXPECT_EQ(errors->Count, 0) << errors->Message;
  EXPECT_EQ(DifferingValues(single, mixed), 0) << "a species of weight 0 changes nothing";
  property->SetComponentWeight(1, 1.0);
  vtkSmartPointer<vtkImageData> both = scene.Capture();
  EXPECT_EQ(errors->Count, 0) << errors->Message;
  std::cout << "two independent components: " << DifferingValues(single, both)
            << " values differ from one component\n";
  EXPECT_GT(DifferingValues(single, both), 100);
}

TEST(MapperDropIn, AnUnnamedArraySelectedByIndexIsTheOneRendered)
{
  // Array 0 unnamed and all below the opacity function's first point (nothing to see); the
  // active scalars another, visible array. SelectScalarArray(0) must render array 0, as
  // vtkGPUVolumeRayCastMapper does (an unnamed array cannot be named to the mapping filter).
  WaveletScene scene;
  vtkNew<vtkRefractiveVolumeMapper> mapper;
  scene.UseRefracta(mapper);
  vtkNew<vtkImageData> image;
  image->ShallowCopy(scene.Wavelet->GetOutput());
  vtkNew<vtkFloatArray> empty;
  empty->SetNumberOfTuples(image->GetNumberOfPoints());
  empty->Fill(0.0);
  vtkDataArray* visible = image->GetPointData()->GetArray("RTData");
  image->GetPointData()->Initialize();
  image->GetPointData()->AddArray(empty); // index 0, no name
  image->GetPointData()->SetScalars(visible);
  mapper->SetInputData(image);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectScalarArray(0);
  int covered = -1;
  MeanBrightness(scene.Capture(), &covered);
  EXPECT_EQ(covered, 0) << "array 0 (nothing to see) is rendered, not the active scalars";
  mapper->SetScalarModeToDefault();
  MeanBrightness(scene.Capture(), &covered);
  EXPECT_GT(covered, Size * Size / 10) << "the active scalars are visible";
}
