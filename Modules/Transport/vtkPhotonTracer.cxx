#include "vtkPhotonTracer.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMediumValidator.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include "photon_tallies.cl" // the layout of the tallies and counters, shared with the kernels

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPhotonTracer);

namespace
{
// Progress at the end of each stage, in proportion to the work measured for 2^20 photons in a
// curved, scattering 96^3 to 128^3 medium on the 2-core CPU (octree and gradient ~1%, generation
// ~1%, marching ~97%, resolve and smoothing ~1%).
constexpr double ProgressOctree = 0.01;
constexpr double ProgressGenerated = 0.02;
constexpr double ProgressMarched = 0.99;
// Automatic photon batches: each launch is sized to take about TargetBatchSeconds.
constexpr double TargetBatchSeconds = 0.05;
constexpr size_t MinimumBatch = 1024;
constexpr size_t MaximumBatch = size_t(1) << 20;

using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A float literal for -D options that the OpenCL compiler reads back as the same float.
std::string FloatLiteral(double value)
{
  std::ostringstream s;
  s.precision(9);
  s << std::scientific << static_cast<float>(value) << "f";
  return s.str();
}

cl_int4 Int4(const int d[3])
{
  cl_int4 v;
  v.s[0] = d[0];
  v.s[1] = d[1];
  v.s[2] = d[2];
  v.s[3] = 0;
  return v;
}

cl_float4 Float4(double x, double y, double z, double w = 0.0)
{
  cl_float4 v;
  v.s[0] = static_cast<float>(x);
  v.s[1] = static_cast<float>(y);
  v.s[2] = static_cast<float>(z);
  v.s[3] = static_cast<float>(w);
  return v;
}

cl_float4 Float4(const double a[3], double w = 0.0)
{
  return Float4(a[0], a[1], a[2], w);
}

uint32_t SplitMix(uint64_t& state)
{
  uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return static_cast<uint32_t>((z ^ (z >> 31)) >> 32);
}

double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

bool Normalize(double a[3])
{
  const double m = std::sqrt(Dot(a, a));
  if (!(m > 0.0) || !std::isfinite(m))
  {
    return false;
  }
  for (int c = 0; c < 3; ++c)
  {
    a[c] /= m;
  }
  return true;
}

// Two unit vectors completing `a` (unit) to an orthonormal basis.
void Basis(const double a[3], double b1[3], double b2[3])
{
  const double h[3] = { std::fabs(a[0]) < 0.9 ? 1.0 : 0.0, std::fabs(a[0]) < 0.9 ? 0.0 : 1.0, 0.0 };
  // b1 = normalize(h x a), b2 = a x b1
  b1[0] = h[1] * a[2] - h[2] * a[1];
  b1[1] = h[2] * a[0] - h[0] * a[2];
  b1[2] = h[0] * a[1] - h[1] * a[0];
  Normalize(b1);
  b2[0] = a[1] * b1[2] - a[2] * b1[1];
  b2[1] = a[2] * b1[0] - a[0] * b1[2];
  b2[2] = a[0] * b1[1] - a[1] * b1[0];
}

// The medium's arrays as float, with defaults and the facts that choose the kernel variant.
struct Medium
{
  int Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
  size_t Voxels = 0;
  std::vector<float> N, Gradient, Extinction, Albedo;
  bool HasGradient = false;
  bool Curved = false;
  bool Attenuates = false;
  bool Scatters = false;
  double Lo[3], Hi[3];           // domain box, grid-local
  double ProxyLo[3], ProxyHi[3]; // photon start box, grid-local
};

void CopyArray(
  vtkDataArray* array, int comps, float fallback, size_t voxels, std::vector<float>& out)
{
  out.assign(voxels * comps, fallback);
  if (!array)
  {
    return;
  }
  for (size_t v = 0; v < voxels; ++v)
  {
    for (int c = 0; c < comps; ++c)
    {
      out[v * comps + c] = static_cast<float>(array->GetComponent(static_cast<vtkIdType>(v), c));
    }
  }
}

void LoadMedium(vtkImageData* image, bool useProxy, Medium& m)
{
  image->GetDimensions(m.Dims);
  image->GetSpacing(m.Spacing);
  m.Voxels = static_cast<size_t>(m.Dims[0]) * m.Dims[1] * m.Dims[2];
  vtkPointData* pd = image->GetPointData();
  vtkDataArray* n = pd->GetArray(vtkRefractaMedium::RefractiveIndexName());
  vtkDataArray* g = pd->GetArray(vtkRefractaMedium::RefractiveIndexGradientName());
  vtkDataArray* e = pd->GetArray(vtkRefractaMedium::ExtinctionName());
  vtkDataArray* a = pd->GetArray(vtkRefractaMedium::AlbedoName());
  CopyArray(n, 1, 1.0f, m.Voxels, m.N);
  CopyArray(e, 3, 0.0f, m.Voxels, m.Extinction);
  CopyArray(a, 3, 0.0f, m.Voxels, m.Albedo);
  m.HasGradient = g != nullptr;
  if (g)
  {
    CopyArray(g, 3, 0.0f, m.Voxels, m.Gradient);
  }
  const auto range = std::minmax_element(m.N.begin(), m.N.end());
  m.Curved = *range.second > *range.first;
  int lo[3] = { m.Dims[0], m.Dims[1], m.Dims[2] };
  int hi[3] = { -1, -1, -1 };
  for (size_t v = 0; v < m.Voxels; ++v)
  {
    bool interesting = m.N[v] != 1.0f;
    for (int c = 0; c < 3; ++c)
    {
      const float st = m.Extinction[3 * v + c];
      m.Attenuates = m.Attenuates || st > 0.0f;
      m.Scatters = m.Scatters || (st > 0.0f && m.Albedo[3 * v + c] > 0.0f);
      interesting = interesting || st > 0.0f;
    }
    if (interesting)
    {
      const int ijk[3] = { static_cast<int>(v % m.Dims[0]),
        static_cast<int>((v / m.Dims[0]) % m.Dims[1]),
        static_cast<int>(v / (static_cast<size_t>(m.Dims[0]) * m.Dims[1])) };
      for (int c = 0; c < 3; ++c)
      {
        lo[c] = std::min(lo[c], ijk[c]);
        hi[c] = std::max(hi[c], ijk[c]);
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    m.Lo[c] = -0.5 * m.Spacing[c];
    m.Hi[c] = (m.Dims[c] - 0.5) * m.Spacing[c];
    m.ProxyLo[c] = m.Lo[c];
    m.ProxyHi[c] = m.Hi[c];
  }
  // The proxy grows the interesting voxels by two: trilinear sampling and the gradient reach one
  // voxel further each.
  if (useProxy && hi[0] >= 0)
  {
    for (int c = 0; c < 3; ++c)
    {
      m.ProxyLo[c] = std::max(m.Lo[c], (lo[c] - 2.5) * m.Spacing[c]);
      m.ProxyHi[c] = std::min(m.Hi[c], (hi[c] + 2.5) * m.Spacing[c]);
    }
  }
}

// One light converted to the grid-local frame, as the generation kernel takes it.
struct LightSetup
{
  bool Positional = false;
  double Origin[3], Axis[3], Basis1[3], Basis2[3];
  double SpotAxis[3] = { 0, 0, 1 };
  double SpotCos = -2.0; // < -1.5: no spot cone
  double Exponent = 0.0;
  double OneMinusCos = 2.0;
  double Measure = 0.0; // solid angle of the sampled cap, or area of the directional rectangle
  double Colour[3];
  double Bound = 0.0;  // largest channel of the power sent towards the box
  double Extent = 0.0; // sphere radius (positional, local units) or sin(angular radius)
  unsigned int Photons = 0;
};

// Device buffers with bookkeeping of the bytes allocated.
struct Allocator
{
  vtkOpenCLContext* Context;
  vtkObject* Reporter;
  double Bytes = 0;
  vtkOpenCLBuffer Make(cl_mem_flags flags, size_t bytes, const void* data, const char* what)
  {
    // CreateBuffer rounds the device allocation up to 16 bytes; `data` holds exactly `bytes`.
    this->Bytes += static_cast<double>((std::max<size_t>(bytes, 1) + 15) / 16 * 16);
    return this->Context->CreateBuffer(flags, bytes, data, what, this->Reporter);
  }
};

bool Run1D(vtkOpenCLContext* ctx, cl_kernel kernel, size_t count, const char* label, vtkObject* r)
{
  const size_t local = 64;
  const size_t global = std::max<size_t>(count, 1);
  return ctx->RunKernel(kernel, 1, &global, &local, label, r);
}

// Builds the octree level array of `nBuffer` into `octree` (one byte per voxel).
bool RunOctree(vtkOpenCLContext* ctx, vtkObject* reporter, Allocator& alloc, cl_mem nBuffer,
  const int dims[3], double eps, double eps2, vtkOpenCLBuffer& octree)
{
  const std::string options = "-DEPS=" + FloatLiteral(eps) + " -DEPS2=" + FloatLiteral(eps2);
  cl_program program = ctx->GetProgram(
    { "refracta_atomics.cl", "refracta_common.cl", "photon_octree.cl" }, options, reporter);
  if (!program)
  {
    return false;
  }
  // Level k has ceil(N / 2^k) nodes per axis; the top level is a single node.
  std::vector<std::array<int, 3>> levelDims;
  std::vector<cl_uint> offsets;
  size_t total = 0;
  for (int k = 0;; ++k)
  {
    std::array<int, 3> d;
    for (int c = 0; c < 3; ++c)
    {
      d[c] = (dims[c] + (1 << k) - 1) >> k;
    }
    levelDims.push_back(d);
    offsets.push_back(static_cast<cl_uint>(total));
    total += static_cast<size_t>(d[0]) * d[1] * d[2];
    if (d[0] == 1 && d[1] == 1 && d[2] == 1)
    {
      break;
    }
  }
  const size_t voxels = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  vtkOpenCLBuffer pyramid =
    alloc.Make(CL_MEM_READ_WRITE, total * 2 * sizeof(float), nullptr, "octree pyramid");
  vtkOpenCLBuffer offsetBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    offsets.size() * sizeof(cl_uint), offsets.data(), "octree level offsets");
  octree = alloc.Make(CL_MEM_READ_WRITE, voxels, nullptr, "octree");
  if (!pyramid || !offsetBuffer || !octree)
  {
    return false;
  }
  vtkOpenCLKernel base = ctx->CreateKernel(program, "photon_pyramid_base", reporter);
  vtkOpenCLKernel reduce = ctx->CreateKernel(program, "photon_pyramid_reduce", reporter);
  vtkOpenCLKernel label = ctx->CreateKernel(program, "photon_octree_label", reporter);
  if (!base || !reduce || !label)
  {
    return false;
  }
  const cl_int4 d0 = Int4(dims);
  const cl_uint count0 = static_cast<cl_uint>(voxels);
  cl_mem pyr = pyramid.Get();
  if (!ctx->Check(vtkOpenCLSetKernelArgs(base.Get(), nBuffer, d0, pyr, count0),
        "clSetKernelArg(photon_pyramid_base)", reporter) ||
    !Run1D(ctx, base.Get(), voxels, "photon_pyramid_base", reporter))
  {
    return false;
  }
  for (size_t k = 1; k < levelDims.size(); ++k)
  {
    const cl_int4 fineDims = Int4(levelDims[k - 1].data());
    const cl_int4 coarseDims = Int4(levelDims[k].data());
    const size_t count = static_cast<size_t>(coarseDims.s[0]) * coarseDims.s[1] * coarseDims.s[2];
    const cl_uint n = static_cast<cl_uint>(count);
    if (!ctx->Check(vtkOpenCLSetKernelArgs(
                      reduce.Get(), pyr, offsets[k - 1], fineDims, offsets[k], coarseDims, n),
          "clSetKernelArg(photon_pyramid_reduce)", reporter) ||
      !Run1D(ctx, reduce.Get(), count, "photon_pyramid_reduce", reporter))
    {
      return false;
    }
  }
  const cl_int levels = static_cast<cl_int>(levelDims.size());
  return ctx->Check(vtkOpenCLSetKernelArgs(
                      label.Get(), pyr, offsetBuffer.Get(), levels, d0, octree.Get(), count0),
           "clSetKernelArg(photon_octree_label)", reporter) &&
    Run1D(ctx, label.Get(), voxels, "photon_octree_label", reporter) && ctx->Finish(reporter);
}
}

//------------------------------------------------------------------------------
vtkPhotonTracer::vtkPhotonTracer()
{
  this->Lights = vtkSmartPointer<vtkLightCollection>::New();
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

vtkPhotonTracer::~vtkPhotonTracer() = default;

void vtkPhotonTracer::AddLight(vtkLight* light)
{
  if (light)
  {
    this->Lights->AddItem(light);
    this->Modified();
  }
}

void vtkPhotonTracer::RemoveAllLights()
{
  this->Lights->RemoveAllItems();
  this->Modified();
}

void vtkPhotonTracer::SetLights(vtkLightCollection* lights)
{
  this->Lights = lights ? vtkSmartPointer<vtkLightCollection>(lights)
                        : vtkSmartPointer<vtkLightCollection>::New();
  this->Modified();
}

vtkLightCollection* vtkPhotonTracer::GetLights()
{
  return this->Lights;
}

void vtkPhotonTracer::SetContext(vtkOpenCLContext* context)
{
  if (this->Context != context)
  {
    this->Context = context;
    this->Modified();
  }
}

vtkOpenCLContext* vtkPhotonTracer::GetContext()
{
  return this->Context ? this->Context.Get() : vtkOpenCLContext::GetDefault();
}

vtkMTimeType vtkPhotonTracer::GetMTime()
{
  // A light changed after being added must re-run the pass.
  vtkMTimeType t = this->Superclass::GetMTime();
  vtkLight* light;
  vtkCollectionSimpleIterator it;
  for (this->Lights->InitTraversal(it); (light = this->Lights->GetNextLight(it));)
  {
    t = std::max(t, light->GetMTime());
  }
  return t;
}

int vtkPhotonTracer::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::BuildOctree(vtkImageData* medium, vtkImageData* octreeOut)
{
  vtkNew<vtkMediumValidator> validator;
  if (!octreeOut || !validator->Validate(medium))
  {
    vtkErrorMacro("BuildOctree needs a valid medium and an output image: "
      << (octreeOut ? validator->GetErrorMessage() : "the output image is null"));
    return false;
  }
  vtkOpenCLContext* ctx = this->GetContext();
  if (!ctx->Initialize())
  {
    vtkErrorMacro("No OpenCL device: " << ctx->GetLastErrorMessage());
    return false;
  }
  Medium m;
  LoadMedium(medium, false, m);
  Allocator alloc{ ctx, this };
  vtkOpenCLBuffer nBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    m.Voxels * sizeof(float), m.N.data(), "RefractiveIndex");
  vtkOpenCLBuffer octree;
  if (!nBuffer ||
    !RunOctree(ctx, this, alloc, nBuffer.Get(), m.Dims, this->PrimaryTolerance,
      this->SecondaryTolerance, octree))
  {
    return false;
  }
  std::vector<unsigned char> codes(m.Voxels);
  if (!ctx->ReadBuffer(octree.Get(), m.Voxels, codes.data(), this))
  {
    return false;
  }
  octreeOut->Initialize();
  octreeOut->CopyStructure(medium);
  vtkNew<vtkUnsignedCharArray> level;
  level->SetName("OctreeLevel");
  level->SetNumberOfTuples(static_cast<vtkIdType>(m.Voxels));
  vtkNew<vtkUnsignedCharArray> limited;
  limited->SetName("OctreeStepLimited");
  limited->SetNumberOfTuples(static_cast<vtkIdType>(m.Voxels));
  for (size_t v = 0; v < m.Voxels; ++v)
  {
    level->SetValue(static_cast<vtkIdType>(v), codes[v] & 0x1f);
    limited->SetValue(static_cast<vtkIdType>(v), (codes[v] & 0x80) ? 1 : 0);
  }
  octreeOut->GetPointData()->AddArray(level);
  octreeOut->GetPointData()->AddArray(limited);
  return true;
}

//------------------------------------------------------------------------------
// The state one run of RequestData passes from stage to stage.
struct vtkPhotonTracer::Internals
{
  vtkImageData* Input = nullptr;
  Medium M;
  std::vector<LightSetup> Lights;
  double TotalBound = 0; // sum of the lights' power bounds towards the box
  size_t Photons = 0;
  vtkOpenCLContext* Context = nullptr;
  Allocator Alloc{ nullptr, nullptr };
  double Unit = 1.0;  // the device's unit of power (TotalBound)
  double Scale = 1.0; // fixed-point scale of the tallies, in host units
  cl_program Trace = nullptr;
  vtkOpenCLBuffer NBuffer, GradBuffer, Octree;
  vtkOpenCLBuffer Pos, Dirs, Power;
  vtkOpenCLBuffer ExtBuffer, AlbBuffer, RadFixed, DirFixed, Tallies, Counters;
  std::vector<cl_long> Tally, Count;
  vtkNew<vtkFloatArray> Radiance;
  vtkNew<vtkFloatArray> Direction;
  double Progress = 0.0; // last value reported, so that progress never goes back
  bool Aborted = false;  // the run stopped because AbortExecute was set
};

//------------------------------------------------------------------------------
bool vtkPhotonTracer::ReportProgress(Internals& run, double progress)
{
  run.Progress = std::max(run.Progress, std::min(progress, 1.0));
  this->UpdateProgress(run.Progress);
  run.Aborted = run.Aborted || this->GetAbortExecute();
  return !run.Aborted;
}

//------------------------------------------------------------------------------
// Lights, converted to the grid-local frame in double precision.
bool vtkPhotonTracer::SetUpLights(Internals& run)
{
  vtkImageData* input = run.Input;
  const double* origin = input->GetOrigin();
  vtkMatrix3x3* dir = input->GetDirectionMatrix();
  int extent[6];
  input->GetExtent(extent);
  Medium& m = run.M;
  LoadMedium(input, this->UseProxyBounds, m);
  auto toLocalPoint = [&](const double p[3], double out[3])
  {
    const double rel[3] = { p[0] - origin[0], p[1] - origin[1], p[2] - origin[2] };
    for (int r = 0; r < 3; ++r)
    {
      out[r] = dir->GetElement(0, r) * rel[0] + dir->GetElement(1, r) * rel[1] +
        dir->GetElement(2, r) * rel[2] - extent[2 * r] * m.Spacing[r];
    }
  };
  auto toLocalVector = [&](const double d[3], double out[3])
  {
    for (int r = 0; r < 3; ++r)
    {
      out[r] =
        dir->GetElement(0, r) * d[0] + dir->GetElement(1, r) * d[1] + dir->GetElement(2, r) * d[2];
    }
  };
  const double boxCentre[3] = { 0.5 * (m.ProxyLo[0] + m.ProxyHi[0]),
    0.5 * (m.ProxyLo[1] + m.ProxyHi[1]), 0.5 * (m.ProxyLo[2] + m.ProxyHi[2]) };
  const double halfDiag[3] = { 0.5 * (m.ProxyHi[0] - m.ProxyLo[0]),
    0.5 * (m.ProxyHi[1] - m.ProxyLo[1]), 0.5 * (m.ProxyHi[2] - m.ProxyLo[2]) };
  const double boxRadius = std::sqrt(Dot(halfDiag, halfDiag));

  std::vector<LightSetup>& lights = run.Lights;
  vtkLight* light;
  vtkCollectionSimpleIterator it;
  int lightIndex = 0;
  for (this->Lights->InitTraversal(it); (light = this->Lights->GetNextLight(it)); ++lightIndex)
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    double pw[3], fw[3], colour[3];
    light->GetTransformedPosition(pw);
    light->GetTransformedFocalPoint(fw);
    light->GetDiffuseColor(colour);
    const double intensity = light->GetIntensity();
    bool finite = std::isfinite(intensity);
    for (int c = 0; c < 3; ++c)
    {
      finite = finite && std::isfinite(pw[c]) && std::isfinite(fw[c]) && std::isfinite(colour[c]);
    }
    if (!finite || intensity < 0 || colour[0] < 0 || colour[1] < 0 || colour[2] < 0)
    {
      vtkErrorMacro("Light " << lightIndex
                             << " has a non-finite position, focal point, colour or intensity, or "
                                "a negative intensity or colour; all must be finite and >= 0.");
      return false;
    }
    LightSetup ls;
    ls.Positional = light->GetPositional();
    for (int c = 0; c < 3; ++c)
    {
      ls.Colour[c] = colour[c] * intensity;
    }
    double p[3], f[3], axisWorld[3] = { fw[0] - pw[0], fw[1] - pw[1], fw[2] - pw[2] };
    toLocalPoint(pw, p);
    toLocalPoint(fw, f);
    double axis[3];
    toLocalVector(axisWorld, axis);
    const bool isSpot = ls.Positional && light->GetConeAngle() < 90.0;
    if ((!ls.Positional || isSpot) && !Normalize(axis))
    {
      vtkErrorMacro("Light " << lightIndex
                             << " is directional or a spot but its position equals its focal "
                                "point; they must differ to give a direction.");
      return false;
    }
    if (isSpot && !(light->GetConeAngle() > 0.0))
    {
      vtkErrorMacro("Light " << lightIndex << " has cone angle " << light->GetConeAngle()
                             << "; a spot needs (0, 90) degrees, a point light >= 90.");
      return false;
    }
    const double maxColour = std::max({ ls.Colour[0], ls.Colour[1], ls.Colour[2] });
    if (!ls.Positional)
    {
      // Rectangle perpendicular to the direction covering the box's projection.
      double b1[3], b2[3];
      Basis(axis, b1, b2);
      double umin = 1e300, umax = -1e300, wmin = 1e300, wmax = -1e300, dmin = 1e300;
      for (int corner = 0; corner < 8; ++corner)
      {
        const double q[3] = { (corner & 1) ? m.ProxyHi[0] : m.ProxyLo[0],
          (corner & 2) ? m.ProxyHi[1] : m.ProxyLo[1], (corner & 4) ? m.ProxyHi[2] : m.ProxyLo[2] };
        umin = std::min(umin, Dot(q, b1));
        umax = std::max(umax, Dot(q, b1));
        wmin = std::min(wmin, Dot(q, b2));
        wmax = std::max(wmax, Dot(q, b2));
        dmin = std::min(dmin, Dot(q, axis));
      }
      const double back = dmin - 0.01 * boxRadius - 1e-6;
      // A disc of angular radius delta tilts rays by up to delta: widen the rectangle by what
      // they drift sideways across the box.
      const double delta = vtkMath::RadiansFromDegrees(this->DirectionalLightAngularRadius);
      ls.Extent = std::sin(delta);
      const double margin = std::tan(delta) * (2.0 * boxRadius + 0.01 * boxRadius);
      umin -= margin;
      wmin -= margin;
      umax += margin;
      wmax += margin;
      for (int c = 0; c < 3; ++c)
      {
        ls.Origin[c] = b1[c] * umin + b2[c] * wmin + axis[c] * back;
        ls.Axis[c] = axis[c];
        ls.Basis1[c] = b1[c] * (umax - umin);
        ls.Basis2[c] = b2[c] * (wmax - wmin);
      }
      ls.Measure = (umax - umin) * (wmax - wmin);
    }
    else
    {
      std::copy(p, p + 3, ls.Origin);
      double toBox[3] = { boxCentre[0] - p[0], boxCentre[1] - p[1], boxCentre[2] - p[2] };
      const double distance = std::sqrt(Dot(toBox, toBox));
      bool inside = true;
      for (int c = 0; c < 3; ++c)
      {
        inside = inside && p[c] >= m.ProxyLo[c] && p[c] <= m.ProxyHi[c];
      }
      double capAxis[3] = { 0, 0, 1 };
      ls.OneMinusCos = 2.0; // whole sphere
      // A sphere light reaches the box from anywhere on its disc: widen the cap by its radius.
      ls.Extent = this->LightRadius;
      const double reach = boxRadius + this->LightRadius;
      if (!inside && distance > reach * (1 + 1e-9))
      {
        const double s = reach / distance;
        ls.OneMinusCos = s * s / (1.0 + std::sqrt(1.0 - s * s));
        for (int c = 0; c < 3; ++c)
        {
          capAxis[c] = toBox[c] / distance;
        }
      }
      if (isSpot)
      {
        const double half = vtkMath::RadiansFromDegrees(light->GetConeAngle());
        const double spotOmc = 2.0 * std::sin(0.5 * half) * std::sin(0.5 * half);
        std::copy(axis, axis + 3, ls.SpotAxis);
        ls.SpotCos = std::cos(half);
        ls.Exponent = light->GetExponent();
        if (spotOmc < ls.OneMinusCos)
        {
          ls.OneMinusCos = spotOmc;
          std::copy(axis, axis + 3, capAxis);
        }
      }
      std::copy(capAxis, capAxis + 3, ls.Axis);
      Basis(ls.Axis, ls.Basis1, ls.Basis2);
      ls.Measure = 2.0 * vtkMath::Pi() * ls.OneMinusCos;
    }
    ls.Bound = maxColour * ls.Measure;
    if (ls.Bound > 0)
    {
      lights.push_back(ls);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
// Photon budget: proportional to each light's power towards the box.
void vtkPhotonTracer::SharePhotons(Internals& run)
{
  std::vector<LightSetup>& lights = run.Lights;
  double& totalBound = run.TotalBound;
  totalBound = 0;
  for (const auto& ls : lights)
  {
    totalBound += ls.Bound;
  }
  unsigned int assigned = 0;
  std::vector<std::pair<double, size_t>> remainders;
  for (size_t l = 0; l < lights.size(); ++l)
  {
    const double share = this->NumberOfPhotons * lights[l].Bound / totalBound;
    lights[l].Photons = static_cast<unsigned int>(std::floor(share));
    assigned += lights[l].Photons;
    remainders.emplace_back(share - std::floor(share), l);
  }
  std::sort(remainders.rbegin(), remainders.rend());
  for (size_t r = 0;
       assigned < static_cast<unsigned int>(this->NumberOfPhotons) && r < remainders.size();
       ++r, ++assigned)
  {
    lights[remainders[r].second].Photons++;
  }
  run.Photons = this->NumberOfPhotons;
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::InitializeDevice(Internals& run)
{
  const Medium& m = run.M;
  run.Context = this->GetContext();
  vtkOpenCLContext* ctx = run.Context;
  if (!ctx->Initialize())
  {
    vtkErrorMacro("No OpenCL device for the photon pass: " << ctx->GetLastErrorMessage());
    return false;
  }
  this->UsedCurvedRays = m.Curved;
  this->UsedExtinction = m.Attenuates;
  this->UsedDeposit = m.Scatters;
  this->UsedOctree = m.Curved && this->AdaptiveStepping;
  this->ComputedGradient = m.Curved && !m.HasGradient;

  run.Alloc = Allocator{ ctx, this };
  return true;
}

//------------------------------------------------------------------------------
// Stage 1: upload of the refractive index, gradient (if needed) and octree.
bool vtkPhotonTracer::BuildOctreeStage(Internals& run)
{
  Medium& m = run.M;
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  const size_t voxels = m.Voxels;
  const cl_int4 dims = Int4(m.Dims);
  const cl_float4 spacing = Float4(m.Spacing);
  const cl_uint voxelCount = static_cast<cl_uint>(voxels);
  vtkOpenCLBuffer& nBuffer = run.NBuffer;
  vtkOpenCLBuffer& gradBuffer = run.GradBuffer;
  vtkOpenCLBuffer& octree = run.Octree;
  auto start = Clock::now();
  nBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    (m.Curved ? voxels : 1) * sizeof(float), m.N.data(), "RefractiveIndex");
  if (!nBuffer)
  {
    return false;
  }
  if (m.Curved && m.HasGradient)
  {
    gradBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, voxels * 3 * sizeof(float),
      m.Gradient.data(), "RefractiveIndexGradient");
  }
  else if (m.Curved)
  {
    cl_program program = ctx->GetProgram(
      { "refracta_atomics.cl", "refracta_common.cl", "photon_octree.cl" }, "", this);
    gradBuffer = alloc.Make(CL_MEM_READ_WRITE, voxels * 3 * sizeof(float), nullptr, "gradient");
    vtkOpenCLKernel kernel =
      program ? ctx->CreateKernel(program, "photon_gradient", this) : vtkOpenCLKernel();
    if (!kernel || !gradBuffer ||
      !ctx->Check(vtkOpenCLSetKernelArgs(
                    kernel.Get(), nBuffer.Get(), dims, spacing, gradBuffer.Get(), voxelCount),
        "clSetKernelArg(photon_gradient)", this) ||
      !Run1D(ctx, kernel.Get(), voxels, "photon_gradient", this))
    {
      return false;
    }
  }
  else
  {
    gradBuffer = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "gradient (unused)");
  }
  if (this->UsedOctree)
  {
    if (!RunOctree(ctx, this, alloc, nBuffer.Get(), m.Dims, this->PrimaryTolerance,
          this->SecondaryTolerance, octree))
    {
      return false;
    }
  }
  else
  {
    octree = alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "octree (unused)");
  }
  if (!gradBuffer || !octree || !ctx->Finish(this))
  {
    return false;
  }
  this->OctreeSeconds = Seconds(start);
  return this->ReportProgress(run, ProgressOctree);
}

