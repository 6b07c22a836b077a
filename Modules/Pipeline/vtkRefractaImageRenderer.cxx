#include "vtkRefractaImageRenderer.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkEffectPlan.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkPointData.h"
#include "vtkRefractaRenderPipeline.h"
#include "vtkRefractaSettings.h"
#include "vtkRefractaViewPass.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkTexture.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>

vtkStandardNewMacro(vtkRefractaImageRenderer);
vtkRefractaCxxSetClampMacro(vtkRefractaImageRenderer, Exposure, 0.0, 1e30);

//------------------------------------------------------------------------------
vtkRefractaImageRenderer::vtkRefractaImageRenderer()
  : Pipeline(vtkSmartPointer<vtkRefractaRenderPipeline>::New())
{
  this->ViewPass = this->Pipeline->GetViewPass();
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(1);
  // The pipeline's progress becomes this filter's; an abort of this filter aborts the pipeline.
  vtkNew<vtkCallbackCommand> forward;
  forward->SetClientData(this);
  forward->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      auto* self = static_cast<vtkRefractaImageRenderer*>(clientData);
      self->UpdateProgress(*static_cast<double*>(callData));
      if (self->GetAbortExecute()) // set before, or by an observer of this very progress event
      {
        self->Pipeline->AbortRender();
      }
    });
  this->Pipeline->AddObserver(vtkCommand::ProgressEvent, forward);
  this->Pipeline->SetEventOwner(this);
  // This filter renders the medium as given: the plan decides only which light passes to run.
  for (int effect :
    { vtkEffectPlan::REFRACTION, vtkEffectPlan::ABSORPTION, vtkEffectPlan::EMISSION })
  {
    this->Pipeline->GetEffectPlan()->SetEffectMode(effect, vtkEffectPlan::FORCE_ON);
  }
}

vtkRefractaImageRenderer::~vtkRefractaImageRenderer()
{
  this->Pipeline->SetEventOwner(nullptr);
}

//------------------------------------------------------------------------------
int vtkRefractaImageRenderer::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

void vtkRefractaImageRenderer::SetSurfaces(vtkRefractaSurfaceSet* surfaces)
{
  this->Pipeline->SetSurfaces(surfaces); // the pipeline's MTime is part of this one's
}

vtkRefractaSurfaceSet* vtkRefractaImageRenderer::GetSurfaces()
{
  return this->Pipeline->GetSurfaces();
}

void vtkRefractaImageRenderer::SetLightingData(vtkImageData* lighting)
{
  if (lighting)
  {
    this->SetInputDataObject(1, lighting);
  }
  else
  {
    this->SetInputConnection(1, nullptr);
  }
}

void vtkRefractaImageRenderer::SetLightingConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

//------------------------------------------------------------------------------
void vtkRefractaImageRenderer::AddLight(vtkLight* light)
{
  this->Pipeline->AddLight(light);
  this->Modified();
}

void vtkRefractaImageRenderer::RemoveAllLights()
{
  this->Pipeline->RemoveAllLights();
  this->Modified();
}

vtkRefractaRenderPipeline* vtkRefractaImageRenderer::GetPipeline()
{
  return this->Pipeline;
}

void vtkRefractaImageRenderer::SetCamera(vtkCamera* camera)
{
  if (this->Camera != camera)
  {
    this->Camera = camera;
    this->Modified();
  }
}

vtkCamera* vtkRefractaImageRenderer::GetCamera()
{
  return this->Camera;
}

void vtkRefractaImageRenderer::SetImageSize(int width, int height)
{
  if (width < 1 || height < 1 || width > MaximumImageSide || height > MaximumImageSide)
  {
    vtkErrorMacro("SetImageSize(" << width << ", " << height << "): each side must be 1 to "
                                  << MaximumImageSide << " pixels; the size stays "
                                  << this->ImageSize[0] << " x " << this->ImageSize[1]);
    return;
  }
  if (width != this->ImageSize[0] || height != this->ImageSize[1])
  {
    this->ImageSize[0] = width;
    this->ImageSize[1] = height;
    this->Modified();
  }
}

void vtkRefractaImageRenderer::SetBackgroundColor(double r, double g, double b)
{
  this->ViewPass->SetBackgroundColor(r, g, b);
}

void vtkRefractaImageRenderer::GetBackgroundColor(double rgb[3])
{
  this->ViewPass->GetBackgroundColor(rgb);
}

