#include "vtkRefractiveVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkEffectPlan.h"
#include "vtkImageData.h"
#include "vtkLatticeBoltzmannLighting.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkMediumValidator.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaViewPass.h"
#include "vtkRenderer.h"
#include "vtkTransferFunctionMedium.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtk_glew.h"

#include "vtkPhotonTracer.h"
#include "vtkSceneAnalysis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkRefractiveVolumeMapper);

struct vtkRefractiveVolumeMapper::Internals
{
  vtkSmartPointer<vtkRefractaViewPass> ViewPass = vtkSmartPointer<vtkRefractaViewPass>::New();
  vtkSmartPointer<vtkTransferFunctionMedium> Mapping =
    vtkSmartPointer<vtkTransferFunctionMedium>::New();
  vtkSmartPointer<vtkPiecewiseFunction> IndexFunction;
  vtkSmartPointer<vtkImageData> LightingData;

  // Medium stage. Medium is the input (or its transfer-function mapping) pruned by the plan.
  vtkSmartPointer<vtkImageData> Medium;
  vtkSmartPointer<vtkSceneAnalysis> Analysis = vtkSmartPointer<vtkSceneAnalysis>::New();
  vtkSmartPointer<vtkEffectPlan> Plan = vtkSmartPointer<vtkEffectPlan>::New();
  std::string MediumKey;

  // Light stage.
  vtkSmartPointer<vtkImageData> Lighting;
  std::string LightKey;
  vtkSmartPointer<vtkPhotonTracer> Tracer = vtkSmartPointer<vtkPhotonTracer>::New();

  // View stage.
  std::string ViewKey;
  std::vector<float> Depth;
  std::vector<float> Image;
  std::vector<float> Transmittance;
  int Viewport[4] = { 0, 0, 0, 0 };
};

//------------------------------------------------------------------------------
vtkRefractiveVolumeMapper::vtkRefractiveVolumeMapper()
  : Internal(new Internals)
{
}

vtkRefractiveVolumeMapper::~vtkRefractiveVolumeMapper() = default;

void vtkRefractiveVolumeMapper::SetRefractiveIndexFunction(vtkPiecewiseFunction* function)
{
  if (this->Internal->IndexFunction != function)
  {
    this->Internal->IndexFunction = function;
    this->Modified();
  }
}

vtkPiecewiseFunction* vtkRefractiveVolumeMapper::GetRefractiveIndexFunction()
{
  return this->Internal->IndexFunction;
}

void vtkRefractiveVolumeMapper::SetLightingData(vtkImageData* lighting)
{
  if (this->Internal->LightingData != lighting)
  {
    this->Internal->LightingData = lighting;
    this->Modified();
  }
}

vtkImageData* vtkRefractiveVolumeMapper::GetLightingData()
{
  return this->Internal->LightingData;
}

void vtkRefractiveVolumeMapper::SetStepSize(double voxels)
{
  this->Internal->ViewPass->SetStepSize(voxels);
}

double vtkRefractiveVolumeMapper::GetStepSize()
{
  return this->Internal->ViewPass->GetStepSize();
}

void vtkRefractiveVolumeMapper::SetRayMode(int mode)
{
  this->Internal->ViewPass->SetRayMode(mode);
}

int vtkRefractiveVolumeMapper::GetRayMode()
{
  return this->Internal->ViewPass->GetRayMode();
}

void vtkRefractiveVolumeMapper::SetTransmittanceCutoff(double cutoff)
{
  this->Internal->ViewPass->SetTransmittanceCutoff(cutoff);
}

double vtkRefractiveVolumeMapper::GetTransmittanceCutoff()
{
  return this->Internal->ViewPass->GetTransmittanceCutoff();
}

void vtkRefractiveVolumeMapper::SetEmptySpaceSkipping(bool on)
{
  this->Internal->ViewPass->SetEmptySpaceSkipping(on);
}

bool vtkRefractiveVolumeMapper::GetEmptySpaceSkipping()
{
  return this->Internal->ViewPass->GetEmptySpaceSkipping();
}

void vtkRefractiveVolumeMapper::SetContext(vtkOpenCLContext* context)
{
  this->Internal->ViewPass->SetContext(context);
  this->Internal->MediumKey.clear();
}

vtkOpenCLContext* vtkRefractiveVolumeMapper::GetContext()
{
  return this->Internal->ViewPass->GetContext();
}

vtkImageData* vtkRefractiveVolumeMapper::GetMedium()
{
  return this->Internal->Medium;
}