//------------------------------------------------------------------------------
// Stage 2: generation.
bool vtkPhotonTracer::GeneratePhotons(Internals& run)
{
  Medium& m = run.M;
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  const double voxelUnit = std::min({ m.Spacing[0], m.Spacing[1], m.Spacing[2] });
  const size_t photons = run.Photons;
  vtkOpenCLBuffer& pos = run.Pos;
  vtkOpenCLBuffer& dirs = run.Dirs;
  vtkOpenCLBuffer& power = run.Power;
  const std::vector<LightSetup>& lights = run.Lights;
  const auto start = Clock::now();
  // The device works in units of the total power sent towards the box (`unit`), so that one
  // compiled program serves every light set up. Every sum (a voxel's deposits, a tally, a
  // direction sum weighted by three channels) is then bounded by 1, plus roulette boosts; 16
  // leaves room for both. The host multiplies the results back by `unit`.
  run.Unit = run.TotalBound > 0 ? run.TotalBound : 1.0;
  run.Scale = vtkOpenCLContext::ChooseFixedPointScale(16.0) / run.Unit;
  const double unit = run.Unit;
  const double deviceScale = vtkOpenCLContext::ChooseFixedPointScale(16.0);
  std::ostringstream scaleLiteral;
  scaleLiteral << "0x1p" << std::ilogb(deviceScale) << "f";
  std::ostringstream options;
  options << "-DREFRACTA_FIXED_SCALE=" << scaleLiteral.str() << " -DREFRACT=" << m.Curved
          << " -DADAPTIVE=" << this->AdaptiveStepping << " -DEXTINCTION=" << m.Attenuates
          << " -DDEPOSIT=" << m.Scatters
          << " -DMIN_STEP=" << FloatLiteral(this->MinimumStep * voxelUnit)
          << " -DMAX_STEP=" << FloatLiteral(this->MaximumStep * voxelUnit) << " -DCAP_STEP="
          << FloatLiteral(std::min(this->SecondaryStepLimit, this->MaximumStep) * voxelUnit)
          << " -DFIXED_STEP=" << FloatLiteral(this->FixedStep * voxelUnit)
          << " -DMAX_STEPS=" << this->MaximumNumberOfSteps
          << " -DEXT_STEP_LIMIT=" << FloatLiteral(this->ExtinctionStepLimit)
          << " -DROULETTE=" << FloatLiteral(this->RouletteThreshold)
          << " -DMAX_TURN=" << FloatLiteral(this->MaximumTurn);
  run.Trace = ctx->GetProgram(
    { "refracta_atomics.cl", "refracta_common.cl", "photon_tallies.cl", "photon_trace.cl" },
    options.str(), this);
  cl_program trace = run.Trace;
  if (!trace)
  {
    return false;
  }
  pos = alloc.Make(CL_MEM_READ_WRITE, photons * sizeof(cl_float4), nullptr, "photon positions");
  dirs = alloc.Make(CL_MEM_READ_WRITE, photons * sizeof(cl_float4), nullptr, "photon directions");
  power = alloc.Make(CL_MEM_READ_WRITE, photons * sizeof(cl_float4), nullptr, "photon powers");
  if (!pos || !dirs || !power || !ctx->ZeroBuffer(power.Get(), photons * sizeof(cl_float4), this))
  {
    return false;
  }
  vtkOpenCLKernel generate = ctx->CreateKernel(trace, "photon_generate", this);
  if (!generate)
  {
    return false;
  }
  uint64_t seedState = 0x5eedULL ^ (static_cast<uint64_t>(this->Seed) << 17);
  cl_uint offset = 0;
  for (const auto& ls : lights)
  {
    const cl_uint count = ls.Photons;
    const cl_uint r1 = SplitMix(seedState);
    const cl_uint r2 = SplitMix(seedState);
    if (count == 0)
    {
      continue;
    }
    const cl_int positional = ls.Positional ? 1 : 0;
    const cl_float4 params =
      Float4(1.0 - ls.OneMinusCos, ls.Exponent, ls.Measure / count, ls.OneMinusCos);
    if (!ctx->Check(
          vtkOpenCLSetKernelArgs(generate.Get(), pos.Get(), dirs.Get(), power.Get(), offset, count,
            positional, Float4(ls.Origin), Float4(ls.Axis), Float4(ls.Basis1), Float4(ls.Basis2),
            Float4(ls.SpotAxis, ls.SpotCos), params,
            Float4(ls.Colour[0] / unit, ls.Colour[1] / unit, ls.Colour[2] / unit),
            Float4(m.ProxyLo), Float4(m.ProxyHi), r1, r2, static_cast<cl_float>(ls.Extent)),
          "clSetKernelArg(photon_generate)", this) ||
      !Run1D(ctx, generate.Get(), count, "photon_generate", this))
    {
      return false;
    }
    offset += count;
  }
  if (!ctx->Finish(this))
  {
    return false;
  }
  this->GenerationSeconds = Seconds(start);
  return this->ReportProgress(run, ProgressGenerated);
}

