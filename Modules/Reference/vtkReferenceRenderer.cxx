#include "vtkReferenceRenderer.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkReferencePathTracer.h"
#include "vtkReferenceView.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaHostThreads.h"
#include "vtkRefractaSettings.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkReferenceRenderer);
vtkRefractaCxxSetClampMacro(vtkReferenceRenderer, IntegratorTolerance, 1e-14, 1e-1);
vtkRefractaCxxSetClampMacro(vtkReferenceRenderer, MaximumStep, 1e-4, 1e3);
vtkRefractaCxxSetClampMacro(vtkReferenceRenderer, DirectionalLightAngularRadius, 1e-4, 45.0);
vtkRefractaCxxSetClampMacro(vtkReferenceRenderer, LightRadius, 0.0, VTK_DOUBLE_MAX);
vtkRefractaCxxSetClampMacro(vtkReferenceRenderer, Exposure, 0.0, VTK_DOUBLE_MAX);
vtkRefractaCxxSetVector3Macro(vtkReferenceRenderer, BackgroundColor);
vtkRefractaCxxSetVector3Macro(vtkReferenceRenderer, EnvironmentUp);
vtkRefractaCxxSetVector3Macro(vtkReferenceRenderer, EnvironmentRight);

namespace
{
using refracta::reference::BuildLights;
using refracta::reference::HasPositionalLight;
using refracta::reference::HGPhase;
using refracta::reference::Medium;
using refracta::reference::Normalized;
using refracta::reference::RayState;
using refracta::reference::Rng;
using refracta::reference::SampleHG;
using refracta::reference::Scene;
using refracta::reference::ToVec3;
using refracta::reference::Tracer;
using refracta::reference::Vec3;
using refracta::reference::View;

inline unsigned char ToneMap(double v, double exposure)
{
  double c = std::min(std::max(exposure * v, 0.0), 1.0);
  if (!(c == c))
  {
    c = 0;
  }
  c = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(255.0 * c));
}
} // namespace

//------------------------------------------------------------------------------
vtkReferenceRenderer::vtkReferenceRenderer()
{
  // Debian's ParaView VTK runs vtkSMPTools on one core unless told otherwise: the pixels and the
  // photon blocks below are its loops.
  vtkRefractaHostThreads::UseThreadedBackend();
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
  this->Lights = vtkSmartPointer<vtkLightCollection>::New();
}

vtkReferenceRenderer::~vtkReferenceRenderer() = default;

void vtkReferenceRenderer::SetCamera(vtkCamera* camera)
{
  if (this->Camera != camera)
  {
    this->Camera = camera;
    this->Modified();
  }
}
vtkCamera* vtkReferenceRenderer::GetCamera()
{
  return this->Camera;
}

void vtkReferenceRenderer::AddLight(vtkLight* light)
{
  if (light)
  {
    this->Lights->AddItem(light);
    this->Modified();
  }
}
void vtkReferenceRenderer::RemoveAllLights()
{
  this->Lights->RemoveAllItems();
  this->Modified();
}
void vtkReferenceRenderer::SetLights(vtkLightCollection* lights)
{
  this->Lights->RemoveAllItems();
  if (lights)
  {
    lights->InitTraversal();
    while (vtkLight* l = lights->GetNextItem())
    {
      this->Lights->AddItem(l);
    }
  }
  this->Modified();
}
vtkLightCollection* vtkReferenceRenderer::GetLights()
{
  return this->Lights;
}

void vtkReferenceRenderer::SetImageSize(int width, int height)
{
  width = std::min(std::max(width, 1), 16384);
  height = std::min(std::max(height, 1), 16384);
  if (width != this->ImageSize[0] || height != this->ImageSize[1])
  {
    this->ImageSize[0] = width;
    this->ImageSize[1] = height;
    this->Modified();
  }
}

void vtkReferenceRenderer::SetEnvironmentMap(vtkImageData* image)
{
  if (this->EnvironmentMap != image)
  {
    this->EnvironmentMap = image;
    this->Modified();
  }
}
vtkImageData* vtkReferenceRenderer::GetEnvironmentMap()
{
  return this->EnvironmentMap;
}