vtkImageData* vtkRefractiveVolumeMapper::GetLighting()
{
  return this->Internal->Lighting;
}

vtkRefractaViewPass* vtkRefractiveVolumeMapper::GetViewPass()
{
  return this->Internal->ViewPass;
}

bool vtkRefractiveVolumeMapper::HasLightPasses()
{
  return true;
}

void vtkRefractiveVolumeMapper::ReleaseGraphicsResources(vtkWindow*)
{
  // The image is drawn through the window's own pixel path; nothing of ours lives in GL.
}

//------------------------------------------------------------------------------
bool vtkRefractiveVolumeMapper::UpdateMedium(vtkVolume* volume)
{
  Internals& in = *this->Internal;
  if (vtkAlgorithm* producer = this->GetInputAlgorithm())
  {
    producer->Update();
  }
  vtkImageData* input = vtkImageData::SafeDownCast(this->GetInput());
  if (!input)
  {
    vtkErrorMacro("The input must be a vtkImageData (a Refracta medium or a scalar image).");
    return false;
  }
  bool isMedium = false;
  for (int id = 0; id < vtkRefractaMedium::NUMBER_OF_ARRAYS; ++id)
  {
    isMedium = isMedium || input->GetPointData()->GetArray(vtkRefractaMedium::GetArrayName(id));
  }
  vtkVolumeProperty* property = volume->GetProperty();
  std::ostringstream key;
  key << input << ":" << input->GetMTime();
  if (!isMedium)
  {
    key << ":" << property << ":" << property->GetMTime() << ":" << this->Anisotropy << ":"
        << this->EmissionScale << ":" << in.IndexFunction.Get() << ":"
        << (in.IndexFunction ? in.IndexFunction->GetMTime() : 0);
  }
  // The plan's settings (not its modification time: deciding it touches that on every run).
  key << ":plan" << in.Plan->GetTolerance();
  for (int e = 0; e < vtkEffectPlan::NUMBER_OF_EFFECTS; ++e)
  {
    key << "," << in.Plan->GetEffectMode(e);
  }
  key << ":" << this->MultipleScattering;
  if (key.str() == in.MediumKey && in.Medium)
  {
    return true;
  }
  in.MediumKey.clear();
  in.Medium = nullptr;
  vtkSmartPointer<vtkImageData> full;
  if (isMedium)
  {
    full = input;
  }
  else
  {
    in.Mapping->SetInputData(input);
    in.Mapping->SetVolumeProperty(property);
    in.Mapping->SetRefractiveIndexFunction(in.IndexFunction);
    in.Mapping->SetAnisotropy(this->Anisotropy);
    in.Mapping->SetEmissionScale(this->EmissionScale);
    in.Mapping->Update();
    if (in.Mapping->GetOutput()->GetNumberOfPoints() == 0)
    {
      vtkErrorMacro("Mapping the scalar input through the volume property failed (see the "
                    "vtkTransferFunctionMedium error above).");
      return false;
    }
    full = vtkSmartPointer<vtkImageData>::New();
    full->ShallowCopy(in.Mapping->GetOutput());
  }
  // The plan's light-independent decisions (refraction, absorption, emission) prune the medium
  // every pass sees; the light stage decides single and multiple scattering with the lights.
  in.Analysis->SetMedium(full);
  in.Analysis->RemoveAllLights();
  if (!in.Analysis->Analyze() || !this->DecidePlan())
  {
    vtkErrorMacro("The scene analysis of the medium failed (see the error above).");
    return false;
  }
  in.Medium = vtkSmartPointer<vtkImageData>::New();
  in.Plan->ApplyToMedium(full, in.Medium);
  if (!in.ViewPass->SetMedium(in.Medium))
  {
    in.Medium = nullptr;
    return false;
  }
  ++this->NumberOfMediumBuilds;
  in.MediumKey = key.str();
  in.LightKey.clear(); // a new medium invalidates the lighting
  return true;
}

//------------------------------------------------------------------------------
bool vtkRefractiveVolumeMapper::DecidePlan()
{
  Internals& in = *this->Internal;
  // MultipleScattering off is a user override of the plan; the plan's own modes stay as set.
  const int userMode = in.Plan->GetEffectMode(vtkEffectPlan::MULTIPLE_SCATTERING);
  if (!this->MultipleScattering)
  {
    in.Plan->SetEffectMode(vtkEffectPlan::MULTIPLE_SCATTERING, vtkEffectPlan::FORCE_OFF);
  }
  const bool decided = in.Plan->Decide(in.Analysis);
  in.Plan->SetEffectMode(vtkEffectPlan::MULTIPLE_SCATTERING, userMode);
  return decided;
}