//------------------------------------------------------------------------------
// Stage 3: marching.
bool vtkPhotonTracer::MarchPhotons(Internals& run)
{
  Medium& m = run.M;
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  const size_t voxels = m.Voxels;
  const cl_int4 dims = Int4(m.Dims);
  const cl_float4 spacing = Float4(m.Spacing);
  const size_t photons = run.Photons;
  const double scale = run.Scale;
  cl_program trace = run.Trace;
  vtkOpenCLBuffer& nBuffer = run.NBuffer;
  vtkOpenCLBuffer& gradBuffer = run.GradBuffer;
  vtkOpenCLBuffer& octree = run.Octree;
  vtkOpenCLBuffer& pos = run.Pos;
  vtkOpenCLBuffer& dirs = run.Dirs;
  vtkOpenCLBuffer& power = run.Power;
  vtkOpenCLBuffer& extBuffer = run.ExtBuffer;
  vtkOpenCLBuffer& albBuffer = run.AlbBuffer;
  vtkOpenCLBuffer& radFixed = run.RadFixed;
  vtkOpenCLBuffer& dirFixed = run.DirFixed;
  vtkOpenCLBuffer& tallies = run.Tallies;
  vtkOpenCLBuffer& counters = run.Counters;
  const auto start = Clock::now();
  const size_t accumulators = m.Scatters ? voxels * 3 : 1;
  extBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    (m.Attenuates ? voxels * 3 : 1) * sizeof(float), m.Extinction.data(), "Extinction");
  albBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    (m.Scatters ? voxels * 3 : 1) * sizeof(float), m.Albedo.data(), "Albedo");
  radFixed =
    alloc.Make(CL_MEM_READ_WRITE, accumulators * sizeof(cl_long), nullptr, "radiance accumulator");
  dirFixed =
    alloc.Make(CL_MEM_READ_WRITE, accumulators * sizeof(cl_long), nullptr, "direction accumulator");
  tallies = alloc.Make(CL_MEM_READ_WRITE, PHOTON_TALLY_COUNT * sizeof(cl_long), nullptr, "tallies");
  counters =
    alloc.Make(CL_MEM_READ_WRITE, PHOTON_COUNTER_COUNT * sizeof(cl_long), nullptr, "counters");
  vtkOpenCLKernel march = ctx->CreateKernel(trace, "photon_march", this);
  if (!extBuffer || !albBuffer || !radFixed || !dirFixed || !tallies || !counters || !march ||
    !ctx->ZeroBuffer(radFixed.Get(), accumulators * sizeof(cl_long), this) ||
    !ctx->ZeroBuffer(dirFixed.Get(), accumulators * sizeof(cl_long), this) ||
    !ctx->ZeroBuffer(tallies.Get(), PHOTON_TALLY_COUNT * sizeof(cl_long), this) ||
    !ctx->ZeroBuffer(counters.Get(), PHOTON_COUNTER_COUNT * sizeof(cl_long), this))
  {
    return false;
  }
  const cl_uint photonCount = static_cast<cl_uint>(photons);
  const cl_uint seed = this->Seed;
  const size_t chunk = size_t(1) << 16;
  this->NumberOfChunks = 0;
  this->NumberOfBatches = 0;
  if (this->StepsPerChunk > 0)
  {
    // Chunked march (photon_march_chunk): all photons advance k steps per launch; the callback
    // (e.g. the Lattice-Boltzmann diffusion of what is already deposited) is enqueued between
    // launches.
    vtkOpenCLKernel marchChunk = ctx->CreateKernel(trace, "photon_march_chunk", this);
    vtkOpenCLBuffer state =
      alloc.Make(CL_MEM_READ_WRITE, photons * 8 * sizeof(cl_float4), nullptr, "photon state");
    vtkOpenCLBuffer status =
      alloc.Make(CL_MEM_READ_WRITE, photons * sizeof(cl_uint4), nullptr, "photon status");
    vtkOpenCLBuffer active = alloc.Make(CL_MEM_READ_WRITE, sizeof(cl_int), nullptr, "active");
    if (!marchChunk || !state || !status || !active ||
      !ctx->ZeroBuffer(status.Get(), photons * sizeof(cl_uint4), this))
    {
      return false;
    }
    const double radianceFactor = 1.0 / (scale * m.Spacing[0] * m.Spacing[1] * m.Spacing[2]);
    const cl_uint k = static_cast<cl_uint>(this->StepsPerChunk);
    // Curved rays stop at MaximumNumberOfSteps; straight ones cross at most the grid's diagonal
    // in voxel edges. The bound only guards against a hang.
    const size_t bound = static_cast<size_t>(this->MaximumNumberOfSteps) + 4 +
      static_cast<size_t>(2 * (m.Dims[0] + m.Dims[1] + m.Dims[2]) *
        std::max({ m.Spacing[0], m.Spacing[1], m.Spacing[2] }) /
        std::min({ m.Spacing[0], m.Spacing[1], m.Spacing[2] }));
    int stillActive = 1;
    for (size_t launch = 0; stillActive > 0 && launch * k <= bound; ++launch)
    {
      if (!ctx->ZeroBuffer(active.Get(), sizeof(cl_int), this))
      {
        return false;
      }
      for (size_t first = 0; first < photons; first += chunk)
      {
        const cl_uint firstId = static_cast<cl_uint>(first);
        if (!ctx->Check(
              vtkOpenCLSetKernelArgs(marchChunk.Get(), pos.Get(), dirs.Get(), power.Get(),
                photonCount, nBuffer.Get(), gradBuffer.Get(), extBuffer.Get(), albBuffer.Get(),
                octree.Get(), dims, spacing, radFixed.Get(), dirFixed.Get(), tallies.Get(),
                counters.Get(), seed, firstId, state.Get(), status.Get(), k, active.Get()),
              "clSetKernelArg(photon_march_chunk)", this) ||
          !Run1D(
            ctx, marchChunk.Get(), std::min(chunk, photons - first), "photon_march_chunk", this))
        {
          return false;
        }
      }
      cl_int count = 0;
      if (!ctx->ReadBuffer(active.Get(), sizeof(cl_int), &count, this))
      {
        return false;
      }
      stillActive = count;
      ++this->NumberOfChunks;
      if (this->Callback &&
        !this->Callback(radFixed.Get(), dirFixed.Get(), radianceFactor, 1.0 / scale, count))
      {
        vtkErrorMacro("The chunk callback failed after chunk " << this->NumberOfChunks << ".");
        return false;
      }
      if (!this->ReportProgress(run,
            ProgressGenerated +
              (ProgressMarched - ProgressGenerated) * (1.0 - double(count) / photons)))
      {
        return false;
      }
    }
  }
  // Unchunked march: photons in batches of whole work-groups, each launch waited for, so that
  // progress is reported and an abort is seen between them. The deposits are fixed-point sums and
  // every photon's random stream depends on its index only, so the batches do not change the
  // result. PhotonBatchSize 0 sizes each batch from the rate measured so far to take about
  // TargetBatchSeconds (at most doubling from one batch to the next).
  const size_t group = 64; // Run1D's work-group size: batches must be whole groups
  const bool automatic = this->PhotonBatchSize <= 0;
  size_t batch = automatic ? MinimumBatch : std::max<size_t>(this->PhotonBatchSize, 1);
  batch = (batch + group - 1) / group * group;
  for (size_t first = 0; this->StepsPerChunk == 0 && first < photons;)
  {
    const size_t count = std::min(batch, photons - first);
    const auto launchStart = Clock::now();
    for (size_t sub = first; sub < first + count; sub += chunk)
    {
      const cl_uint firstId = static_cast<cl_uint>(sub);
      if (!ctx->Check(vtkOpenCLSetKernelArgs(march.Get(), pos.Get(), dirs.Get(), power.Get(),
                        photonCount, nBuffer.Get(), gradBuffer.Get(), extBuffer.Get(),
                        albBuffer.Get(), octree.Get(), dims, spacing, radFixed.Get(),
                        dirFixed.Get(), tallies.Get(), counters.Get(), seed, firstId),
            "clSetKernelArg(photon_march)", this) ||
        !Run1D(ctx, march.Get(), std::min(chunk, first + count - sub), "photon_march", this))
      {
        return false;
      }
    }
    if (!ctx->Finish(this))
    {
      return false;
    }
    first += count;
    ++this->NumberOfBatches;
    if (!this->ReportProgress(
          run, ProgressGenerated + (ProgressMarched - ProgressGenerated) * double(first) / photons))
    {
      return false;
    }
    if (automatic)
    {
      const double seconds = std::max(Seconds(launchStart), 1e-6);
      const double wanted = static_cast<double>(count) * TargetBatchSeconds / seconds;
      batch = static_cast<size_t>(std::min({ wanted, 2.0 * count, double(MaximumBatch) }));
      batch = std::max<size_t>(batch / group * group, MinimumBatch);
    }
  }
  std::vector<cl_long>& tally = run.Tally;
  std::vector<cl_long>& count = run.Count;
  tally.assign(PHOTON_TALLY_COUNT, 0);
  count.assign(PHOTON_COUNTER_COUNT, 0);
  if (!ctx->ReadBuffer(tallies.Get(), PHOTON_TALLY_COUNT * sizeof(cl_long), tally.data(), this) ||
    !ctx->ReadBuffer(counters.Get(), PHOTON_COUNTER_COUNT * sizeof(cl_long), count.data(), this))
  {
    return false;
  }
  this->MarchingSeconds = Seconds(start);
  return true;
}

