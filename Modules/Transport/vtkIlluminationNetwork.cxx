#include "vtkIlluminationNetwork.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkIlluminationNetworkInternals.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"
#include "vtkRefractaParticleMedium.h"
#include "vtkRefractaSettings.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkIlluminationNetwork);
vtkRefractaCxxSetClampMacro(vtkIlluminationNetwork, WindowPixelSize, 0.0, VTK_DOUBLE_MAX);
vtkRefractaCxxSetClampMacro(vtkIlluminationNetwork, Tolerance, 0.0, 1.0);
vtkRefractaCxxSetVector3Macro(vtkIlluminationNetwork, LightPosition);
vtkRefractaCxxSetVector3Macro(vtkIlluminationNetwork, LightDirection);
vtkRefractaCxxSetVector3Macro(vtkIlluminationNetwork, LightIntensity);
vtkRefractaCxxSetVector3Macro(vtkIlluminationNetwork, SkyRadiance);

namespace geo = vtkIlluminationNetworkGeometry;

namespace
{
constexpr double Pi = 3.14159265358979323846;
}

// Everything an update keeps for the next one: the particles, the current direction set and its
// networks on the host and the device.
struct vtkIlluminationNetwork::Internals
{
  geo::Particles Particles;
  std::vector<double> Directions;
  unsigned int RotationIndex = 0;
  std::vector<int> Visible;
  std::vector<unsigned char> HasNext;
  std::vector<int> PhaseClass;
  std::vector<float> Phase;
  std::vector<float> Emitted;
  std::vector<double> Irradiance, Travel;
  vtkMTimeType InputTime = 0;
  int BuiltDirections = 0;
  double BuiltPixel = 0;
  unsigned int BuiltSeed = 0;
  bool HasState = false; // I holds a previous solution

  vtkOpenCLBuffer Incoming, IncomingNext, Outgoing, EmittedBuffer, VisibleBuffer, Opacity, Albedo,
    PhaseClassBuffer, PhaseBuffer, Change;
  vtkOpenCLKernel Scatter, Propagate, ChangeKernel;
};

//------------------------------------------------------------------------------
vtkIlluminationNetwork::vtkIlluminationNetwork()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(1);
}

vtkIlluminationNetwork::~vtkIlluminationNetwork() = default;

//------------------------------------------------------------------------------
void vtkIlluminationNetwork::SetContext(vtkOpenCLContext* context)
{
  if (this->Context != context)
  {
    this->Context = context;
    this->Internal.reset(new Internals);
    this->Modified();
  }
}

vtkOpenCLContext* vtkIlluminationNetwork::GetContext()
{
  return this->Context ? this->Context.Get() : vtkOpenCLContext::GetDefault();
}

//------------------------------------------------------------------------------
void vtkIlluminationNetwork::ResetState()
{
  this->Internal->HasState = false;
  this->Modified();
}

//------------------------------------------------------------------------------
double vtkIlluminationNetwork::NetworkBytes(long long n, int d)
{
  // I, I', O, E (RGB floats) and V (int) per particle and direction.
  return static_cast<double>(n) * d * (4 * 3 * sizeof(float) + sizeof(int));
}

//------------------------------------------------------------------------------
int vtkIlluminationNetwork::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

namespace
{
// Builds the program's kernels once per context.
bool BuildKernels(vtkOpenCLContext* context, vtkOpenCLKernel& scatter, vtkOpenCLKernel& propagate,
  vtkOpenCLKernel& change, vtkObject* reporter)
{
  if (scatter && propagate && change)
  {
    return true;
  }
  cl_program program = context->GetProgram({ "illumination_network.cl" }, "", reporter);
  if (!program)
  {
    return false;
  }
  scatter = context->CreateKernel(program, "ilnet_scatter", reporter);
  propagate = context->CreateKernel(program, "ilnet_propagate", reporter);
  change = context->CreateKernel(program, "ilnet_change", reporter);
  return scatter && propagate && change;
}

template <typename T>
vtkOpenCLBuffer Upload(
  vtkOpenCLContext* context, const std::vector<T>& data, const char* what, vtkObject* reporter)
{
  return context->CreateBuffer(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
    std::max<size_t>(1, data.size()) * sizeof(T), data.empty() ? nullptr : data.data(), what,
    reporter);
}
}