//------------------------------------------------------------------------------
vtkEffectPlan* vtkRefractiveVolumeMapper::GetEffectPlan()
{
  return this->Internal->Plan;
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::SetQuality(int quality)
{
  vtkEffectPlan* plan = this->Internal->Plan;
  plan->SetQuality(quality);
  if (plan->GetQuality() != quality)
  {
    return; // the plan reported the unknown preset
  }
  this->QualityPresetApplied = true;
  this->SetNumberOfPhotons(plan->GetRecommendedNumberOfPhotons());
  this->SetStepSize(plan->GetRecommendedViewStep());
  this->Modified();
}

//------------------------------------------------------------------------------
vtkSceneAnalysis* vtkRefractiveVolumeMapper::GetSceneAnalysis()
{
  return this->Internal->Analysis;
}

//------------------------------------------------------------------------------
bool vtkRefractiveVolumeMapper::UpdateLighting(vtkRenderer* renderer, vtkVolume* volume)
{
  Internals& in = *this->Internal;
  if (in.LightingData)
  {
    std::ostringstream key;
    key << "data:" << in.LightingData.Get() << ":" << in.LightingData->GetMTime() << ":"
        << in.MediumKey;
    if (key.str() != in.LightKey)
    {
      in.Lighting = in.LightingData;
      if (!in.ViewPass->SetLighting(in.Lighting))
      {
        in.Lighting = nullptr;
        return false;
      }
      in.LightKey = key.str();
    }
    return true;
  }
  // Signature of every light that is on, in world coordinates, and of the volume's placement.
  std::ostringstream key;
  key.precision(17);
  key << "lights:" << in.MediumKey << ":" << this->NumberOfPhotons << ":" << this->Seed << ":"
      << this->MultipleScattering << ":"
      << (this->QualityPresetApplied ? in.Plan->GetQuality() : -1);
  const double* m = volume->GetMatrix()->GetData();
  for (int i = 0; i < 16; ++i)
  {
    key << ":" << m[i];
  }
  vtkLightCollection* lights = renderer->GetLights();
  vtkCollectionSimpleIterator it;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    double p[3], f[3], c[3];
    light->GetTransformedPosition(p);
    light->GetTransformedFocalPoint(f);
    light->GetDiffuseColor(c);
    key << "|" << light->GetPositional() << ":" << p[0] << "," << p[1] << "," << p[2] << ":" << f[0]
        << "," << f[1] << "," << f[2] << ":" << c[0] << "," << c[1] << "," << c[2] << ":"
        << light->GetIntensity() << ":" << light->GetConeAngle() << ":" << light->GetExponent();
  }
  if (key.str() == in.LightKey)
  {
    return true;
  }
  in.Lighting = nullptr;
  // The renderer's lights in the medium's data coordinates (through the inverse prop matrix).
  vtkNew<vtkMatrix4x4> toData;
  vtkMatrix4x4::Invert(volume->GetMatrix(), toData);
  vtkPhotonTracer* tracer = in.Tracer;
  tracer->RemoveAllLights();
  in.Analysis->RemoveAllLights();
  int lightCount = 0;
  lights->InitTraversal(it);
  while (vtkLight* light = lights->GetNextLight(it))
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    vtkNew<vtkLight> copy;
    copy->DeepCopy(light);
    copy->SetLightTypeToSceneLight();
    copy->SetTransformMatrix(nullptr);
    double p[4] = { 0, 0, 0, 1 }, f[4] = { 0, 0, 0, 1 };
    light->GetTransformedPosition(p);
    light->GetTransformedFocalPoint(f);
    toData->MultiplyPoint(p, p);
    toData->MultiplyPoint(f, f);
    copy->SetPosition(p[0] / p[3], p[1] / p[3], p[2] / p[3]);
    copy->SetFocalPoint(f[0] / f[3], f[1] / f[3], f[2] / f[3]);
    tracer->AddLight(copy);
    in.Analysis->AddLight(copy);
    ++lightCount;
  }
  // Only the effects the scene needs: the plan, now with the lights, decides whether the photon
  // pass and the Lattice-Boltzmann pass would change the image.
  if (!in.Analysis->Analyze() || !this->DecidePlan())
  {
    vtkErrorMacro("The scene analysis with the renderer's lights failed (see the error above).");
    return false;
  }
  if (in.Plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING) && lightCount > 0)
  {
    tracer->SetContext(in.ViewPass->GetContext());
    tracer->SetInputData(in.Medium);
    tracer->SetNumberOfPhotons(this->NumberOfPhotons);
    tracer->SetSeed(static_cast<unsigned int>(this->Seed));
    if (this->QualityPresetApplied)
    {
      tracer->SetMinimumStep(in.Plan->GetRecommendedPhotonMinimumStep());
      tracer->SetPrimaryTolerance(in.Plan->GetRecommendedOctreeTolerance());
      tracer->SetSecondaryTolerance(4.0 * in.Plan->GetRecommendedOctreeTolerance());
    }
    tracer->Update();
    if (tracer->GetOutput()->GetNumberOfPoints() == 0)
    {
      vtkErrorMacro("The light pass (vtkPhotonTracer) failed; see its error above.");
      return false;
    }
    in.Lighting = vtkSmartPointer<vtkImageData>::New();
    in.Lighting->ShallowCopy(tracer->GetOutput());
    if (in.Plan->IsEnabled(vtkEffectPlan::MULTIPLE_SCATTERING))
    {
      // Multiple scattering: Lattice-Boltzmann lighting driven by the photon pass's S1.
      vtkNew<vtkLatticeBoltzmannLighting> lbl;
      lbl->SetContext(in.ViewPass->GetContext());
      lbl->SetInputData(in.Medium);
      lbl->SetLightingData(in.Lighting);
      if (this->QualityPresetApplied)
      {
        lbl->SetTolerance(in.Plan->GetRecommendedLatticeTolerance());
        lbl->SetBlockSize(in.Plan->GetRecommendedLatticeBlockSize());
      }
      lbl->Update();
      if (lbl->GetOutput()->GetNumberOfPoints() == 0)
      {
        vtkErrorMacro("The multiple-scattering pass (vtkLatticeBoltzmannLighting) failed; see "
                      "its error above.");
        in.Lighting = nullptr;
        return false;
      }
      in.Lighting->ShallowCopy(lbl->GetOutput());
    }
    ++this->NumberOfLightPassRuns;
  }
  if (!in.ViewPass->SetLighting(in.Lighting))
  {
    in.Lighting = nullptr;
    return false;
  }
  in.LightKey = key.str();
  return true;
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  Internals& in = *this->Internal;
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window)
  {
    vtkErrorMacro("vtkRefractiveVolumeMapper draws into an OpenGL render window; got "
      << (renderer->GetRenderWindow() ? renderer->GetRenderWindow()->GetClassName() : "none"));
    return;
  }
  if (!this->UpdateMedium(volume) || !this->UpdateLighting(renderer, volume))
  {
    return;
  }

  int width, height, x0, y0;
  renderer->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  if (width < 1 || height < 1)
  {
    return;
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  const size_t pixels = static_cast<size_t>(width) * height;

  // Depth of the opaque geometry drawn so far -> path-length limit along each pixel's ray.
  std::vector<float> depth(pixels, 1.0f);
  window->GetZbufferData(x0, y0, x0 + width - 1, y0 + height - 1, depth.data());
  vtkRefractaViewPass::RayFrame frame;
  if (!vtkRefractaViewPass::ComputeRayFrame(
        camera, in.Medium, volume->GetMatrix(), width, height, frame))
  {
    vtkErrorMacro("The renderer's camera is degenerate.");
    return;
  }
  std::ostringstream key;
  key.precision(17);
  key << in.MediumKey << "|" << in.LightKey << "|" << camera << ":" << camera->GetMTime() << ":"
      << width << "x" << height << "+" << x0 << "+" << y0 << ":" << in.ViewPass->GetMTime();
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      key << ":" << frame.WorldToLocal[r][c];
    }
  }
  if (key.str() != in.ViewKey || depth != in.Depth)
  {
    vtkMatrix4x4* projection =
      camera->GetCompositeProjectionTransformMatrix(renderer->GetTiledAspectRatio(), -1, 1);
    vtkNew<vtkMatrix4x4> inverse;
    vtkMatrix4x4::Invert(projection, inverse);
    std::vector<float> limits(pixels, std::numeric_limits<float>::infinity());
    double w[3] = { frame.W[0], frame.W[1], frame.W[2] };
    const double wLength = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int j = 0; j < height; ++j)
    {
      for (int i = 0; i < width; ++i)
      {
        const size_t p = i + static_cast<size_t>(width) * j;
        if (depth[p] >= 1.0f)
        {
          continue; // nothing drawn there: the ray runs to the background
        }
        const double sx = 2.0 * (i + 0.5) / width - 1.0, sy = 2.0 * (j + 0.5) / height - 1.0;
        double ndc[4] = { sx, sy, 2.0 * depth[p] - 1.0, 1.0 }, world[4];
        inverse->MultiplyPoint(ndc, world);
        double local[3];
        for (int r = 0; r < 3; ++r)
        {
          local[r] = (frame.WorldToLocal[r][0] * world[0] + frame.WorldToLocal[r][1] * world[1] +
                       frame.WorldToLocal[r][2] * world[2]) /
              world[3] +
            frame.WorldToLocal[r][3];
        }
        double distance;
        if (frame.Parallel)
        {
          double along = 0;
          for (int r = 0; r < 3; ++r)
          {
            const double origin = frame.Eye[r] + sx * frame.U[r] + sy * frame.V[r];
            along += (local[r] - origin) * w[r] / wLength;
          }
          distance = along;
        }
        else
        {
          distance = std::sqrt(vtkMath::Distance2BetweenPoints(local, frame.Eye));
        }
        limits[p] = static_cast<float>(std::max(distance, 0.0));
      }
    }
    in.ViewPass->SetBackgroundColor(0, 0, 0);
    in.ViewPass->SetEnvironmentMap(nullptr);
    if (!in.ViewPass->Render(
          camera, width, height, volume->GetMatrix(), limits.data(), in.Image, &in.Transmittance))
    {
      in.ViewKey.clear();
      return;
    }
    ++this->NumberOfViewPassRuns;
    in.ViewKey = key.str();
    in.Depth = std::move(depth);
  }

  // Per-channel compositing in two blended draws: first dst *= T (blend ZERO, SRC_COLOR), then
  // dst += E L (blend ONE, ONE). Together: dst = E L + T dst, channel by channel.
  std::vector<float> radiance(pixels * 4), transmittance(pixels * 4);
  const float exposure = static_cast<float>(this->Exposure);
  for (size_t p = 0; p < pixels; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      radiance[4 * p + c] = std::min(std::max(exposure * in.Image[4 * p + c], 0.0f), 1.0f);
      transmittance[4 * p + c] = std::min(std::max(in.Transmittance[4 * p + c], 0.0f), 1.0f);
    }
    radiance[4 * p + 3] = 0.0f;
    transmittance[4 * p + 3] = 1.0f;
  }
  vtkOpenGLState* state = window->GetState();
  vtkOpenGLState::ScopedglBlendFuncSeparate blendSaver(state);
  vtkOpenGLState::ScopedglEnableDisable blendEnable(state, GL_BLEND);
  vtkOpenGLState::ScopedglEnableDisable depthEnable(state, GL_DEPTH_TEST);
  vtkOpenGLState::ScopedglDepthMask depthMask(state);
  state->vtkglEnable(GL_BLEND);
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglBlendFuncSeparate(GL_ZERO, GL_SRC_COLOR, GL_ZERO, GL_ONE);
  window->DrawPixels(x0, y0, x0 + width - 1, y0 + height - 1, 4, VTK_FLOAT, transmittance.data());
  state->vtkglBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);
  window->DrawPixels(x0, y0, x0 + width - 1, y0 + height - 1, 4, VTK_FLOAT, radiance.data());
}

//------------------------------------------------------------------------------
void vtkRefractiveVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RefractiveIndexFunction: " << this->Internal->IndexFunction.Get() << "\n";
  os << indent << "Anisotropy: " << this->Anisotropy << "\n";
  os << indent << "EmissionScale: " << this->EmissionScale << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
  os << indent << "NumberOfPhotons: " << this->NumberOfPhotons << "\n";
  os << indent << "QualityPresetApplied: " << this->QualityPresetApplied << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MultipleScattering: " << this->MultipleScattering << "\n";
  os << indent << "LightingData: " << this->Internal->LightingData.Get() << "\n";
  os << indent << "NumberOfMediumBuilds: " << this->NumberOfMediumBuilds << "\n";
  os << indent << "NumberOfLightPassRuns: " << this->NumberOfLightPassRuns << "\n";
  os << indent << "NumberOfViewPassRuns: " << this->NumberOfViewPassRuns << "\n";
  os << indent << "ViewPass:\n";
  this->Internal->ViewPass->PrintSelf(os, indent.GetNextIndent());
}
