#include "vtkParticleMediumDeposit.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaParticleMedium.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkParticleMediumDeposit);

namespace
{
using PM = vtkRefractaParticleMedium;

double Value(vtkDataArray* array, vtkIdType p, int c, double fallback)
{
  return array ? array->GetComponent(p, c) : fallback;
}

vtkSmartPointer<vtkFloatArray> NewArray(const char* name, int components, vtkIdType n)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(n);
  array->Fill(0.0);
  return array;
}

// Per-voxel sums of the deposit, in double.
struct Sums
{
  explicit Sums(size_t n)
    : SigmaT(3 * n, 0.0)
    , SigmaS(3 * n, 0.0)
    , SigmaSG(3 * n, 0.0)
    , Emission(3 * n, 0.0)
    , Single(3 * n, 0.0)
    , Direction(3 * n, 0.0)
    , Multiple(3 * n, 0.0)
  {
  }
  std::vector<double> SigmaT, SigmaS, SigmaSG, Emission, Single, Direction, Multiple;
};
}

//------------------------------------------------------------------------------
vtkParticleMediumDeposit::vtkParticleMediumDeposit()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

int vtkParticleMediumDeposit::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

//------------------------------------------------------------------------------
int vtkParticleMediumDeposit::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  for (int port = 0; port < 2; ++port)
  {
    const int extent[6] = { 0, std::max(1, this->SampleDimensions[0] - 1), 0,
      std::max(1, this->SampleDimensions[1] - 1), 0, std::max(1, this->SampleDimensions[2] - 1) };
    outputVector->GetInformationObject(port)->Set(
      vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkParticleMediumDeposit::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkImageData* medium = vtkImageData::GetData(outputVector, 0);
  vtkImageData* lighting = vtkImageData::GetData(outputVector, 1);
  std::string message;
  if (!PM::Validate(input, message))
  {
    vtkErrorMacro("Input 0 is not a valid particle medium: " << message << ".");
    return 0;
  }
  const int* dims = this->SampleDimensions;
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    vtkErrorMacro(
      "SampleDimensions " << dims[0] << " " << dims[1] << " " << dims[2] << " must each be >= 2.");
    return 0;
  }
  vtkPointData* pd = input->GetPointData();
  vtkDataArray* radius = pd->GetArray(PM::RadiusName());
  vtkDataArray* extinction = pd->GetArray(PM::ExtinctionName());
  vtkDataArray* albedo = pd->GetArray(PM::AlbedoName());
  vtkDataArray* g = pd->GetArray(PM::AnisotropyName());
  vtkDataArray* emission = pd->GetArray(PM::EmissionName());
  vtkDataArray* direct = pd->GetArray(PM::DirectFluenceName());
  vtkDataArray* travel = pd->GetArray(PM::DirectDirectionName());
  vtkDataArray* multiple = pd->GetArray(PM::MultipleFluenceName());
  const bool lit = direct && travel && multiple;

  double bounds[6];
  std::copy(this->ModelBounds, this->ModelBounds + 6, bounds);
  if (!(bounds[0] < bounds[1] && bounds[2] < bounds[3] && bounds[4] < bounds[5]))
  {
    input->GetBounds(bounds);
    const double grow = radius->GetRange(0)[1];
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] -= grow;
      bounds[2 * a + 1] += grow;
    }
  }
  double origin[3], spacing[3];
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = bounds[2 * a];
    spacing[a] = std::max(bounds[2 * a + 1] - bounds[2 * a], 1e-12) / (dims[a] - 1);
  }
  const size_t voxels = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  Sums sums(voxels);
  const int s = this->SamplesPerAxis;
  const double weight = 1.0 / (s * s * s);
  double x[3];
  for (vtkIdType p = 0; p < input->GetNumberOfPoints(); ++p)
  {
    input->GetPoint(p, x);
    const double r = radius->GetComponent(p, 0);
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::max(0, static_cast<int>(std::floor((x[a] - r - origin[a]) / spacing[a] - 0.5)));
      hi[a] = std::min(
        dims[a] - 1, static_cast<int>(std::ceil((x[a] + r - origin[a]) / spacing[a] + 0.5)));
    }
    // Scattered power of the particle per unit of its volume, per unit fluence.
    double a[3], perVolume[3];
    for (int c = 0; c < 3; ++c)
    {
      a[c] = Value(albedo, p, c, 0.0);
      perVolume[c] = PM::ScatteringPerVolume(extinction->GetComponent(p, c), a[c], r);
    }
    const double gp = Value(g, p, 0, 0.0);
    for (int k = lo[2]; k <= hi[2]; ++k)
    {
      for (int j = lo[1]; j <= hi[1]; ++j)
      {
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          const int index[3] = { i, j, k };
          int inside = 0;
          for (int sk = 0; sk < s; ++sk)
          {
            for (int sj = 0; sj < s; ++sj)
            {
              for (int si = 0; si < s; ++si)
              {
                const int sub[3] = { si, sj, sk };
                double d2 = 0;
                for (int ax = 0; ax < 3; ++ax)
                {
                  const double y =
                    origin[ax] + spacing[ax] * (index[ax] + (sub[ax] + 0.5) / s - 0.5) - x[ax];
                  d2 += y * y;
                }
                inside += d2 <= r * r ? 1 : 0;
              }
            }
          }
          if (!inside)
          {
            continue;
          }
          const double f = inside * weight;
          const size_t v = static_cast<size_t>(i) +
            static_cast<size_t>(dims[0]) * (j + static_cast<size_t>(dims[1]) * k);
          for (int c = 0; c < 3; ++c)
          {
            const double st = extinction->GetComponent(p, c);
            sums.SigmaT[3 * v + c] += f * st;
            sums.SigmaS[3 * v + c] += f * st * a[c];
            sums.SigmaSG[3 * v + c] += f * st * a[c] * gp;
            sums.Emission[3 * v + c] += f * Value(emission, p, c, 0.0);
            if (lit)
            {
              const double single = f * perVolume[c] * direct->GetComponent(p, c);
              sums.Single[3 * v + c] += single;
              sums.Multiple[3 * v + c] += f * perVolume[c] * multiple->GetComponent(p, c);
              // The mean travel direction, weighted by the green channel's scattered power.
              sums.Direction[3 * v + c] +=
                f * perVolume[1] * direct->GetComponent(p, 1) * travel->GetComponent(p, c);
            }
          }
        }
      }
    }
  }
  const vtkIdType n = static_cast<vtkIdType>(voxels);
  auto ext = NewArray(vtkRefractaMedium::ExtinctionName(), 3, n);
  auto alb = NewArray(vtkRefractaMedium::AlbedoName(), 3, n);
  auto ani = NewArray(vtkRefractaMedium::AnisotropyName(), 1, n);
  auto emi = NewArray(vtkRefractaMedium::EmissionName(), 3, n);
  for (size_t v = 0; v < voxels; ++v)
  {
    double sigmaS = 0, sigmaSG = 0;
    for (int c = 0; c < 3; ++c)
    {
      const double st = sums.SigmaT[3 * v + c];
      ext->SetComponent(v, c, st);
      alb->SetComponent(v, c, st > 0 ? std::min(1.0, sums.SigmaS[3 * v + c] / st) : 0.0);
      emi->SetComponent(v, c, sums.Emission[3 * v + c]);
      sigmaS += sums.SigmaS[3 * v + c];
      sigmaSG += sums.SigmaSG[3 * v + c];
    }
    ani->SetValue(v, sigmaS > 0 ? std::clamp(sigmaSG / sigmaS, -0.999, 0.999) : 0.0);
  }
  medium->SetDimensions(dims);
  medium->SetOrigin(origin);
  medium->SetSpacing(spacing);
  medium->GetPointData()->AddArray(ext);
  medium->GetPointData()->AddArray(alb);
  medium->GetPointData()->AddArray(ani);
  medium->GetPointData()->AddArray(emi);
  vtkNew<vtkIdTypeArray> particles;
  particles->SetName(vtkRefractaParticleMedium::DepositedParticlesName());
  particles->InsertNextValue(input->GetNumberOfPoints());
  medium->GetFieldData()->AddArray(particles);
  lighting->SetDimensions(dims);
  lighting->SetOrigin(origin);
  lighting->SetSpacing(spacing);
  if (lit)
  {
    auto single = NewArray(vtkRefractaLightingVolume::RadianceName(), 3, n);
    auto dir = NewArray(vtkRefractaLightingVolume::RadianceDirectionName(), 3, n);
    auto ms = NewArray(vtkRefractaLightingVolume::MultipleScatteringName(), 3, n);
    for (size_t v = 0; v < voxels; ++v)
    {
      const double* d = &sums.Direction[3 * v];
      const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (int c = 0; c < 3; ++c)
      {
        single->SetComponent(v, c, sums.Single[3 * v + c]);
        ms->SetComponent(v, c, sums.Multiple[3 * v + c]);
        dir->SetComponent(v, c, len > 0 ? d[c] / len : 0.0);
      }
    }
    lighting->GetPointData()->AddArray(single);
    lighting->GetPointData()->AddArray(dir);
    lighting->GetPointData()->AddArray(ms);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkParticleMediumDeposit::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleDimensions: " << this->SampleDimensions[0] << " "
     << this->SampleDimensions[1] << " " << this->SampleDimensions[2] << "\n";
  os << indent << "ModelBounds: " << this->ModelBounds[0] << " " << this->ModelBounds[1] << " "
     << this->ModelBounds[2] << " " << this->ModelBounds[3] << " " << this->ModelBounds[4] << " "
     << this->ModelBounds[5] << "\n";
  os << indent << "SamplesPerAxis: " << this->SamplesPerAxis << "\n";
}
