#include "vtkSceneAnalysis.h"

#include "vtkPolyData.h"
#include "vtkRefractaSurfaceSet.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaParticleMedium.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

vtkStandardNewMacro(vtkSceneAnalysis);

namespace
{
// The medium's arrays as dense float copies, with the documented defaults for missing ones.
struct MediumFields
{
  int Dims[3];
  double Spacing[3];
  std::vector<float> N, SigmaT, Albedo, Anisotropy, Emission, GradN;

  size_t Index(int i, int j, int k) const
  {
    return static_cast<size_t>(i) +
      static_cast<size_t>(Dims[0]) * (j + static_cast<size_t>(Dims[1]) * k);
  }

  void Load(vtkImageData* image)
  {
    image->GetDimensions(this->Dims);
    image->GetSpacing(this->Spacing);
    this->N = vtkRefractaMedium::ReadArray(image, vtkRefractaMedium::REFRACTIVE_INDEX);
    this->SigmaT = vtkRefractaMedium::ReadArray(image, vtkRefractaMedium::EXTINCTION);
    this->Albedo = vtkRefractaMedium::ReadArray(image, vtkRefractaMedium::ALBEDO);
    this->Anisotropy = vtkRefractaMedium::ReadArray(image, vtkRefractaMedium::ANISOTROPY);
    this->Emission = vtkRefractaMedium::ReadArray(image, vtkRefractaMedium::EMISSION);
    if (image->GetPointData()->GetArray(vtkRefractaMedium::RefractiveIndexGradientName()))
    {
      this->GradN =
        vtkRefractaMedium::ReadArray(image, vtkRefractaMedium::REFRACTIVE_INDEX_GRADIENT);
    }
    else
    {
      this->ComputeGradient();
    }
  }

  // Central differences in grid-local world units, one-sided at the faces.
  void ComputeGradient()
  {
    this->GradN.assign(this->N.size() * 3, 0.0f);
    vtkSMPTools::For(0, this->Dims[2],
      [&](int k0, int k1)
      {
        for (int k = k0; k < k1; ++k)
        {
          for (int j = 0; j < this->Dims[1]; ++j)
          {
            for (int i = 0; i < this->Dims[0]; ++i)
            {
              const int ijk[3] = { i, j, k };
              for (int a = 0; a < 3; ++a)
              {
                if (this->Dims[a] < 2)
                {
                  continue;
                }
                int lo[3] = { i, j, k }, hi[3] = { i, j, k };
                lo[a] = std::max(ijk[a] - 1, 0);
                hi[a] = std::min(ijk[a] + 1, this->Dims[a] - 1);
                const double dn = this->N[this->Index(hi[0], hi[1], hi[2])] -
                  this->N[this->Index(lo[0], lo[1], lo[2])];
                this->GradN[3 * this->Index(i, j, k) + a] =
                  static_cast<float>(dn / ((hi[a] - lo[a]) * this->Spacing[a]));
              }
            }
          }
        }
      });
  }