//------------------------------------------------------------------------------
// Stage 4: resolve, smooth, normalise.
bool vtkPhotonTracer::ResolveRadiance(Internals& run)
{
  Medium& m = run.M;
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  const size_t voxels = m.Voxels;
  const cl_int4 dims = Int4(m.Dims);
  const cl_uint voxelCount = static_cast<cl_uint>(voxels);
  const double scale = run.Scale;
  vtkOpenCLBuffer& radFixed = run.RadFixed;
  vtkOpenCLBuffer& dirFixed = run.DirFixed;
  const auto start = Clock::now();
  vtkFloatArray* radiance = run.Radiance;
  radiance->SetName("Radiance");
  radiance->SetNumberOfComponents(3);
  radiance->SetNumberOfTuples(static_cast<vtkIdType>(voxels));
  vtkFloatArray* direction = run.Direction;
  direction->SetName("RadianceDirection");
  direction->SetNumberOfComponents(3);
  direction->SetNumberOfTuples(static_cast<vtkIdType>(voxels));
  if (!m.Scatters)
  {
    radiance->FillValue(0.0f);
    direction->FillValue(0.0f);
  }
  else
  {
    cl_program smooth = ctx->GetProgram({ "refracta_common.cl", "radiance_smooth.cl" }, "", this);
    vtkOpenCLBuffer radA =
      alloc.Make(CL_MEM_READ_WRITE, voxels * 3 * sizeof(float), nullptr, "radiance");
    vtkOpenCLBuffer dirA =
      alloc.Make(CL_MEM_READ_WRITE, voxels * 3 * sizeof(float), nullptr, "direction");
    vtkOpenCLBuffer radB, dirB;
    if (this->Smoothing)
    {
      radB = alloc.Make(CL_MEM_READ_WRITE, voxels * 3 * sizeof(float), nullptr, "radiance");
      dirB = alloc.Make(CL_MEM_READ_WRITE, voxels * 3 * sizeof(float), nullptr, "direction");
    }
    if (!smooth || !radA || !dirA || (this->Smoothing && (!radB || !dirB)))
    {
      return false;
    }
    vtkOpenCLKernel resolve = ctx->CreateKernel(smooth, "radiance_resolve", this);
    vtkOpenCLKernel filter = ctx->CreateKernel(smooth, "radiance_smooth", this);
    vtkOpenCLKernel normalize = ctx->CreateKernel(smooth, "radiance_normalize", this);
    if (!resolve || !filter || !normalize)
    {
      return false;
    }
    const float radianceFactor =
      static_cast<float>(1.0 / (scale * m.Spacing[0] * m.Spacing[1] * m.Spacing[2]));
    const float directionFactor = static_cast<float>(1.0 / scale);
    if (!ctx->Check(vtkOpenCLSetKernelArgs(resolve.Get(), radFixed.Get(), dirFixed.Get(),
                      radianceFactor, directionFactor, radA.Get(), dirA.Get(), voxelCount),
          "clSetKernelArg(radiance_resolve)", this) ||
      !Run1D(ctx, resolve.Get(), voxels, "radiance_resolve", this))
    {
      return false;
    }
    cl_mem radOut = radA.Get();
    cl_mem dirOut = dirA.Get();
    if (this->Smoothing)
    {
      if (!ctx->Check(
            vtkOpenCLSetKernelArgs(filter.Get(), radA.Get(), dims, radB.Get(), voxelCount),
            "clSetKernelArg(radiance_smooth)", this) ||
        !Run1D(ctx, filter.Get(), voxels, "radiance_smooth", this) ||
        !ctx->Check(vtkOpenCLSetKernelArgs(filter.Get(), dirA.Get(), dims, dirB.Get(), voxelCount),
          "clSetKernelArg(radiance_smooth)", this) ||
        !Run1D(ctx, filter.Get(), voxels, "radiance_smooth", this))
      {
        return false;
      }
      radOut = radB.Get();
      dirOut = dirB.Get();
    }
    if (!ctx->Check(vtkOpenCLSetKernelArgs(normalize.Get(), dirOut, voxelCount),
          "clSetKernelArg(radiance_normalize)", this) ||
      !Run1D(ctx, normalize.Get(), voxels, "radiance_normalize", this) ||
      !ctx->ReadBuffer(radOut, voxels * 3 * sizeof(float), radiance->GetPointer(0), this) ||
      !ctx->ReadBuffer(dirOut, voxels * 3 * sizeof(float), direction->GetPointer(0), this))
    {
      return false;
    }
  }
  this->SmoothingSeconds = Seconds(start);
  this->PeakDeviceMemoryBytes = alloc.Bytes;
  return true;
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::WriteOutput(Internals& run, vtkImageData* output)
{
  const double scale = run.Scale;
  const std::vector<cl_long>& tally = run.Tally;
  const std::vector<cl_long>& count = run.Count;
  output->CopyStructure(run.Input);
  output->GetPointData()->AddArray(run.Radiance);
  output->GetPointData()->SetScalars(run.Radiance);
  output->GetPointData()->AddArray(run.Direction);
  vtkFieldData* fd = output->GetFieldData();
  auto addCount = [&](const char* name, long long value)
  {
    vtkNew<vtkTypeInt64Array> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fd->AddArray(a);
  };
  addCount("NumberOfPhotons", static_cast<long long>(run.Photons));
  addCount("PhotonsMarched", count[PHOTON_COUNTER_MARCHED]);
  addCount("PhotonsMissed", count[PHOTON_COUNTER_MISSED]);
  addCount("TerminatedEscaped", count[PHOTON_COUNTER_ESCAPED]);
  addCount("TerminatedRoulette", count[PHOTON_COUNTER_ROULETTE]);
  addCount("TerminatedStepCap", count[PHOTON_COUNTER_STEP_CAP]);
  addCount("TerminatedInvalid", count[PHOTON_COUNTER_INVALID]);
  addCount("TotalSteps", count[PHOTON_COUNTER_STEPS]);
  addCount("TotalVoxelPieces", count[PHOTON_COUNTER_PIECES]);
  auto energy = [&](int t, int c) { return static_cast<double>(tally[3 * t + c]) / scale; };
  auto addEnergy = [&](const char* name, const std::array<double, 3>& v)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfComponents(3);
    a->InsertNextTuple(v.data());
    fd->AddArray(a);
  };
  std::array<double, 3> e[PHOTON_TALLY_BOOKS], remaining;
  for (int t = 0; t < PHOTON_TALLY_BOOKS; ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      e[t][c] = energy(t, c);
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    remaining[c] =
      e[PHOTON_TALLY_REMAINING][c] + e[PHOTON_TALLY_KILLED][c] - e[PHOTON_TALLY_GAINED][c];
  }
  addEnergy("EnergyEmitted", e[PHOTON_TALLY_EMITTED]);
  addEnergy("EnergyAbsorbed", e[PHOTON_TALLY_ABSORBED]);
  addEnergy("EnergyEscaped", e[PHOTON_TALLY_ESCAPED]);
  addEnergy("EnergyScattered", e[PHOTON_TALLY_SCATTERED]);
  addEnergy("EnergyRemaining", remaining);
  addEnergy("EnergyRouletteKilled", e[PHOTON_TALLY_KILLED]);
  addEnergy("EnergyRouletteGained", e[PHOTON_TALLY_GAINED]);
}