void vtkReferenceRenderer::SetSurfaces(vtkRefractaSurfaceSet* surfaces)
{
  if (this->Surfaces != surfaces)
  {
    this->Surfaces = surfaces;
    this->Modified();
  }
}
vtkRefractaSurfaceSet* vtkReferenceRenderer::GetSurfaces()
{
  return this->Surfaces;
}

vtkMTimeType vtkReferenceRenderer::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->Camera)
  {
    t = std::max(t, this->Camera->GetMTime());
  }
  if (this->EnvironmentMap)
  {
    t = std::max(t, this->EnvironmentMap->GetMTime());
  }
  if (this->Surfaces)
  {
    t = std::max(t, this->Surfaces->GetMTime());
  }
  this->Lights->InitTraversal();
  while (vtkLight* l = this->Lights->GetNextItem())
  {
    t = std::max(t, l->GetMTime());
  }
  return t;
}

//------------------------------------------------------------------------------
double vtkReferenceRenderer::HenyeyGreensteinPhase(double g, double cosTheta)
{
  const double c = std::min(std::max(cosTheta, -1.0), 1.0);
  return HGPhase(g, 1 - c);
}

void vtkReferenceRenderer::SampleHenyeyGreenstein(
  double g, const double in[3], double u1, double u2, double out[3])
{
  const Vec3 w = SampleHG(g, Normalized(ToVec3(in)), u1, u2);
  out[0] = w.x;
  out[1] = w.y;
  out[2] = w.z;
}

int vtkReferenceRenderer::TraceRay(vtkImageData* medium, const double origin[3],
  const double direction[3], double arcLength, double endPoint[3], double endDirection[3])
{
  vtkNew<vtkMediumValidator> validator;
  if (!validator->Validate(medium))
  {
    vtkErrorMacro("TraceRay: the medium is not valid: " << validator->GetErrorMessage());
    return -1;
  }
  Medium m;
  m.Load(medium);
  Tracer tr;
  tr.M = &m;
  tr.Tol = this->IntegratorTolerance;
  tr.MaxStep = this->MaximumStep;
  Vec3 x = m.ToLocalPoint(origin);
  Vec3 d = Normalized(m.ToLocalVector(direction));
  double remaining = arcLength;
  int64_t steps = 0;
  double t0, t1;
  if (!m.Inside(x, 0) && m.Intersect(x, d, t0, t1) && t0 < remaining)
  {
    x = x + t0 * d;
    remaining -= t0;
  }
  if (m.Inside(x, 0) && remaining > 0)
  {
    RayState r;
    tr.Start(r, x, d);
    double moved;
    int hit;
    tr.Advance(r, remaining, moved, hit, steps);
    remaining -= moved;
    x = r.X;
    d = r.Dir;
  }
  if (remaining > 0)
  {
    x = x + remaining * d;
  }
  const Vec3 pw = m.ToWorldPoint(x), dw = Normalized(m.ToWorldVector(d));
  for (int i = 0; i < 3; ++i)
  {
    endPoint[i] = pw[i];
    endDirection[i] = dw[i];
  }
  return static_cast<int>(steps);
}

//------------------------------------------------------------------------------
int vtkReferenceRenderer::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
    return 1;
  }
  return 0;
}

int vtkReferenceRenderer::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int extent[6] = { 0, this->ImageSize[0] - 1, 0, this->ImageSize[1] - 1, 0, 0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  const double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 3);
  return 1;
}

int vtkReferenceRenderer::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The whole medium is needed whatever part of the image is requested.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo && inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(),
      inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
  return 1;
}