//------------------------------------------------------------------------------
int vtkIlluminationNetwork::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->Iterations = 0;
  this->Converged = false;
  std::string message;
  if (!vtkRefractaParticleMedium::Validate(input, message))
  {
    vtkErrorMacro("Input 0 is not a valid particle medium: " << message << ".");
    return 0;
  }
  vtkOpenCLContext* context = this->GetContext();
  if (!context->Initialize())
  {
    vtkErrorMacro("No OpenCL device: " << context->GetLastErrorMessage());
    return 0;
  }
  const long long n = input->GetNumberOfPoints();
  const int d = this->NumberOfDirections;
  const double bytes = NetworkBytes(n, d);
  const double largestBuffer = static_cast<double>(n) * d * 3 * sizeof(float);
  if (largestBuffer > context->GetMaximumAllocationBytes() ||
    bytes > 0.8 * context->GetGlobalMemoryBytes() || bytes > 0.5 * context->GetHostMemoryBytes())
  {
    vtkErrorMacro("Input 0: a network of "
      << n << " particles and " << d << " directions needs " << bytes / 1048576.0
      << " MiB (one array " << largestBuffer / 1048576.0 << " MiB); the device allows "
      << context->GetMaximumAllocationMiB() << " MiB per buffer and "
      << context->GetGlobalMemoryMiB() << " MiB in all. Use fewer particles or directions.");
    return 0;
  }
  if (!BuildKernels(context, this->Internal->Scatter, this->Internal->Propagate,
        this->Internal->ChangeKernel, this))
  {
    return 0;
  }
  if (!this->PrepareNetwork(input) || !this->SolveRotations(output))
  {
    output->Initialize();
    return 0;
  }
  return 1;
}