  // Largest sigma_t over the RGB channels, trilinear at continuous voxel coordinate u.
  double SigmaTMaxAt(const double u[3]) const
  {
    int i0[3], i1[3];
    double w[3];
    for (int a = 0; a < 3; ++a)
    {
      const double c = std::min(std::max(u[a], 0.0), double(this->Dims[a] - 1));
      i0[a] = static_cast<int>(std::floor(c));
      i1[a] = std::min(i0[a] + 1, this->Dims[a] - 1);
      w[a] = c - i0[a];
    }
    double best = 0.0;
    for (int ch = 0; ch < 3; ++ch)
    {
      double value = 0.0;
      for (int corner = 0; corner < 8; ++corner)
      {
        const int i = (corner & 1) ? i1[0] : i0[0];
        const int j = (corner & 2) ? i1[1] : i0[1];
        const int k = (corner & 4) ? i1[2] : i0[2];
        const double weight = ((corner & 1) ? w[0] : 1 - w[0]) * ((corner & 2) ? w[1] : 1 - w[1]) *
          ((corner & 4) ? w[2] : 1 - w[2]);
        value += weight * this->SigmaT[3 * this->Index(i, j, k) + ch];
      }
      best = std::max(best, value);
    }
    return best;
  }
};

// Per-thread accumulation of the per-voxel facts.
struct VoxelFacts
{
  double NMin = std::numeric_limits<double>::max();
  double NMax = std::numeric_limits<double>::lowest();
  double AlbedoMin = std::numeric_limits<double>::max();
  double AlbedoMax = std::numeric_limits<double>::lowest();
  double EmissionMax = 0.0;
  double SigmaTMax = 0.0;
  double Scattering = 0.0;            // sum of sigma_s (mean over the channels)
  double AnisotropicScattering = 0.0; // sum of sigma_s |g|
  bool Scatters = false;
  vtkIdType Occupied = 0;
};

// Largest line integrals along `axis` of sigma_t (per channel max), sigma_s, and abs(grad n) / n.
struct LineIntegrals
{
  double Extinction = 0.0;
  double Scattering = 0.0;
  double Bending = 0.0;
};

LineIntegrals IntegrateLines(const MediumFields& f, int axis)
{
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  const double ds = f.Spacing[axis];
  vtkSMPThreadLocal<LineIntegrals> local;
  vtkSMPTools::For(0, f.Dims[a2],
    [&](int b0, int b1)
    {
      LineIntegrals& best = local.Local();
      for (int b = b0; b < b1; ++b)
      {
        for (int a = 0; a < f.Dims[a1]; ++a)
        {
          double ext[3] = { 0, 0, 0 }, sca[3] = { 0, 0, 0 }, bend = 0.0;
          for (int t = 0; t < f.Dims[axis]; ++t)
          {
            int ijk[3];
            ijk[axis] = t;
            ijk[a1] = a;
            ijk[a2] = b;
            const size_t p = f.Index(ijk[0], ijk[1], ijk[2]);
            for (int c = 0; c < 3; ++c)
            {
              ext[c] += f.SigmaT[3 * p + c] * ds;
              sca[c] += f.SigmaT[3 * p + c] * f.Albedo[3 * p + c] * ds;
            }
            const double g[3] = { f.GradN[3 * p], f.GradN[3 * p + 1], f.GradN[3 * p + 2] };
            bend += vtkMath::Norm(g) / std::max(1.0, double(f.N[p])) * ds;
          }
          best.Extinction = std::max({ best.Extinction, ext[0], ext[1], ext[2] });
          best.Scattering = std::max({ best.Scattering, sca[0], sca[1], sca[2] });
          best.Bending = std::max(best.Bending, bend);
        }
      }
    });
  LineIntegrals result;
  for (const LineIntegrals& l : local)
  {
    result.Extinction = std::max(result.Extinction, l.Extinction);
    result.Scattering = std::max(result.Scattering, l.Scattering);
    result.Bending = std::max(result.Bending, l.Bending);
  }
  return result;
}

// Largest optical thickness from probe points on an 8^3 lattice inside the box toward the light
// (to the box face, or to the light itself when it is inside), marched in half-voxel steps.
double ProbeTowardLight(const MediumFields& fields, vtkImageData* medium, vtkLight* light)
{
  // Grid-local frame (vtkRefractaGridFrame: origin, extent and direction matrix).
  vtkNew<vtkRefractaGridFrame> grid;
  grid->SetImage(medium);
  auto toLocal = [&](const double world[3], bool isPoint, double local[3])
  {
    if (isPoint)
    {
      grid->WorldToLocalPoint(world, local);
    }
    else
    {
      grid->WorldToLocalVector(world, local);
    }
  };
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = -0.5 * fields.Spacing[a];
    hi[a] = (fields.Dims[a] - 0.5) * fields.Spacing[a];
  }
  double lightPosition[3], towardLight[3];
  toLocal(light->GetTransformedPosition(), true, lightPosition);
  double travel[3];
  {
    const double* p = light->GetTransformedPosition();
    const double* f = light->GetTransformedFocalPoint();
    const double worldTravel[3] = { f[0] - p[0], f[1] - p[1], f[2] - p[2] };
    toLocal(worldTravel, false, travel);
    vtkMath::Normalize(travel);
  }
  const bool positional = light->GetPositional() != 0;
  const int probesPerAxis = 8;
  double worst = 0.0;
  for (int pk = 0; pk < probesPerAxis; ++pk)
  {
    for (int pj = 0; pj < probesPerAxis; ++pj)
    {
      for (int pi = 0; pi < probesPerAxis; ++pi)
      {
        const int pijk[3] = { pi, pj, pk };
        double target[3];
        for (int a = 0; a < 3; ++a)
        {
          target[a] = lo[a] + (pijk[a] + 0.5) / probesPerAxis * (hi[a] - lo[a]);
        }
        double length = std::numeric_limits<double>::max();
        if (positional)
        {
          for (int a = 0; a < 3; ++a)
          {
            towardLight[a] = lightPosition[a] - target[a];
          }
          length = vtkMath::Normalize(towardLight);
        }
        else
        {
          for (int a = 0; a < 3; ++a)
          {
            towardLight[a] = -travel[a];
          }
        }
        // March from the target toward the light until it or the box's face is reached, half a
        // voxel per step along the axis the ray crosses fastest in voxels: at most about twice
        // the grid's largest dimension of steps, whatever the voxels' aspect ratio (a step of
        // half the smallest spacing took ~1e30 steps through a grid 2e30 long).
        double voxelsPerLength = 0.0;
        for (int a = 0; a < 3; ++a)
        {
          voxelsPerLength = std::max(voxelsPerLength, std::abs(towardLight[a]) / fields.Spacing[a]);
        }
        const double step = voxelsPerLength > 0 ? 0.5 / voxelsPerLength : length;
        double tau = 0.0;
        for (double t = 0.5 * step; t < length; t += step)
        {
          double u[3];
          bool inside = true;
          for (int a = 0; a < 3; ++a)
          {
            const double x = target[a] + t * towardLight[a];
            inside = inside && x >= lo[a] && x <= hi[a];
            u[a] = x / fields.Spacing[a];
          }
          if (!inside)
          {
            break;
          }
          tau += fields.SigmaTMaxAt(u) * step;
        }
        worst = std::max(worst, tau);
      }
    }
  }
  return worst;
}

