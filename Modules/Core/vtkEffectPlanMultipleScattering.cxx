// vtkEffectPlan's choice of the multiple-scattering method (issue 14): the Lattice-Boltzmann
// solver alone, the first-collision split (photons carry the first k orders, the lattice the
// rest) or photons carrying every order.
#include "vtkEffectPlan.h"

#include "vtkSceneAnalysis.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <sstream>

namespace
{
const char* const MultipleMethodNames[] = { "auto", "lattice", "split", "photons" };

// |axis / diagonal - 1| of S_ms at distance 1 from a point light in fog, per k = 0, 1, ...
// (RefractaTransport.MultipleScatteringIsotropy and its k sweep, 2^18-2^19 photons).
const double AnisotropyD3Q6[] = { 2.57, 0.74, 0.27, 0.11, 0.049, 0.024, 0.012, 0.0085, 0.0038 };
const double AnisotropyD3Q18[] = { 0.34, 0.094, 0.028, 0.0076, 0.0016 };
// The largest k the plan chooses: beyond the table the anisotropy is below the photon noise of
// the measurement.
constexpr int MaximumChosenOrders = 8;
}

const char* vtkEffectPlan::GetMultipleScatteringMethodName(int method)
{
  return method >= AUTOMATIC_MULTIPLE_METHOD && method < NUMBER_OF_MULTIPLE_METHODS
    ? MultipleMethodNames[method]
    : nullptr;
}

int vtkEffectPlan::GetMultipleScatteringMethodFromName(const char* name)
{
  for (int m = AUTOMATIC_MULTIPLE_METHOD; m < NUMBER_OF_MULTIPLE_METHODS && name; ++m)
  {
    if (std::strcmp(name, MultipleMethodNames[m]) == 0)
    {
      return m;
    }
  }
  return -1;
}

double vtkEffectPlan::GetRayEffectAnisotropy(int lattice, int orders)
{
  const double* table = lattice == 18 ? AnisotropyD3Q18 : AnisotropyD3Q6;
  const int size = lattice == 18 ? static_cast<int>(std::size(AnisotropyD3Q18))
                                 : static_cast<int>(std::size(AnisotropyD3Q6));
  return table[std::min(std::max(orders, 0), size - 1)];
}