//------------------------------------------------------------------------------
int vtkPhotonTracer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!output)
  {
    vtkErrorMacro("The output is not a vtkImageData.");
    return 0;
  }
  output->Initialize();
  this->OctreeSeconds = this->GenerationSeconds = this->MarchingSeconds = 0;
  this->SmoothingSeconds = this->PeakDeviceMemoryBytes = 0;
  this->UsedCurvedRays = this->UsedExtinction = this->UsedDeposit = false;
  this->UsedOctree = this->ComputedGradient = false;

  vtkNew<vtkMediumValidator> validator;
  if (!validator->Validate(input))
  {
    vtkErrorMacro("Input 0 is not a valid Refracta medium: " << validator->GetErrorMessage());
    return 0;
  }
  this->LastRunAborted = false;
  Internals run;
  run.Input = input;
  if (!this->SetUpLights(run))
  {
    return 0;
  }
  this->SharePhotons(run);
  if (!this->InitializeDevice(run) || !this->BuildOctreeStage(run) || !this->GeneratePhotons(run) ||
    !this->MarchPhotons(run) || !this->ResolveRadiance(run))
  {
    if (run.Aborted)
    {
      // An abort is not an error: the output stays empty, the device buffers are released with
      // `run`, and the next Update() (AbortExecute off again) runs from the start.
      this->LastRunAborted = true;
      return 1;
    }
    return 0;
  }
  this->PeakDeviceMemoryBytes = run.Alloc.Bytes;
  this->WriteOutput(run, output);
  this->ReportProgress(run, 1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfLights: " << this->Lights->GetNumberOfItems() << "\n";
  os << indent << "LightRadius: " << this->LightRadius << "\n";
  os << indent << "DirectionalLightAngularRadius: " << this->DirectionalLightAngularRadius << "\n";
  os << indent << "NumberOfPhotons: " << this->NumberOfPhotons << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "PrimaryTolerance: " << this->PrimaryTolerance << "\n";
  os << indent << "SecondaryTolerance: " << this->SecondaryTolerance << "\n";
  os << indent << "SecondaryStepLimit: " << this->SecondaryStepLimit << " voxels\n";
  os << indent << "MinimumStep: " << this->MinimumStep << " voxels\n";
  os << indent << "MaximumStep: " << this->MaximumStep << " voxels\n";
  os << indent << "AdaptiveStepping: " << this->AdaptiveStepping << "\n";
  os << indent << "FixedStep: " << this->FixedStep << " voxels\n";
  os << indent << "ExtinctionStepLimit: " << this->ExtinctionStepLimit << "\n";
  os << indent << "RouletteThreshold: " << this->RouletteThreshold << "\n";
  os << indent << "MaximumNumberOfSteps: " << this->MaximumNumberOfSteps << "\n";
  os << indent << "MaximumTurn: " << this->MaximumTurn << "\n";
  os << indent << "Smoothing: " << this->Smoothing << "\n";
  os << indent << "StepsPerChunk: " << this->StepsPerChunk << "\n";
  os << indent << "PhotonBatchSize: " << this->PhotonBatchSize << "\n";
  os << indent << "NumberOfBatches: " << this->NumberOfBatches << "\n";
  os << indent << "LastRunAborted: " << this->LastRunAborted << "\n";
  os << indent << "UseProxyBounds: " << this->UseProxyBounds << "\n";
  os << indent << "Stage seconds (octree, generation, marching, smoothing): " << this->OctreeSeconds
     << ", " << this->GenerationSeconds << ", " << this->MarchingSeconds << ", "
     << this->SmoothingSeconds << "\n";
  os << indent << "PeakDeviceMemoryBytes: " << this->PeakDeviceMemoryBytes << "\n";
  os << indent << "Plan: curved " << this->UsedCurvedRays << ", extinction " << this->UsedExtinction
     << ", deposit " << this->UsedDeposit << ", octree " << this->UsedOctree
     << ", gradient computed " << this->ComputedGradient << "\n";
}