bool LightHasPower(vtkLight* light)
{
  const double* c = light->GetDiffuseColor();
  return light->GetSwitch() && light->GetIntensity() > 0.0 && (c[0] > 0 || c[1] > 0 || c[2] > 0);
}
}

//------------------------------------------------------------------------------
// The light-independent facts of one medium, and its extinction for the light probes.
struct vtkSceneAnalysis::MediumCache
{
  vtkWeakPointer<vtkImageData> Medium;
  vtkMTimeType MediumTime = 0;
  MediumFields Fields; // only Dims, Spacing and SigmaT are kept after the scan
  double RefractiveIndexRange[2] = { 1.0, 1.0 };
  double AlbedoRange[2] = { 0.0, 0.0 };
  bool HasScattering = false;
  double MeanAnisotropy = 0.0;
  double MaximumEmission = 0.0;
  double OccupiedFraction = 0.0;
  double AxisOpticalThickness[3] = { 0.0, 0.0, 0.0 };
  double MaximumOpticalThickness = 0.0;
  double MaximumScatteringThickness = 0.0;
  double MaximumVoxelOpticalDepth = 0.0;
  double MaximumBendingAngle = 0.0;
  double MaximumDisplacementInVoxels = 0.0;

  bool Matches(vtkImageData* medium) const
  {
    return medium && this->Medium == medium && this->MediumTime == medium->GetMTime();
  }
};

//------------------------------------------------------------------------------
vtkSceneAnalysis::vtkSceneAnalysis()
  : Cache(new MediumCache)
{
}
vtkSceneAnalysis::~vtkSceneAnalysis() = default;