//------------------------------------------------------------------------------
void vtkEffectPlan::SetLatticeDirections(int directions)
{
  if (directions != AUTOMATIC_LATTICE && directions != 6 && directions != 18)
  {
    vtkErrorMacro(
      "LatticeDirections " << directions << " is not supported: use 0 (automatic), 6 or 18.");
    return;
  }
  if (this->LatticeDirections != directions)
  {
    this->LatticeDirections = directions;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
bool vtkEffectPlan::CallsForD3Q18(vtkSceneAnalysis* analysis) const
{
  // Measured against the path-traced reference (vtkEffectPlan.h): from g = 0.6 on, D3Q6's image
  // error grows to 1.5x and more of D3Q18's, 5x at 0.8.
  return this->LatticeDirections == AUTOMATIC_LATTICE &&
    analysis->GetMeanAnisotropy() >= D3Q18Anisotropy;
}

//------------------------------------------------------------------------------
std::string vtkEffectPlan::DecideLattice(vtkSceneAnalysis* analysis)
{
  std::ostringstream why;
  const double g = analysis->GetMeanAnisotropy();
  if (this->LatticeDirections != AUTOMATIC_LATTICE)
  {
    this->ChosenLattice = this->LatticeDirections;
    why << "D3Q" << this->ChosenLattice << " forced";
  }
  else if (this->CallsForD3Q18(analysis) && !this->D3Q18FitsInMemory)
  {
    this->ChosenLattice = 6;
    why << "D3Q6: the medium's mean |g| " << g << " >= " << D3Q18Anisotropy
        << " calls for D3Q18, but its lattice (3x D3Q6's memory) does not fit the device";
  }
  else if (this->CallsForD3Q18(analysis))
  {
    this->ChosenLattice = 18;
    why << "D3Q18: the medium's mean |g| " << g << " >= " << D3Q18Anisotropy
        << ", where D3Q6's six directions would pull the multiply scattered light's direction "
           "onto the grid's axes";
  }
  else
  {
    this->ChosenLattice = 6;
    why << "D3Q6: the medium's mean |g| " << g << " < " << D3Q18Anisotropy
        << ", where D3Q18 (about 4x the time) is hardly closer to the reference";
  }
  return why.str();
}

//------------------------------------------------------------------------------
void vtkEffectPlan::DecideMultipleScatteringMethod(vtkSceneAnalysis* analysis)
{
  std::ostringstream why;
  this->ChosenOrders = 0;
  this->ChosenLattice = this->LatticeDirections == 18 ? 18 : 6;
  if (!this->Enabled[MULTIPLE_SCATTERING])
  {
    this->ChosenMultipleMethod = LATTICE_ONLY;
    this->MultipleReason = "multiple scattering off";
    return;
  }
  const bool litSurfaces = this->Enabled[SURFACE_LIGHTING] && analysis->GetNumberOfSurfaces() > 0;
  if (litSurfaces)
  {
    // Whatever was asked: the lattice would never light a surface (Physics.md, "Surfaces and
    // multiple scattering").
    this->ChosenMultipleMethod = PHOTONS_EVERY_ORDER;
    this->ChosenOrders = -1;
    why << "lit surfaces: the lattice knows none, the photons carry every order";
    // Say so when that overrides a request (as the single-scattering method's reason does).
    if (this->MultipleScatteringMethod != AUTOMATIC_MULTIPLE_METHOD &&
      this->MultipleScatteringMethod != PHOTONS_EVERY_ORDER)
    {
      why << " (" << GetMultipleScatteringMethodName(this->MultipleScatteringMethod)
          << " forced, but it would leave the surfaces unlit)";
    }
    else if (this->ScatteringOrders > 0)
    {
      why << " (k = " << this->ScatteringOrders
          << " forced, but the lattice would leave the surfaces unlit)";
    }
    this->MultipleReason = why.str();
    return;
  }
  const int method = this->MultipleScatteringMethod;
  if (method == PHOTONS_EVERY_ORDER)
  {
    this->ChosenMultipleMethod = method;
    this->ChosenOrders = -1;
    this->MultipleReason = "forced";
    return;
  }
  const std::string lattice = this->DecideLattice(analysis);
  if (method == LATTICE_ONLY)
  {
    this->ChosenMultipleMethod = method;
    why << "forced (ray-effect anisotropy up to " << GetRayEffectAnisotropy(this->ChosenLattice, 0)
        << " around point lights); " << lattice;
    this->MultipleReason = why.str();
    return;
  }
  const bool lightInside = analysis->GetNumberOfLightsInsideMedium() > 0;
  // Refraction that moves light by a voxel or more can gather it into a voxel-sized focus.
  const bool focusing =
    this->Enabled[REFRACTION] && analysis->GetMaximumDisplacementInVoxels() >= 1.0;
  if (method == AUTOMATIC_MULTIPLE_METHOD && !lightInside && !focusing)
  {
    // Lights outside a medium that does not bend light put S1 on its lit side, spread over an
    // area: measured, the lattice alone is as close to the reference as any split
    // (BenchmarkAccuracyTime: cloud 0.95%, dense cube 5.1% against 6.6-13% with photons carrying
    // orders) and cheaper.
    this->ChosenMultipleMethod = LATTICE_ONLY;
    this->MultipleReason = "no light inside the medium and no refraction that could focus its "
                           "light, so no concentrated source to draw ray effects; " +
      lattice;
    return;
  }
  this->ChosenMultipleMethod = FIRST_COLLISION_SPLIT;
  if (this->ScatteringOrders > 0)
  {
    this->ChosenOrders = this->ScatteringOrders;
    why << "k = " << this->ScatteringOrders << " forced";
  }
  else
  {
    int k = 1;
    while (
      k < MaximumChosenOrders && GetRayEffectAnisotropy(this->ChosenLattice, k) > this->Tolerance)
    {
      ++k;
    }
    this->ChosenOrders = k;
    // Refraction focuses light inside the medium (a GRIN lens's focus, a caustic): a concentrated
    // S1 like a lamp's. Measured against the photon-mapped truth at 64^3 (Benchmarks.md, "Ground
    // truth for refracted light"): the GRIN lens's lattice alone is 6.2% off (3.4% dark), the
    // split 1.4%; the glass sphere in fog 2.4% and 3.1%.
    if (method == FIRST_COLLISION_SPLIT)
    {
      why << "forced";
    }
    else if (lightInside)
    {
      why << "a light inside the medium";
    }
    else
    {
      why << "refraction can focus the light into a concentrated source ("
          << analysis->GetMaximumDisplacementInVoxels() << " voxels of displacement)";
    }
    why << ", k = " << k << ": the smallest k whose measured ray-effect anisotropy with D3Q"
        << this->ChosenLattice << " (" << GetRayEffectAnisotropy(this->ChosenLattice, k)
        << ") is within the tolerance " << this->Tolerance
        << (k == MaximumChosenOrders ? " or the largest the plan chooses" : "");
  }
  why << "; " << lattice;
  this->MultipleReason = why.str();
}