void vtkRefractaImageRenderer::SetEnvironmentMap(vtkImageData* image)
{
  this->ViewPass->SetEnvironmentMap(image);
}

vtkImageData* vtkRefractaImageRenderer::GetEnvironmentMap()
{
  return this->ViewPass->GetEnvironmentMap();
}

void vtkRefractaImageRenderer::SetEnvironmentTexture(vtkTexture* texture)
{
  if (this->EnvironmentTexture != texture)
  {
    this->EnvironmentTexture = texture;
    this->Modified();
  }
}

vtkTexture* vtkRefractaImageRenderer::GetEnvironmentTexture()
{
  return this->EnvironmentTexture;
}

void vtkRefractaImageRenderer::SetEnvironmentUp(double x, double y, double z)
{
  this->ViewPass->SetEnvironmentUp(x, y, z);
}

void vtkRefractaImageRenderer::SetEnvironmentRight(double x, double y, double z)
{
  this->ViewPass->SetEnvironmentRight(x, y, z);
}

void vtkRefractaImageRenderer::SetStepSize(double voxels)
{
  this->ViewPass->SetStepSize(voxels);
}

double vtkRefractaImageRenderer::GetStepSize()
{
  return this->ViewPass->GetStepSize();
}

void vtkRefractaImageRenderer::SetRayMode(int mode)
{
  this->ViewPass->SetRayMode(mode);
}

int vtkRefractaImageRenderer::GetRayMode()
{
  return this->ViewPass->GetRayMode();
}

void vtkRefractaImageRenderer::SetTransmittanceCutoff(double cutoff)
{
  this->ViewPass->SetTransmittanceCutoff(cutoff);
}

double vtkRefractaImageRenderer::GetTransmittanceCutoff()
{
  return this->ViewPass->GetTransmittanceCutoff();
}

void vtkRefractaImageRenderer::SetMaxSteps(int steps)
{
  this->ViewPass->SetMaxSteps(steps);
}

int vtkRefractaImageRenderer::GetMaxSteps()
{
  return this->ViewPass->GetMaxSteps();
}

void vtkRefractaImageRenderer::SetEmptySpaceSkipping(bool on)
{
  this->ViewPass->SetEmptySpaceSkipping(on);
}

bool vtkRefractaImageRenderer::GetEmptySpaceSkipping()
{
  return this->ViewPass->GetEmptySpaceSkipping();
}

void vtkRefractaImageRenderer::SetContext(vtkOpenCLContext* context)
{
  this->Pipeline->SetContext(context);
}

vtkOpenCLContext* vtkRefractaImageRenderer::GetContext()
{
  return this->ViewPass->GetContext();
}

vtkRefractaViewPass* vtkRefractaImageRenderer::GetViewPass()
{
  return this->ViewPass;
}

vtkMTimeType vtkRefractaImageRenderer::GetMTime()
{
  vtkMTimeType t = std::max(this->Superclass::GetMTime(), this->Pipeline->GetInputsMTime());
  if (this->Camera)
  {
    t = std::max(t, this->Camera->GetMTime());
  }
  if (this->EnvironmentTexture)
  {
    t = std::max(t, this->EnvironmentTexture->GetMTime());
  }
  return t;
}

//------------------------------------------------------------------------------
int vtkRefractaImageRenderer::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, this->ImageSize[0] - 1, 0, this->ImageSize[1] - 1, 0, 0 };
  const double spacing[3] = { 1, 1, 1 };
  const double origin[3] = { 0, 0, 0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 3);
  return 1;
}

int vtkRefractaImageRenderer::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The view pass needs whole volumes, whatever piece of the image is asked for.
  for (int port = 0; port < 2; ++port)
  {
    for (int i = 0; i < inputVector[port]->GetNumberOfInformationObjects(); ++i)
    {
      vtkInformation* inInfo = inputVector[port]->GetInformationObject(i);
      if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
      {
        inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
          inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
      }
    }
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkRefractaImageRenderer::ToneMap(
  const float* hdr, size_t pixels, int toneMapping, double exposure, vtkUnsignedCharArray* rgb)
{
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(pixels));
  unsigned char* out = rgb->GetPointer(0);
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      double v = exposure * static_cast<double>(hdr[p * 4 + c]);
      v = std::isfinite(v) ? std::max(v, 0.0) : 0.0;
      switch (toneMapping)
      {
        case REINHARD:
          v = v / (1.0 + v);
          break;
        case EXPONENTIAL:
          v = -std::expm1(-v);
          break;
        default:
          v = std::min(v, 1.0);
      }
      const double srgb = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
      out[p * 3 + c] = static_cast<unsigned char>(std::lround(std::min(srgb, 1.0) * 255.0));
    }
  }
}

