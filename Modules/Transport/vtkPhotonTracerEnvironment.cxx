// The environment light of vtkPhotonTracer: the background (EnvironmentMap or BackgroundColor)
// emits photons, importance-sampled by luminance x solid angle, from a disc covering the emission
// sphere (see the class description and Kernels/photon_environment.cl).
#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkRefractaEnvironmentMap.h"
#include "vtkRefractaGridFrame.h"

#include <algorithm>
#include <cmath>

using namespace vtkPhotonTracerDetail;

namespace
{
// Rec. 709 luminance of linear RGB: the weight of the importance sampling.
double Luminance(const double rgb[3])
{
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

// Solid angle of a texel of row j (of H rows, W columns): (2 pi / W) (sin lat1 - sin lat0), with
// latitude pi (v - 1/2) and row j spanning v in [j / H, (j + 1) / H].
double TexelSolidAngle(int j, int width, int height)
{
  const double s0 = -std::cos(vtkMath::Pi() * j / height);
  const double s1 = -std::cos(vtkMath::Pi() * (j + 1) / height);
  return 2.0 * vtkMath::Pi() / width * (s1 - s0);
}
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::SetEnvironmentMap(vtkImageData* image)
{
  if (this->EnvironmentMap != image)
  {
    this->EnvironmentMap = image;
    this->Modified();
  }
}

vtkImageData* vtkPhotonTracer::GetEnvironmentMap()
{
  return this->EnvironmentMap;
}

//------------------------------------------------------------------------------
// The environment's linear RGB radiance, W x H texels (row 0 first): the map, or the uniform
// BackgroundColor as one texel covering the sphere. False after an error naming the bad input.
bool vtkPhotonTracer::ReadEnvironmentRadiance(std::vector<double>& rgb, int size[2])
{
  vtkImageData* image = this->EnvironmentMap;
  if (!image)
  {
    size[0] = size[1] = 1;
    rgb.assign(this->BackgroundColor, this->BackgroundColor + 3);
  }
  else
  {
    std::string error;
    if (!vtkRefractaEnvironmentMap::ReadRadiance(image, rgb, size, error))
    {
      vtkErrorMacro("EnvironmentMap: " << error << " The environment cannot light the scene.");
      return false;
    }
  }
  for (size_t k = 0; k < rgb.size(); ++k)
  {
    if (!std::isfinite(rgb[k]) || rgb[k] < 0)
    {
      vtkErrorMacro("The environment's radiance ("
        << (image ? "EnvironmentMap texel " : "BackgroundColor ") << k / 3 << ", channel " << k % 3
        << ") is " << rgb[k] << "; it must be finite and >= 0.");
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
// Appends the environment to run.Lights (when it illuminates and emits anything) and fills run.Env:
// texels, CDFs, the basis and the emission sphere in the grid-local frame.
bool vtkPhotonTracer::SetUpEnvironment(Internals& run)
{
  if (!this->BackgroundIlluminates)
  {
    return true;
  }
  EnvironmentSetup& env = run.Env;
  std::vector<double> rgb;
  if (!this->ReadEnvironmentRadiance(rgb, env.Size))
  {
    return false;
  }
  double right[3], up[3], front[3];
  if (!vtkRefractaEnvironmentMap::ComputeBasis(
        this->EnvironmentUp, this->EnvironmentRight, right, up, front))
  {
    vtkErrorMacro("EnvironmentUp is zero or parallel to EnvironmentRight; they must span a plane "
                  "to orient the environment that lights the scene.");
    return false;
  }
  // World (the surfaces' frame) -> the medium's data frame (MediumToWorld is rigid: its inverse
  // rotation is the transpose) -> grid-local.
  vtkNew<vtkRefractaGridFrame> grid;
  grid->SetImage(run.Input);
  auto toLocal = [&](const double world[3], double local[3])
  {
    double data[3] = { world[0], world[1], world[2] };
    if (this->MediumToWorld)
    {
      for (int r = 0; r < 3; ++r)
      {
        data[r] = this->MediumToWorld->GetElement(0, r) * world[0] +
          this->MediumToWorld->GetElement(1, r) * world[1] +
          this->MediumToWorld->GetElement(2, r) * world[2];
      }
    }
    grid->WorldToLocalVector(data, local);
    Normalize(local);
  };
  toLocal(right, env.Right);
  toLocal(up, env.Up);
  toLocal(front, env.Front);

  const int w = env.Size[0], h = env.Size[1];
  env.Texels.resize(static_cast<size_t>(w) * h);
  env.Conditional.resize(static_cast<size_t>(w) * h);
  env.Marginal.resize(h);
  double total = 0, flux[3] = { 0, 0, 0 };
  std::vector<double> rowSums(h, 0.0);
  for (int j = 0; j < h; ++j)
  {
    const double omega = TexelSolidAngle(j, w, h);
    for (int i = 0; i < w; ++i)
    {
      const size_t k = static_cast<size_t>(j) * w + i;
      const double* L = &rgb[3 * k];
      const double lum = Luminance(L);
      env.Texels[k] = Float4(L[0], L[1], L[2], lum);
      rowSums[j] += lum * omega;
      env.Conditional[k] = static_cast<float>(rowSums[j]);
      for (int c = 0; c < 3; ++c)
      {
        flux[c] += L[c] * omega;
      }
    }
    for (int i = 0; i < w; ++i)
    {
      float& cdf = env.Conditional[static_cast<size_t>(j) * w + i];
      cdf = rowSums[j] > 0 ? static_cast<float>(cdf / rowSums[j]) : 1.0f;
    }
    env.Conditional[static_cast<size_t>(j) * w + w - 1] = 1.0f;
    total += rowSums[j];
    env.Marginal[j] = static_cast<float>(total);
  }
  if (!(total > 0))
  {
    return true; // a black sky (or one with only zero-luminance colours) emits nothing
  }
  for (int j = 0; j < h; ++j)
  {
    env.Marginal[j] = static_cast<float>(env.Marginal[j] / total);
  }
  env.Marginal[h - 1] = 1.0f;

  // The emission sphere around the box the lights aim at (grid-local), grown by 1% so that
  // photons start strictly outside it.
  double halfDiag2 = 0;
  for (int c = 0; c < 3; ++c)
  {
    env.Centre[c] = 0.5 * (run.EmitLo[c] + run.EmitHi[c]);
    halfDiag2 += 0.25 * (run.EmitHi[c] - run.EmitLo[c]) * (run.EmitHi[c] - run.EmitLo[c]);
  }
  env.Radius = 1.01 * std::sqrt(halfDiag2) + 1e-9;
  const double discArea = vtkMath::Pi() * env.Radius * env.Radius;
  env.PowerFactor = discArea * total;

  LightSetup ls;
  ls.Environment = true;
  ls.Measure = discArea;
  for (int c = 0; c < 3; ++c)
  {
    ls.Colour[c] = flux[c];
  }
  ls.Bound = discArea * std::max({ flux[0], flux[1], flux[2] });
  run.Lights.push_back(ls);
  return true;
}

//------------------------------------------------------------------------------
// Launches photon_generate_environment for the environment's photons [offset, offset + count).
bool vtkPhotonTracer::GenerateEnvironmentPhotons(
  Internals& run, size_t light, unsigned int offset, unsigned int r1, unsigned int r2)
{
  const LightSetup& ls = run.Lights[light];
  const EnvironmentSetup& env = run.Env;
  vtkOpenCLContext* ctx = run.Context;
  const size_t texels = env.Texels.size();
  vtkOpenCLBuffer texelBuffer = run.Alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    texels * sizeof(cl_float4), env.Texels.data(), "environment radiance");
  vtkOpenCLBuffer marginal = run.Alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    env.Marginal.size() * sizeof(float), env.Marginal.data(), "environment marginal CDF");
  vtkOpenCLBuffer conditional = run.Alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    texels * sizeof(float), env.Conditional.data(), "environment conditional CDF");
  vtkOpenCLKernel generate = ctx->CreateKernel(run.Trace, "photon_generate_environment", this);
  if (!texelBuffer || !marginal || !conditional || !generate)
  {
    return false;
  }
  const cl_uint count = ls.Photons;
  const cl_int width = env.Size[0], height = env.Size[1];
  const cl_float powerScale = static_cast<float>(env.PowerFactor / (count * run.Unit));
  if (!ctx->Check(vtkOpenCLSetKernelArgs(generate.Get(), run.Pos.Get(), run.Dirs.Get(),
                    run.Power.Get(), static_cast<cl_uint>(offset), count, texelBuffer.Get(),
                    marginal.Get(), conditional.Get(), width, height, Float4(env.Right),
                    Float4(env.Up), Float4(env.Front), Float4(env.Centre, env.Radius), powerScale,
                    Float4(run.EmitLo), Float4(run.EmitHi), static_cast<cl_uint>(r1),
                    static_cast<cl_uint>(r2), static_cast<cl_float>(run.LightLobes[light])),
        "clSetKernelArg(photon_generate_environment)", this) ||
    !Run1D(ctx, generate.Get(), count, "photon_generate_environment", this))
  {
    return false;
  }
  // The buffers are released when this returns: wait for the kernel that reads them.
  if (!ctx->Finish(this))
  {
    return false;
  }
  this->UsedEnvironment = true;
  this->EnvironmentPhotons = static_cast<int>(count);
  return true;
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::PrintEnvironment(ostream& os, vtkIndent indent)
{
  os << indent << "BackgroundIlluminates: " << this->BackgroundIlluminates << "\n";
  os << indent << "BackgroundColor: (" << this->BackgroundColor[0] << ", "
     << this->BackgroundColor[1] << ", " << this->BackgroundColor[2] << ")\n";
  os << indent << "EnvironmentMap: " << this->EnvironmentMap.Get() << "\n";
  os << indent << "EnvironmentUp: (" << this->EnvironmentUp[0] << ", " << this->EnvironmentUp[1]
     << ", " << this->EnvironmentUp[2] << ")\n";
  os << indent << "EnvironmentRight: (" << this->EnvironmentRight[0] << ", "
     << this->EnvironmentRight[1] << ", " << this->EnvironmentRight[2] << ")\n";
  os << indent << "UsedEnvironment: " << this->UsedEnvironment << "\n";
}