//------------------------------------------------------------------------------
bool vtkIlluminationNetwork::PrepareNetwork(vtkPointSet* input)
{
  Internals& in = *this->Internal;
  const double pixelSetting = this->WindowPixelSize;
  const bool rebuild = !in.Incoming || input->GetMTime() != in.InputTime ||
    in.BuiltDirections != this->NumberOfDirections || in.BuiltPixel != pixelSetting ||
    in.BuiltSeed != this->Seed || in.Particles.N != input->GetNumberOfPoints();
  if (rebuild)
  {
    geo::ReadParticles(input, in.Particles);
    in.InputTime = input->GetMTime();
    in.BuiltDirections = this->NumberOfDirections;
    in.BuiltPixel = pixelSetting;
    in.BuiltSeed = this->Seed;
    in.RotationIndex = 0;
    in.HasState = false;
    in.Directions = geo::Rotate(
      geo::FibonacciDirections(this->NumberOfDirections), geo::RandomRotation(this->Seed, 0));
    this->PixelSize = pixelSetting > 0 ? pixelSetting : std::sqrt(Pi) * in.Particles.MeanRadius;
    vtkOpenCLContext* context = this->GetContext();
    const size_t cells = static_cast<size_t>(in.Particles.N) * this->NumberOfDirections;
    in.Opacity = Upload(context, in.Particles.Opacity, "particle opacity", this);
    in.Albedo = Upload(context, in.Particles.Albedo, "particle albedo", this);
    in.Incoming = context->CreateBuffer(
      CL_MEM_READ_WRITE, cells * 3 * sizeof(float), nullptr, "network I", this);
    in.IncomingNext = context->CreateBuffer(
      CL_MEM_READ_WRITE, cells * 3 * sizeof(float), nullptr, "network I (next)", this);
    in.Outgoing = context->CreateBuffer(
      CL_MEM_READ_WRITE, cells * 3 * sizeof(float), nullptr, "network O", this);
    in.EmittedBuffer = context->CreateBuffer(
      CL_MEM_READ_ONLY, cells * 3 * sizeof(float), nullptr, "network E", this);
    in.Change = context->CreateBuffer(CL_MEM_READ_WRITE,
      2 * static_cast<size_t>(in.Particles.N) * sizeof(float), nullptr, "network change", this);
    if (!in.Opacity || !in.Albedo || !in.Incoming || !in.IncomingNext || !in.Outgoing ||
      !in.EmittedBuffer || !in.Change || !this->BuildDirectionSet())
    {
      in.Incoming.Reset(); // forces a rebuild next time
      return false;
    }
  }
  if (!this->UpdateEmitted())
  {
    return false;
  }
  if (!in.HasState || !this->WarmStart)
  {
    const size_t bytes =
      static_cast<size_t>(in.Particles.N) * this->NumberOfDirections * 3 * sizeof(float);
    return this->GetContext()->ZeroBuffer(in.Incoming.Get(), bytes, this);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkIlluminationNetwork::BuildDirectionSet()
{
  Internals& in = *this->Internal;
  geo::BuildVisibility(in.Particles, in.Directions, this->PixelSize, in.Visible, in.HasNext);
  geo::BuildPhase(in.Particles, in.Directions, in.PhaseClass, in.Phase);
  vtkOpenCLContext* context = this->GetContext();
  in.VisibleBuffer = Upload(context, in.Visible, "visibility network", this);
  in.PhaseClassBuffer = Upload(context, in.PhaseClass, "phase classes", this);
  in.PhaseBuffer = Upload(context, in.Phase, "phase matrices", this);
  return in.VisibleBuffer && in.PhaseClassBuffer && in.PhaseBuffer;
}

//------------------------------------------------------------------------------
bool vtkIlluminationNetwork::UpdateEmitted()
{
  Internals& in = *this->Internal;
  geo::Light light;
  light.Type = this->LightType;
  std::copy(this->LightPosition, this->LightPosition + 3, light.Position);
  std::copy(this->LightDirection, this->LightDirection + 3, light.Direction);
  std::copy(this->LightIntensity, this->LightIntensity + 3, light.Intensity);
  if (light.Type == DIRECTIONAL_LIGHT && light.Direction[0] == 0 && light.Direction[1] == 0 &&
    light.Direction[2] == 0)
  {
    vtkErrorMacro("LightDirection is the zero vector; a directional light needs a direction.");
    return false;
  }
  geo::DirectIrradiance(in.Particles, light, this->PixelSize, in.Irradiance, in.Travel);
  geo::BuildEmitted(
    in.Particles, in.Directions, in.PhaseClass, in.Phase, in.Irradiance, in.Travel, in.Emitted);
  return this->GetContext()->WriteBuffer(
    in.EmittedBuffer.Get(), in.Emitted.size() * sizeof(float), in.Emitted.data(), this);
}

//------------------------------------------------------------------------------
bool vtkIlluminationNetwork::RotateDirections()
{
  Internals& in = *this->Internal;
  vtkOpenCLContext* context = this->GetContext();
  const int d = this->NumberOfDirections;
  const size_t n = static_cast<size_t>(in.Particles.N);
  std::vector<float> previous(n * d * 3);
  if (!context->ReadBuffer(
        in.Incoming.Get(), previous.size() * sizeof(float), previous.data(), this))
  {
    return false;
  }
  const std::vector<double> old = in.Directions;
  in.RotationIndex += 1;
  in.Directions =
    geo::Rotate(geo::FibonacciDirections(d), geo::RandomRotation(this->Seed, in.RotationIndex));
  // The fixed point does not depend on the start; the nearest old direction is a close start.
  const std::vector<int> nearest = geo::NearestDirections(old, in.Directions);
  std::vector<float> carried(previous.size());
  for (size_t p = 0; p < n; ++p)
  {
    for (int i = 0; i < d; ++i)
    {
      std::copy_n(&previous[(p * d + nearest[i]) * 3], 3, &carried[(p * d + i) * 3]);
    }
  }
  return this->BuildDirectionSet() && this->UpdateEmitted() &&
    context->WriteBuffer(in.Incoming.Get(), carried.size() * sizeof(float), carried.data(), this);
}

//------------------------------------------------------------------------------
bool vtkIlluminationNetwork::Iterate()
{
  Internals& in = *this->Internal;
  vtkOpenCLContext* context = this->GetContext();
  const cl_int d = this->NumberOfDirections;
  const cl_int n = static_cast<cl_int>(in.Particles.N);
  const size_t global[2] = { static_cast<size_t>(d), static_cast<size_t>(n) };
  const size_t perParticle = static_cast<size_t>(n);
  const cl_float sky[3] = { static_cast<cl_float>(this->SkyRadiance[0]),
    static_cast<cl_float>(this->SkyRadiance[1]), static_cast<cl_float>(this->SkyRadiance[2]) };
  std::vector<float> change(2 * perParticle);
  bool converged = false;
  int steps = 0;
  while (!converged && steps < this->MaximumIterations)
  {
    const bool check =
      (steps + 1) % this->CheckInterval == 0 || steps + 1 == this->MaximumIterations;
    if (!context->Check(vtkOpenCLSetKernelArgs(in.Scatter.Get(), in.Incoming.Get(),
                          in.EmittedBuffer.Get(), in.Opacity.Get(), in.Albedo.Get(),
                          in.PhaseClassBuffer.Get(), in.PhaseBuffer.Get(), in.Outgoing.Get(), d, n),
          "clSetKernelArg(ilnet_scatter)", this) ||
      !context->RunKernel(in.Scatter.Get(), 2, global, nullptr, "ilnet_scatter", this) ||
      !context->Check(vtkOpenCLSetKernelArgs(in.Propagate.Get(), in.VisibleBuffer.Get(),
                        in.Outgoing.Get(), in.IncomingNext.Get(), sky[0], sky[1], sky[2], d, n),
        "clSetKernelArg(ilnet_propagate)", this) ||
      !context->RunKernel(in.Propagate.Get(), 2, global, nullptr, "ilnet_propagate", this))
    {
      return false;
    }
    if (check)
    {
      if (!context->Check(vtkOpenCLSetKernelArgs(in.ChangeKernel.Get(), in.Incoming.Get(),
                            in.IncomingNext.Get(), in.Change.Get(), d, n),
            "clSetKernelArg(ilnet_change)", this) ||
        !context->RunKernel(
          in.ChangeKernel.Get(), 1, &perParticle, nullptr, "ilnet_change", this) ||
        !context->ReadBuffer(in.Change.Get(), change.size() * sizeof(float), change.data(), this))
      {
        return false;
      }
      double largestChange = 0, largest = 0;
      for (size_t p = 0; p < perParticle; ++p)
      {
        largestChange = std::max(largestChange, static_cast<double>(change[2 * p]));
        largest = std::max(largest, static_cast<double>(change[2 * p + 1]));
      }
      if (!std::isfinite(largestChange) || !std::isfinite(largest))
      {
        vtkErrorMacro("The illumination network stopped being finite after "
          << this->Iterations + steps + 1 << " iterations.");
        return false;
      }
      this->Residual = largest > 0 ? largestChange / largest : 0.0;
      converged = this->Residual < this->Tolerance;
    }
    std::swap(in.Incoming, in.IncomingNext);
    ++steps;
    this->UpdateProgress(std::min(1.0, static_cast<double>(steps) / this->MaximumIterations));
    if (this->GetAbortExecute())
    {
      break;
    }
  }
  this->Iterations += steps;
  return converged;
}

//------------------------------------------------------------------------------
bool vtkIlluminationNetwork::Gather(std::vector<double>& multipleFluence)
{
  Internals& in = *this->Internal;
  vtkOpenCLContext* context = this->GetContext();
  const cl_int d = this->NumberOfDirections;
  const cl_int n = static_cast<cl_int>(in.Particles.N);
  const size_t global[2] = { static_cast<size_t>(d), static_cast<size_t>(n) };
  const size_t cells = static_cast<size_t>(n) * d;
  std::vector<float> incoming(cells * 3), outgoing(cells * 3);
  // O from the final I, so that the books describe one consistent state.
  if (!context->Check(vtkOpenCLSetKernelArgs(in.Scatter.Get(), in.Incoming.Get(),
                        in.EmittedBuffer.Get(), in.Opacity.Get(), in.Albedo.Get(),
                        in.PhaseClassBuffer.Get(), in.PhaseBuffer.Get(), in.Outgoing.Get(), d, n),
        "clSetKernelArg(ilnet_scatter)", this) ||
    !context->RunKernel(in.Scatter.Get(), 2, global, nullptr, "ilnet_scatter", this) ||
    !context->ReadBuffer(
      in.Incoming.Get(), incoming.size() * sizeof(float), incoming.data(), this) ||
    !context->ReadBuffer(in.Outgoing.Get(), outgoing.size() * sizeof(float), outgoing.data(), this))
  {
    return false;
  }
  // Power carried by radiance L along one line of one direction: L * pixel area * 4 pi / D.
  const double weight = this->PixelSize * this->PixelSize * 4.0 * Pi / d;
  const double sphere = 4.0 * Pi / d;
  double injected[3] = { 0, 0, 0 }, escaped[3] = { 0, 0, 0 }, absorbed[3] = { 0, 0, 0 };
  for (size_t p = 0; p < static_cast<size_t>(n); ++p)
  {
    for (int i = 0; i < d; ++i)
    {
      const size_t k = p * d + i;
      for (int c = 0; c < 3; ++c)
      {
        const double value = incoming[3 * k + c];
        multipleFluence[3 * p + c] += sphere * value;
        injected[c] += weight * in.Emitted[3 * k + c];
        if (in.Visible[k] < 0)
        {
          injected[c] += weight * this->SkyRadiance[c];
        }
        if (!in.HasNext[k])
        {
          escaped[c] += weight * outgoing[3 * k + c];
        }
        absorbed[c] +=
          weight * (1.0 - in.Particles.Albedo[3 * p + c]) * in.Particles.Opacity[3 * p + c] * value;
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    this->InjectedPower[c] = injected[c];
    this->EscapedPower[c] = escaped[c];
    this->AbsorbedPower[c] = absorbed[c];
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkIlluminationNetwork::SolveRotations(vtkPolyData* output)
{
  Internals& in = *this->Internal;
  const size_t n = static_cast<size_t>(in.Particles.N);
  std::vector<double> multiple(3 * n, 0.0);
  bool allConverged = true;
  for (int r = 0; r < this->NumberOfRotations; ++r)
  {
    if (r > 0 && !this->RotateDirections())
    {
      return false;
    }
    const bool converged = this->Iterate();
    if (this->GetAbortExecute())
    {
      return false;
    }
    allConverged = allConverged && converged;
    if (!this->Gather(multiple))
    {
      return false;
    }
    in.HasState = true;
  }
  this->Converged = allConverged;
  if (!allConverged && this->Tolerance > 0)
  {
    vtkWarningMacro("The illumination network did not reach Tolerance "
      << this->Tolerance << " in " << this->MaximumIterations << " iterations (residual "
      << this->Residual << ").");
  }
  vtkNew<vtkFloatArray> direct, scattered, travel;
  travel->SetName(vtkRefractaParticleMedium::DirectDirectionName());
  travel->SetNumberOfComponents(3);
  travel->SetNumberOfTuples(static_cast<vtkIdType>(n));
  direct->SetName(vtkRefractaParticleMedium::DirectFluenceName());
  scattered->SetName(vtkRefractaParticleMedium::MultipleFluenceName());
  direct->SetNumberOfComponents(3);
  scattered->SetNumberOfComponents(3);
  direct->SetNumberOfTuples(static_cast<vtkIdType>(n));
  scattered->SetNumberOfTuples(static_cast<vtkIdType>(n));
  for (size_t k = 0; k < 3 * n; ++k)
  {
    direct->SetValue(static_cast<vtkIdType>(k), static_cast<float>(in.Irradiance[k]));
    travel->SetValue(static_cast<vtkIdType>(k), static_cast<float>(in.Travel[k]));
    scattered->SetValue(
      static_cast<vtkIdType>(k), static_cast<float>(multiple[k] / this->NumberOfRotations));
  }
  vtkPointSet* input = vtkPointSet::GetData(this->GetInputInformation(0, 0));
  output->SetPoints(input->GetPoints());
  output->GetPointData()->PassData(input->GetPointData());
  output->GetPointData()->AddArray(direct);
  output->GetPointData()->AddArray(scattered);
  output->GetPointData()->AddArray(travel);
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType p = 0; p < static_cast<vtkIdType>(n); ++p)
  {
    vertices->InsertNextCell(1, &p);
  }
  output->SetVerts(vertices);
  return true;
}

//------------------------------------------------------------------------------
void vtkIlluminationNetwork::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfDirections: " << this->NumberOfDirections << "\n";
  os << indent << "NumberOfRotations: " << this->NumberOfRotations << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "WindowPixelSize: " << this->WindowPixelSize << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "CheckInterval: " << this->CheckInterval << "\n";
  os << indent << "MaximumIterations: " << this->MaximumIterations << "\n";
  os << indent << "WarmStart: " << this->WarmStart << "\n";
  os << indent << "LightType: " << this->LightType << "\n";
  os << indent << "LightPosition: " << this->LightPosition[0] << " " << this->LightPosition[1]
     << " " << this->LightPosition[2] << "\n";
  os << indent << "LightDirection: " << this->LightDirection[0] << " " << this->LightDirection[1]
     << " " << this->LightDirection[2] << "\n";
  os << indent << "LightIntensity: " << this->LightIntensity[0] << " " << this->LightIntensity[1]
     << " " << this->LightIntensity[2] << "\n";
  os << indent << "SkyRadiance: " << this->SkyRadiance[0] << " " << this->SkyRadiance[1] << " "
     << this->SkyRadiance[2] << "\n";
  os << indent << "Iterations: " << this->Iterations << "\n";
  os << indent << "Residual: " << this->Residual << "\n";
  os << indent << "Converged: " << this->Converged << "\n";
  os << indent << "PixelSize: " << this->PixelSize << "\n";
}