//------------------------------------------------------------------------------
int vtkRefractaImageRenderer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  output->Initialize();
  this->LastRunAborted = false;
  vtkImageData* medium = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* lighting = inputVector[1]->GetNumberOfInformationObjects()
    ? vtkImageData::GetData(inputVector[1], 0)
    : nullptr;
  if (!this->Camera)
  {
    vtkErrorMacro("No camera: call SetCamera() with a vtkCamera before updating.");
    return 0;
  }
  vtkRefractaViewPass* pass = this->ViewPass;
  if (this->EnvironmentTexture)
  {
    vtkImageData* image = this->EnvironmentTexture->GetInput();
    if (!image)
    {
      vtkErrorMacro("The environment texture has no input image (set its input data or "
                    "connection to an equirectangular vtkImageData).");
      return 0;
    }
    if (vtkAlgorithm* producer = this->EnvironmentTexture->GetInputAlgorithm())
    {
      producer->Update();
      image = this->EnvironmentTexture->GetInput();
    }
    pass->SetEnvironmentMap(image);
  }
  vtkRefractaRenderPipeline* pipeline = this->Pipeline;
  pipeline->SetMedium(medium);
  pipeline->SetLightingData(lighting);
  pipeline->SetCamera(this->Camera);
  if (!pipeline->Render(this->ImageSize[0], this->ImageSize[1]))
  {
    // An abort is not an error: empty output, no message.
    this->LastRunAborted = pipeline->GetLastRenderAborted();
    return this->LastRunAborted ? 1 : 0;
  }
  const std::vector<float>& hdr = pipeline->GetImage();

  const size_t pixels = static_cast<size_t>(this->ImageSize[0]) * this->ImageSize[1];
  output->SetExtent(0, this->ImageSize[0] - 1, 0, this->ImageSize[1] - 1, 0, 0);
  output->SetSpacing(1, 1, 1);
  output->SetOrigin(0, 0, 0);
  vtkNew<vtkFloatArray> hdrArray;
  hdrArray->SetName("HDR");
  hdrArray->SetNumberOfComponents(4);
  hdrArray->SetNumberOfTuples(static_cast<vtkIdType>(pixels));
  std::copy(hdr.begin(), hdr.end(), hdrArray->GetPointer(0));
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  ToneMap(hdr.data(), pixels, this->ToneMapping, this->Exposure, rgb);
  output->GetPointData()->AddArray(hdrArray);
  output->GetPointData()->SetScalars(rgb);

  auto record = [&](const char* name, double value)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    output->GetFieldData()->AddArray(a);
  };
  record("ViewPassSeconds", pass->GetLastSeconds());
  record("TotalSteps", pass->GetLastTotalSteps());
  record("CurvedRays", pass->GetLastCurved() ? 1.0 : 0.0);
  record("EmptySpaceSkipping", pass->GetLastSkipping() ? 1.0 : 0.0);
  record("ActiveCellFraction", pass->GetLastActiveCellFraction());
  record("LaneMarching", pass->GetLastLaneMarching() ? 1.0 : 0.0);
  record("PlanSeconds", pipeline->GetStageSeconds(vtkRefractaRenderPipeline::PLAN));
  record("LightingSeconds", pipeline->GetStageSeconds(vtkRefractaRenderPipeline::LIGHTING));
  record("ViewSeconds", pipeline->GetStageSeconds(vtkRefractaRenderPipeline::VIEW));
  pipeline->GetEffectPlan()->RecordInFieldData(output->GetFieldData());
  return 1;
}

//------------------------------------------------------------------------------
void vtkRefractaImageRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ImageSize: " << this->ImageSize[0] << " x " << this->ImageSize[1] << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "ToneMapping: "
     << (this->ToneMapping == CLAMP ? "CLAMP"
                                    : (this->ToneMapping == REINHARD ? "REINHARD" : "EXPONENTIAL"))
     << "\n";
  os << indent << "Camera: " << this->Camera.Get() << "\n";
  os << indent << "LastRunAborted: " << this->LastRunAborted << "\n";
  os << indent << "EnvironmentTexture: " << this->EnvironmentTexture.Get() << "\n";
  os << indent << "Pipeline:\n";
  this->Pipeline->PrintSelf(os, indent.GetNextIndent());
}