//------------------------------------------------------------------------------
bool vtkReferenceRenderer::BuildScene(vtkImageData* medium, Scene& scene, View& view)
{
  vtkNew<vtkMediumValidator> validator;
  if (!medium || !validator->Validate(medium))
  {
    vtkErrorMacro("Input 0 is not a valid Refracta medium (a vtkImageData with the point arrays of "
                  "vtkRefractaMedium): "
      << (medium ? validator->GetErrorMessage() : "no input"));
    return false;
  }
  if (!this->Camera)
  {
    vtkErrorMacro("No camera: call SetCamera(vtkCamera*) before rendering.");
    return false;
  }
  for (int c = 0; c < 3; ++c)
  {
    if (!std::isfinite(this->BackgroundColor[c]) || this->BackgroundColor[c] < 0)
    {
      vtkErrorMacro("BackgroundColor component " << c << " is " << this->BackgroundColor[c]
                                                 << "; it must be finite and >= 0.");
      return false;
    }
  }

  scene.M.Load(medium);
  const Medium& m = scene.M;

  // Environment map.
  if (this->EnvironmentMap)
  {
    vtkImageData* env = this->EnvironmentMap;
    int size[2];
    std::string error;
    if (!vtkRefractaEnvironmentMap::ReadRadiance(env, scene.Env.Rgb, size, error))
    {
      vtkErrorMacro("EnvironmentMap: " << error);
      return false;
    }
    scene.Env.W = size[0];
    scene.Env.H = size[1];
    if (!vtkRefractaEnvironmentMap::GetChecker(
          env, scene.Env.CheckerSquares, scene.Env.Checker1, scene.Env.Checker2))
    {
      scene.Env.CheckerSquares[0] = scene.Env.CheckerSquares[1] = 0;
    }
  }
  scene.Env.Colour = ToVec3(this->BackgroundColor);
  std::copy(this->EnvironmentUp, this->EnvironmentUp + 3, scene.Env.Up);
  std::copy(this->EnvironmentRight, this->EnvironmentRight + 3, scene.Env.Right);
  // A black background has nothing to sample: it illuminates nothing either way.
  scene.EnvLight = this->BackgroundIlluminates && scene.Env.BuildSampling();
  const std::string surfaceError = scene.Surf.Load(this->Surfaces, m);
  if (!surfaceError.empty())
  {
    vtkErrorMacro("Surfaces: " << surfaceError << ".");
    return false;
  }
  // LightRadius = 0 is a delta light, as in every pass. This estimator reaches a point or spot
  // light only by tracing a (possibly curved) ray that hits its sphere, which a point cannot be:
  // it needs an explicit radius, and says so rather than choosing one.
  const double radius = this->LightRadius;
  if (!(radius > 0) && HasPositionalLight(this->Lights))
  {
    vtkErrorMacro("LightRadius is 0 (a delta point or spot light), but the reference renderer "
                  "connects paths to point and spot lights by hitting their sphere and cannot "
                  "estimate a delta light; set LightRadius > 0 (world units; e.g. "
      << 0.01 * m.Diagonal << ", 1% of this medium's diagonal).");
    return false;
  }
  const std::string lightError = BuildLights(
    m, this->Lights, this->Camera, this->DirectionalLightAngularRadius, radius, scene.Lights);
  if (!lightError.empty())
  {
    vtkErrorMacro(<< lightError);
    return false;
  }
  scene.MaxDepth = this->MaximumScatteringDepth;
  scene.RouletteDepth = this->RouletteDepth;
  scene.MaxVertices = this->MaximumPathVertices;
  scene.T.M = &scene.M;
  scene.T.Tol = this->IntegratorTolerance;
  scene.T.MaxStep = this->MaximumStep;
  scene.T.Surf = scene.Surf.Empty() ? nullptr : &scene.Surf;
  scene.TLight = scene.T;
  scene.TLight.Lights = &scene.Lights;

  // Camera in the grid-local frame.
  vtkCamera* cam = this->Camera;
  double pos[3], foc[3], up[3];
  cam->GetPosition(pos);
  cam->GetFocalPoint(foc);
  cam->GetViewUp(up);
  const Vec3 eye = m.ToLocalPoint(pos);
  const Vec3 fwd = Normalized(m.ToLocalPoint(foc) - eye);
  Vec3 vup = m.ToLocalVector(up);
  vup = vup - glm::dot(vup, fwd) * fwd;
  if (glm::length(vup) < 1e-12)
  {
    vtkErrorMacro("The camera's view up is parallel to its direction of projection.");
    return false;
  }
  vup = Normalized(vup);
  view.Eye = eye;
  view.Forward = fwd;
  view.Up = vup;
  view.Right = glm::cross(fwd, vup);
  view.Width = this->ImageSize[0];
  view.Height = this->ImageSize[1];
  view.Aspect = static_cast<double>(view.Width) / view.Height;
  view.Parallel = cam->GetParallelProjection() != 0;
  view.HalfHeight = view.Parallel ? cam->GetParallelScale()
                                  : std::tan(vtkMath::RadiansFromDegrees(cam->GetViewAngle()) / 2);
  return true;
}