//------------------------------------------------------------------------------
void vtkSceneAnalysis::SetMedium(vtkImageData* medium)
{
  if (this->Medium != medium)
  {
    this->Medium = medium;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkImageData* vtkSceneAnalysis::GetMedium()
{
  return this->Medium;
}

//------------------------------------------------------------------------------
void vtkSceneAnalysis::AddLight(vtkLight* light)
{
  if (light)
  {
    this->Lights.emplace_back(light);
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkSceneAnalysis::RemoveAllLights()
{
  this->Lights.clear();
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkSceneAnalysis::SetLights(vtkLightCollection* lights)
{
  this->Lights.clear();
  if (lights)
  {
    lights->InitTraversal();
    while (vtkLight* light = lights->GetNextItem())
    {
      this->Lights.emplace_back(light);
    }
  }
  this->Modified();
}

namespace
{
// Surfaces with something to hit (the plan depends on their presence only).
int CountSurfaces(vtkRefractaSurfaceSet* set)
{
  return set ? set->GetNumberOfNonEmptySurfaces() : 0;
}
}

//------------------------------------------------------------------------------
void vtkSceneAnalysis::Reset()
{
  this->RefractiveIndexRange[0] = this->RefractiveIndexRange[1] = 1.0;
  this->MaximumBendingAngle = this->MaximumDisplacementInVoxels = 0.0;
  std::fill(this->AxisOpticalThickness, this->AxisOpticalThickness + 3, 0.0);
  this->MaximumOpticalThickness = this->MaximumScatteringThickness = 0.0;
  this->MaximumVoxelOpticalDepth = 0.0;
  this->LightOpticalThickness.assign(this->Lights.size(), 0.0);
  this->AlbedoRange[0] = this->AlbedoRange[1] = 0.0;
  this->HasScattering = this->HasEmission = false;
  this->MeanAnisotropy = 0.0;
  this->MaximumEmission = this->OccupiedFraction = 0.0;
  this->NumberOfPoweredLights = this->NumberOfLightsInsideMedium = 0;
  this->NumberOfSurfaces = this->NumberOfInterfaceSurfaces = 0;
  this->NumberOfDepositedParticles = 0;
}

//------------------------------------------------------------------------------
namespace
{
// Whether `light` is positional and sits in or next to the medium: a voxel within
// LightNeighbourhood voxels of it (Chebyshev distance from the voxel nearest to it, through the
// grid's frame: extent, spacing, direction; the light may be just outside the grid) has
// extinction. Its single scattering is then concentrated on the grid's scale (a point source for
// the lattice); a light further away spreads its light over the medium before it scatters.
constexpr int LightNeighbourhood = 2;

bool LightInMedium(const MediumFields& fields, vtkImageData* medium, vtkLight* light)
{
  if (!light->GetPositional() || fields.SigmaT.empty())
  {
    return false;
  }
  vtkNew<vtkRefractaGridFrame> frame;
  frame->SetImage(medium);
  double index[3]; // from the first point: 0 .. dims - 1
  frame->WorldToIndexPoint(light->GetPosition(), index);
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    if (!(index[a] >= -0.5 - LightNeighbourhood &&
          index[a] <= fields.Dims[a] - 0.5 + LightNeighbourhood))
    {
      return false;
    }
    const int nearest = static_cast<int>(std::lround(index[a]));
    lo[a] = std::max(nearest - LightNeighbourhood, 0);
    hi[a] = std::min(nearest + LightNeighbourhood, fields.Dims[a] - 1);
  }
  for (int k = lo[2]; k <= hi[2]; ++k)
  {
    for (int j = lo[1]; j <= hi[1]; ++j)
    {
      for (int i = lo[0]; i <= hi[0]; ++i)
      {
        const size_t v = fields.Index(i, j, k);
        if (fields.SigmaT[3 * v] > 0 || fields.SigmaT[3 * v + 1] > 0 ||
          fields.SigmaT[3 * v + 2] > 0)
        {
          return true;
        }
      }
    }
  }
  return false;
}
}

//------------------------------------------------------------------------------
bool vtkSceneAnalysis::Analyze()
{
  this->Reset();
  if (!this->Cache->Matches(this->Medium) && !this->ScanMedium())
  {
    return false;
  }
  const MediumCache& cache = *this->Cache;
  std::copy(cache.RefractiveIndexRange, cache.RefractiveIndexRange + 2, this->RefractiveIndexRange);
  std::copy(cache.AlbedoRange, cache.AlbedoRange + 2, this->AlbedoRange);
  std::copy(cache.AxisOpticalThickness, cache.AxisOpticalThickness + 3, this->AxisOpticalThickness);
  this->HasScattering = cache.HasScattering;
  this->MeanAnisotropy = cache.MeanAnisotropy;
  this->MaximumEmission = cache.MaximumEmission;
  this->HasEmission = cache.MaximumEmission > 0.0;
  this->OccupiedFraction = cache.OccupiedFraction;
  this->MaximumOpticalThickness = cache.MaximumOpticalThickness;
  this->MaximumScatteringThickness = cache.MaximumScatteringThickness;
  this->MaximumVoxelOpticalDepth = cache.MaximumVoxelOpticalDepth;
  this->MaximumBendingAngle = cache.MaximumBendingAngle;
  this->MaximumDisplacementInVoxels = cache.MaximumDisplacementInVoxels;

  for (size_t l = 0; l < this->Lights.size(); ++l)
  {
    if (LightHasPower(this->Lights[l]))
    {
      ++this->NumberOfPoweredLights;
      this->LightOpticalThickness[l] =
        ProbeTowardLight(cache.Fields, this->Medium, this->Lights[l]);
      this->NumberOfLightsInsideMedium +=
        LightInMedium(cache.Fields, this->Medium, this->Lights[l]) ? 1 : 0;
    }
  }
  this->NumberOfSurfaces = CountSurfaces(this->Surfaces);
  this->NumberOfInterfaceSurfaces =
    this->Surfaces ? this->Surfaces->GetNumberOfNonEmptyDielectricSurfaces() : 0;
  vtkDataArray* particles =
    this->Medium->GetFieldData()->GetArray(vtkRefractaParticleMedium::DepositedParticlesName());
  this->NumberOfDepositedParticles = particles && particles->GetNumberOfTuples() > 0
    ? static_cast<vtkIdType>(std::max(0.0, particles->GetComponent(0, 0)))
    : 0;
  this->Modified();
  return true;
}

//------------------------------------------------------------------------------
bool vtkSceneAnalysis::ScanMedium()
{
  MediumCache& cache = *this->Cache;
  cache.Medium = nullptr;
  vtkNew<vtkMediumValidator> validator;
  if (!validator->Validate(this->Medium))
  {
    vtkErrorMacro("Cannot analyse the scene: " << validator->GetErrorMessage());
    return false;
  }
  cache = MediumCache();
  MediumFields& fields = cache.Fields;
  fields.Load(this->Medium);
  const vtkIdType numberOfVoxels = this->Medium->GetNumberOfPoints();

  vtkSMPThreadLocal<VoxelFacts> local;
  vtkSMPTools::For(0, numberOfVoxels,
    [&](vtkIdType begin, vtkIdType end)
    {
      VoxelFacts& facts = local.Local();
      for (vtkIdType p = begin; p < end; ++p)
      {
        const double n = fields.N[p];
        facts.NMin = std::min(facts.NMin, n);
        facts.NMax = std::max(facts.NMax, n);
        bool occupied = n > 1.0;
        double sigmaS = 0.0;
        for (int c = 0; c < 3; ++c)
        {
          const double sigmaT = fields.SigmaT[3 * p + c];
          const double albedo = fields.Albedo[3 * p + c];
          sigmaS += sigmaT * albedo / 3.0;
          const double emission = fields.Emission[3 * p + c];
          if (sigmaT > 0.0)
          {
            facts.AlbedoMin = std::min(facts.AlbedoMin, albedo);
            facts.AlbedoMax = std::max(facts.AlbedoMax, albedo);
            facts.Scatters = facts.Scatters || albedo > 0.0;
            occupied = true;
          }
          facts.EmissionMax = std::max(facts.EmissionMax, emission);
          if (albedo > 0.0)
          {
            facts.SigmaTMax = std::max(facts.SigmaTMax, sigmaT); // of scattering voxels only
          }
          occupied = occupied || emission > 0.0;
        }
        facts.Occupied += occupied ? 1 : 0;
        facts.Scattering += sigmaS;
        facts.AnisotropicScattering += sigmaS * std::abs(fields.Anisotropy[p]);
      }
    });
  VoxelFacts all;
  for (const VoxelFacts& f : local)
  {
    all.NMin = std::min(all.NMin, f.NMin);
    all.NMax = std::max(all.NMax, f.NMax);
    all.AlbedoMin = std::min(all.AlbedoMin, f.AlbedoMin);
    all.AlbedoMax = std::max(all.AlbedoMax, f.AlbedoMax);
    all.EmissionMax = std::max(all.EmissionMax, f.EmissionMax);
    all.SigmaTMax = std::max(all.SigmaTMax, f.SigmaTMax);
    all.Scatters = all.Scatters || f.Scatters;
    all.Scattering += f.Scattering;
    all.AnisotropicScattering += f.AnisotropicScattering;
    all.Occupied += f.Occupied;
  }
  cache.RefractiveIndexRange[0] = all.NMin;
  cache.RefractiveIndexRange[1] = all.NMax;
  cache.AlbedoRange[0] = cache.AlbedoRange[1] = 0.0;
  if (all.AlbedoMax >= all.AlbedoMin)
  {
    cache.AlbedoRange[0] = all.AlbedoMin;
    cache.AlbedoRange[1] = all.AlbedoMax;
  }
  cache.HasScattering = all.Scatters;
  cache.MeanAnisotropy = all.Scattering > 0.0 ? all.AnisotropicScattering / all.Scattering : 0.0;
  cache.MaximumEmission = all.EmissionMax;
  cache.OccupiedFraction = static_cast<double>(all.Occupied) / numberOfVoxels;

  double diagonal2 = 0.0;
  double minimumSpacing = std::numeric_limits<double>::max();
  for (int axis = 0; axis < 3; ++axis)
  {
    const LineIntegrals lines = IntegrateLines(fields, axis);
    cache.AxisOpticalThickness[axis] = lines.Extinction;
    cache.MaximumOpticalThickness = std::max(cache.MaximumOpticalThickness, lines.Extinction);
    cache.MaximumScatteringThickness = std::max(cache.MaximumScatteringThickness, lines.Scattering);
    cache.MaximumBendingAngle = std::max(cache.MaximumBendingAngle, lines.Bending);
    diagonal2 += std::pow(fields.Dims[axis] * fields.Spacing[axis], 2);
    minimumSpacing = std::min(minimumSpacing, fields.Spacing[axis]);
  }
  cache.MaximumDisplacementInVoxels =
    cache.MaximumBendingAngle * std::sqrt(diagonal2) / minimumSpacing;
  cache.MaximumVoxelOpticalDepth =
    all.SigmaTMax * std::max({ fields.Spacing[0], fields.Spacing[1], fields.Spacing[2] });

  // The light probes need only the extinction: free the rest.
  std::vector<float>().swap(fields.N);
  std::vector<float>().swap(fields.Albedo);
  std::vector<float>().swap(fields.Anisotropy);
  std::vector<float>().swap(fields.Emission);
  std::vector<float>().swap(fields.GradN);
  cache.Medium = this->Medium;
  cache.MediumTime = this->Medium->GetMTime();
  ++this->NumberOfMediumScans;
  return true;
}

//------------------------------------------------------------------------------
void vtkSceneAnalysis::SetSurfaces(vtkRefractaSurfaceSet* surfaces)
{
  if (this->Surfaces != surfaces)
  {
    this->Surfaces = surfaces;
    this->Modified();
  }
}

vtkRefractaSurfaceSet* vtkSceneAnalysis::GetSurfaces()
{
  return this->Surfaces;
}

//------------------------------------------------------------------------------
double vtkSceneAnalysis::GetMaximumOpticalThickness(int axis) const
{
  return (axis >= 0 && axis < 3) ? this->AxisOpticalThickness[axis] : 0.0;
}

//------------------------------------------------------------------------------
double vtkSceneAnalysis::GetOpticalThicknessTowardLight(int i) const
{
  return (i >= 0 && i < static_cast<int>(this->LightOpticalThickness.size()))
    ? this->LightOpticalThickness[i]
    : 0.0;
}

//------------------------------------------------------------------------------
void vtkSceneAnalysis::RecordInFieldData(vtkFieldData* fieldData) const
{
  if (!fieldData)
  {
    return;
  }
  auto add = [fieldData](const char* name, std::initializer_list<double> values)
  {
    vtkNew<vtkDoubleArray> array;
    array->SetName(name);
    for (double v : values)
    {
      array->InsertNextValue(v);
    }
    fieldData->AddArray(array);
  };
  add("AnalysisRefractiveIndexRange",
    { this->RefractiveIndexRange[0], this->RefractiveIndexRange[1] });
  add("AnalysisMaximumBendingAngle", { this->MaximumBendingAngle });
  add("AnalysisMaximumDisplacementInVoxels", { this->MaximumDisplacementInVoxels });
  add("AnalysisOpticalThicknessAlongAxes",
    { this->AxisOpticalThickness[0], this->AxisOpticalThickness[1],
      this->AxisOpticalThickness[2] });
  add("AnalysisMaximumScatteringThickness", { this->MaximumScatteringThickness });
  vtkNew<vtkDoubleArray> toward;
  toward->SetName("AnalysisOpticalThicknessTowardLights");
  for (double tau : this->LightOpticalThickness)
  {
    toward->InsertNextValue(tau);
  }
  fieldData->AddArray(toward);
  add("AnalysisAlbedoRange", { this->AlbedoRange[0], this->AlbedoRange[1] });
  add("AnalysisMeanAnisotropy", { this->MeanAnisotropy });
  add("AnalysisMaximumEmission", { this->MaximumEmission });
  add("AnalysisOccupiedFraction", { this->OccupiedFraction });
  add("AnalysisNumberOfPoweredLights", { static_cast<double>(this->NumberOfPoweredLights) });
  add("AnalysisNumberOfLightsInsideMedium",
    { static_cast<double>(this->NumberOfLightsInsideMedium) });
  add("AnalysisNumberOfSurfaces", { static_cast<double>(this->NumberOfSurfaces) });
  add(
    "AnalysisNumberOfInterfaceSurfaces", { static_cast<double>(this->NumberOfInterfaceSurfaces) });
  add("AnalysisNumberOfDepositedParticles",
    { static_cast<double>(this->NumberOfDepositedParticles) });
}

//------------------------------------------------------------------------------
std::string vtkSceneAnalysis::GetSummary() const
{
  std::ostringstream s;
  s << "n in [" << this->RefractiveIndexRange[0] << ", " << this->RefractiveIndexRange[1]
    << "], bending <= " << this->MaximumBendingAngle << " rad ("
    << this->MaximumDisplacementInVoxels << " voxels), tau <= " << this->MaximumOpticalThickness
    << ", tau_s <= " << this->MaximumScatteringThickness
    << ", voxel tau <= " << this->MaximumVoxelOpticalDepth << ", albedo in ["
    << this->AlbedoRange[0] << ", " << this->AlbedoRange[1] << "], mean |g| "
    << this->MeanAnisotropy << ", emission " << (this->HasEmission ? "yes" : "no") << ", occupied "
    << 100.0 * this->OccupiedFraction << "%, " << this->NumberOfPoweredLights
    << " powered light(s), " << this->NumberOfSurfaces << " surface(s)";
  if (this->NumberOfInterfaceSurfaces > 0)
  {
    s << " (" << this->NumberOfInterfaceSurfaces << " dielectric)";
  }
  if (this->NumberOfDepositedParticles > 0)
  {
    s << ", " << this->NumberOfDepositedParticles << " particles deposited";
  }
  return s.str();
}

//------------------------------------------------------------------------------
void vtkSceneAnalysis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Medium: " << this->Medium.Get() << "\n";
  os << indent << "NumberOfLights: " << this->Lights.size() << "\n";
  os << indent << "EnvironmentLight: " << this->EnvironmentLight << "\n";
  os << indent << "Facts: " << this->GetSummary() << "\n";
  for (size_t l = 0; l < this->LightOpticalThickness.size(); ++l)
  {
    os << indent << "OpticalThicknessTowardLight " << l << ": " << this->LightOpticalThickness[l]
       << "\n";
  }
}