//------------------------------------------------------------------------------
int vtkReferenceRenderer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const auto start = std::chrono::steady_clock::now();
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkImageData* medium = vtkImageData::GetData(inputVector[0], 0);
  if (!output)
  {
    vtkErrorMacro("No output image.");
    return 0;
  }
  output->Initialize();

  Scene scene;
  View view;
  if (!this->BuildScene(medium, scene, view))
  {
    return 0;
  }
  const Medium& m = scene.M;
  const int W = view.Width, H = view.Height;
  const double radius = this->LightRadius;
  const int spp = this->SamplesPerPixel;
  const bool grey = m.Grey;
  const bool jitter = this->PixelJitter;
  const uint64_t seed = this->Seed;
  const int64_t numPixels = static_cast<int64_t>(W) * H;
  std::vector<double> mean(3 * numPixels), stderrs(3 * numPixels);
  std::atomic<int64_t> truncated(0), nonFinite(0);

  auto renderPixels = [&](vtkIdType begin, vtkIdType end)
  {
    int64_t localTrunc = 0, localNonFinite = 0;
    for (vtkIdType p = begin; p < end; ++p)
    {
      const int i = static_cast<int>(p % W), j = static_cast<int>(p / W);
      Rng rng(seed, static_cast<uint64_t>(p));
      double sum[3] = { 0, 0, 0 }, sum2[3] = { 0, 0, 0 };
      for (int s = 0; s < spp; ++s)
      {
        const double jx = jitter ? rng.Uniform() : 0.5, jy = jitter ? rng.Uniform() : 0.5;
        Vec3 o, d;
        view.Ray(i, j, jx, jy, o, d);
        Vec3 val(0.0);
        bool trunc = false;
        if (grey)
        {
          val = scene.Trace(o, d, -1, rng, trunc);
        }
        else
        {
          for (int c = 0; c < 3; ++c)
          {
            val += scene.Trace(o, d, c, rng, trunc);
          }
        }
        localTrunc += trunc ? 1 : 0;
        if (!std::isfinite(val.x) || !std::isfinite(val.y) || !std::isfinite(val.z))
        {
          // Never expected; counted and reported (field data NonFiniteSamples) rather than
          // spreading a NaN through the image.
          ++localNonFinite;
          val = Vec3(0.0);
        }
        for (int c = 0; c < 3; ++c)
        {
          sum[c] += val[c];
          sum2[c] += val[c] * val[c];
        }
      }
      for (int c = 0; c < 3; ++c)
      {
        const double mu = sum[c] / spp;
        mean[3 * p + c] = mu;
        if (spp > 1)
        {
          const double var = std::max(0.0, (sum2[c] - spp * mu * mu) / (spp - 1));
          stderrs[3 * p + c] = std::sqrt(var / spp);
        }
        else
        {
          stderrs[3 * p + c] = -1;
        }
      }
    }
    truncated += localTrunc;
    nonFinite += localNonFinite;
  };

  // Rows in blocks so that progress can be reported (and aborts honoured) between parallel runs.
  const int blocks = std::min(H, 20);
  for (int b = 0; b < blocks && !this->GetAbortExecute(); ++b)
  {
    const int64_t r0 = static_cast<int64_t>(H) * b / blocks;
    const int64_t r1 = static_cast<int64_t>(H) * (b + 1) / blocks;
    vtkSMPTools::For(r0 * W, r1 * W, 1, renderPixels);
    this->UpdateProgress(static_cast<double>(b + 1) / blocks);
  }

  this->WriteImage(output, W, H, mean, stderrs);

  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  auto addField = [output](const char* name, double value, bool integer)
  { vtkReferenceRenderer::AddFieldValue(output, name, value, integer); };
  addField("SamplesPerPixel", spp, true);
  addField("RenderSeconds", seconds, false);
  addField("Seed", static_cast<double>(this->Seed), false);
  addField("TruncatedPaths", static_cast<double>(truncated.load()), false);
  addField("NonFiniteSamples", static_cast<double>(nonFinite.load()), false);
  addField("LightRadius", radius, false);
  return 1;
}

//------------------------------------------------------------------------------
void vtkReferenceRenderer::WriteImage(vtkImageData* output, int W, int H,
  const std::vector<double>& mean, const std::vector<double>& stderrs)
{
  const int64_t numPixels = static_cast<int64_t>(W) * H;
  output->SetExtent(0, W - 1, 0, H - 1, 0, 0);
  output->SetSpacing(1, 1, 1);
  output->SetOrigin(0, 0, 0);
  vtkNew<vtkFloatArray> hdr;
  hdr->SetName("HDR");
  hdr->SetNumberOfComponents(4);
  hdr->SetNumberOfTuples(numPixels);
  vtkNew<vtkFloatArray> se;
  se->SetName("StandardError");
  se->SetNumberOfComponents(3);
  se->SetNumberOfTuples(numPixels);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetName("RGB");
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(numPixels);
  for (int64_t p = 0; p < numPixels; ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      hdr->SetTypedComponent(p, c, static_cast<float>(mean[3 * p + c]));
      se->SetTypedComponent(p, c, static_cast<float>(stderrs[3 * p + c]));
      rgb->SetTypedComponent(p, c, ToneMap(mean[3 * p + c], this->Exposure));
    }
    hdr->SetTypedComponent(p, 3, 1.0f);
  }
  output->GetPointData()->AddArray(hdr);
  output->GetPointData()->AddArray(se);
  output->GetPointData()->SetScalars(rgb);
}

void vtkReferenceRenderer::AddFieldValue(
  vtkImageData* output, const char* name, double value, bool integer)
{
  if (integer)
  {
    vtkNew<vtkIntArray> a;
    a->SetName(name);
    a->InsertNextValue(static_cast<int>(value));
    output->GetFieldData()->AddArray(a);
  }
  else
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    output->GetFieldData()->AddArray(a);
  }
}

//------------------------------------------------------------------------------
void vtkReferenceRenderer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Camera: " << this->Camera.Get() << "\n";
  os << indent << "Lights: " << this->Lights->GetNumberOfItems() << "\n";
  os << indent << "ImageSize: " << this->ImageSize[0] << " x " << this->ImageSize[1] << "\n";
  os << indent << "BackgroundColor: " << this->BackgroundColor[0] << " " << this->BackgroundColor[1]
     << " " << this->BackgroundColor[2] << "\n";
  os << indent << "EnvironmentMap: " << this->EnvironmentMap.Get() << "\n";
  os << indent << "EnvironmentUp: (" << this->EnvironmentUp[0] << ", " << this->EnvironmentUp[1]
     << ", " << this->EnvironmentUp[2] << ")\n";
  os << indent << "EnvironmentRight: (" << this->EnvironmentRight[0] << ", "
     << this->EnvironmentRight[1] << ", " << this->EnvironmentRight[2] << ")\n";
  os << indent << "BackgroundIlluminates: " << this->BackgroundIlluminates << "\n";
  os << indent << "Surfaces: " << this->Surfaces.Get() << "\n";
  os << indent << "SamplesPerPixel: " << this->SamplesPerPixel << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "MaximumScatteringDepth: " << this->MaximumScatteringDepth << "\n";
  os << indent << "RouletteDepth: " << this->RouletteDepth << "\n";
  os << indent << "MaximumPathVertices: " << this->MaximumPathVertices << "\n";
  os << indent << "IntegratorTolerance: " << this->IntegratorTolerance << "\n";
  os << indent << "MaximumStep: " << this->MaximumStep << "\n";
  os << indent << "DirectionalLightAngularRadius: " << this->DirectionalLightAngularRadius << "\n";
  os << indent << "LightRadius: " << this->LightRadius << "\n";
  os << indent << "PixelJitter: " << this->PixelJitter << "\n";
  os << indent << "Exposure: " << this->Exposure << "\n";
}
