// The volume-caustic stage of vtkPhotonTracer (VolumeCausticSubdivision): a pilot march places
// bricks of c^3 fine voxels where light focused by dielectric interfaces crosses voxels densely;
// the march then deposits that light's S1 into the bricks (photon_deposit_volume_caustic in
// photon_trace.cl), and the fine deposits are resolved into field-data arrays
// (vtkRefractaLightingVolume::VolumeCaustic*Name()). Documentation/Physics.md "Volume caustics".
#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkRefractaLightingVolume.h"

#include "photon_tallies.cl" // the sizes of the tallies and counters the pilot clears

#include <algorithm>
#include <numeric>

using namespace vtkPhotonTracerDetail;

namespace
{
// Fixed-point accumulators per fine voxel: S1 (3), direction sums (3), two of padding (64 bytes;
// PHOTON_FINE_LONGS in photon_trace.cl).
constexpr size_t FineLongs = 8;
// The pilot marches the first 1/PilotShare of every light's photons (whole work-groups).
constexpr size_t PilotShare = 8;

size_t Cube(int c)
{
  return static_cast<size_t>(c) * c * c;
}

// The bricks from the pilot's caustic pieces per voxel (times perPilotPiece, the photons per pilot
// photon): the largest c <= maxC for which the voxels expecting at least k c^3 pieces, c^3 fine
// voxels each, fit in `budget` fine voxels. Fills `bricks` (per voxel: its brick, numbered in
// voxel order, or -1) and returns c, or 1 (every entry -1) when none fits.
int ChooseBricks(const std::vector<cl_uint>& pieces, double perPilotPiece, double k, int maxC,
  vtkIdType budget, std::vector<int>& bricks)
{
  auto qualifies = [&](size_t v, int c)
  {
    const double expected = double(pieces[v]) * perPilotPiece;
    return expected > 0.0 && expected >= k * double(Cube(c));
  };
  bricks.assign(pieces.size(), -1);
  for (int c = maxC; c >= 2; --c)
  {
    size_t count = 0;
    for (size_t v = 0; v < pieces.size(); ++v)
    {
      count += qualifies(v, c) ? 1 : 0;
    }
    if (count > 0 && double(count) * double(Cube(c)) <= double(budget))
    {
      int next = 0;
      for (size_t v = 0; v < pieces.size(); ++v)
      {
        bricks[v] = qualifies(v, c) ? next++ : -1;
      }
      return c;
    }
  }
  return 1;
}
}

//------------------------------------------------------------------------------
size_t vtkPhotonTracerDetail::VolumeCausticPilot(size_t photons)
{
  const size_t block = PilotShare * PhotonWorkGroup;
  return std::min(photons, (photons + block - 1) / block * PhotonWorkGroup);
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::UsesVolumeCaustic(Internals& run)
{
  // A chunked march hands the accumulators to its callback (the interleaved lattice) while
  // photons are still in flight, before any brick could be read back into its voxel.
  const bool interfaces = run.Surfaces && run.Surfaces->GetNumberOfDielectricTriangles() > 0;
  run.VolumeCaustic = this->VolumeCausticSubdivision > 1 && interfaces && run.M.Scatters &&
    this->StepsPerChunk == 0;
  run.VolumeCausticSub = 1;
  run.NumberOfBricks = 0;
  this->LastVolumeCausticSubdivision = 1;
  this->LastNumberOfVolumeCausticBricks = 0;
  return run.VolumeCaustic;
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::SetVolumeCausticArguments(
  Internals& run, cl_kernel kernel, cl_uint first, int subdivision)
{
  if (!run.BrickBuffer)
  {
    // The kernels take these arguments in every run: 16-byte buffers they never read (0).
    run.BrickBuffer = run.Alloc.Make(CL_MEM_READ_ONLY, 16, nullptr, "volume caustic bricks (none)");
    run.FineFixed =
      run.Alloc.Make(CL_MEM_READ_WRITE, 16, nullptr, "volume caustic accumulators (none)");
    if (!run.BrickBuffer || !run.FineFixed)
    {
      return false;
    }
  }
  const cl_mem bricks = run.BrickBuffer.Get(), fine = run.FineFixed.Get();
  const cl_int sub = subdivision;
  return run.Context->Check(vtkOpenCLSetKernelArgsFrom(kernel, first, bricks, fine, sub),
    "clSetKernelArg(volume caustic)", this);
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::PlaceVolumeCausticBricks(
  Internals& run, const std::function<bool(size_t, size_t)>& march, cl_kernel kernel, cl_uint first)
{
  if (!run.VolumeCaustic)
  {
    return this->SetVolumeCausticArguments(run, kernel, first, 0);
  }
  vtkOpenCLContext* ctx = run.Context;
  Allocator& alloc = run.Alloc;
  const size_t voxels = run.M.Voxels;
  // The pilot: every voxel is its own brick at c = 1, where the kernel only counts the caustic
  // pieces per voxel (one cl_uint each).
  std::vector<int> identity(voxels);
  std::iota(identity.begin(), identity.end(), 0);
  run.BrickBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, voxels * sizeof(int),
    identity.data(), "volume caustic pilot bricks");
  const size_t pilotBytes = voxels * sizeof(cl_uint);
  run.FineFixed =
    alloc.Make(CL_MEM_READ_WRITE, pilotBytes, nullptr, "volume caustic pilot accumulators");
  if (!run.BrickBuffer || !run.FineFixed ||
    !ctx->ZeroBuffer(run.FineFixed.Get(), pilotBytes, this) ||
    !this->SetVolumeCausticArguments(run, kernel, first, 1))
  {
    return false;
  }
  size_t offset = 0, marched = 0;
  for (const LightSetup& ls : run.Lights)
  {
    const size_t n = ls.Photons;
    const size_t pilot = VolumeCausticPilot(n);
    if (pilot > 0 && !march(offset, pilot))
    {
      return false;
    }
    offset += n;
    marched += pilot;
  }
  std::vector<cl_uint> pieces(voxels);
  if (!ctx->Finish(this) ||
    !ctx->ReadBuffer(run.FineFixed.Get(), pilotBytes, pieces.data(), this))
  {
    return false;
  }
  const double perPilotPiece = marched > 0 ? double(run.Photons) / double(marched) : 0.0;
  const int chosen = ChooseBricks(pieces, perPilotPiece, this->VolumeCausticPiecesPerFineVoxel,
    this->VolumeCausticSubdivision, this->MaximumNumberOfVolumeCausticVoxels, run.Bricks);
  const size_t bricks =
    chosen > 1 ? static_cast<size_t>(*std::max_element(run.Bricks.begin(), run.Bricks.end()) + 1) : 0;
  run.VolumeCausticSub = chosen;
  run.NumberOfBricks = static_cast<vtkIdType>(bricks);
  // The main march starts from clean accumulators: the pilot's deposits, books and counts go.
  const size_t fineBytes = std::max<size_t>(bricks * Cube(chosen) * FineLongs * sizeof(cl_long), 16);
  run.BrickBuffer = alloc.Make(CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, voxels * sizeof(int),
    run.Bricks.data(), "volume caustic bricks");
  run.FineFixed = alloc.Make(CL_MEM_READ_WRITE, fineBytes, nullptr, "volume caustic accumulators");
  const size_t accumulatorBytes = voxels * 6 * run.DepositBlocks() * sizeof(cl_long); // Deposits
  return run.BrickBuffer && run.FineFixed &&
    ctx->ZeroBuffer(run.FineFixed.Get(), fineBytes, this) &&
    ctx->ZeroBuffer(run.Deposits.Get(), accumulatorBytes, this) &&
    ctx->ZeroBuffer(run.Tallies.Get(), PHOTON_TALLY_COUNT * sizeof(cl_long), this) &&
    ctx->ZeroBuffer(run.Counters.Get(), PHOTON_COUNTER_COUNT * sizeof(cl_long), this) &&
    (run.MultipleBytes == 0 || ctx->ZeroBuffer(run.MultipleFixed.Get(), run.MultipleBytes, this)) &&
    (run.SurfIrradianceBytes == 0 ||
      ctx->ZeroBuffer(run.SurfIrradiance.Get(), run.SurfIrradianceBytes, this)) &&
    this->SetVolumeCausticArguments(run, kernel, first, chosen > 1 ? chosen : 0);
}

//------------------------------------------------------------------------------
bool vtkPhotonTracer::ResolveVolumeCaustic(Internals& run)
{
  const int c = run.VolumeCausticSub;
  if (c < 2)
  {
    return true;
  }
  const size_t fine = static_cast<size_t>(run.NumberOfBricks) * Cube(c);
  std::vector<cl_long> fixed(fine * FineLongs);
  if (!run.Context->ReadBuffer(
        run.FineFixed.Get(), fixed.size() * sizeof(cl_long), fixed.data(), this))
  {
    return false;
  }
  // Deposits become power per unit volume of a fine voxel (1 / c^3 of a voxel's).
  const double* h = run.M.Spacing;
  const double valueFactor = double(Cube(c)) / (run.Scale * h[0] * h[1] * h[2]);
  vtkFloatArray* radiance = run.FineRadiance;
  vtkFloatArray* direction = run.FineDirection;
  radiance->SetName(vtkRefractaLightingVolume::VolumeCausticRadianceName());
  direction->SetName(vtkRefractaLightingVolume::VolumeCausticRadianceDirectionName());
  for (vtkFloatArray* a : { radiance, direction })
  {
    a->SetNumberOfComponents(3);
    a->SetNumberOfTuples(static_cast<vtkIdType>(fine));
  }
  float* r = radiance->GetPointer(0);
  float* d = direction->GetPointer(0);
  for (size_t i = 0; i < fine; ++i)
  {
    const cl_long* acc = fixed.data() + FineLongs * i;
    double sum[3];
    double length = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      r[3 * i + k] = static_cast<float>(std::max(0.0, double(acc[k]) * valueFactor));
      sum[k] = double(acc[3 + k]);
      length += sum[k] * sum[k];
    }
    length = std::sqrt(length);
    for (int k = 0; k < 3; ++k)
    {
      d[3 * i + k] = length > 0.0 ? static_cast<float>(sum[k] / length) : 0.0f;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::WriteVolumeCausticOutput(Internals& run, vtkImageData* output)
{
  this->LastVolumeCausticSubdivision = run.VolumeCausticSub;
  this->LastNumberOfVolumeCausticBricks = run.NumberOfBricks;
  if (run.VolumeCausticSub < 2)
  {
    return;
  }
  vtkNew<vtkIntArray> bricks;
  bricks->SetName(vtkRefractaLightingVolume::VolumeCausticBricksName());
  bricks->SetNumberOfTuples(static_cast<vtkIdType>(run.Bricks.size()));
  std::copy(run.Bricks.begin(), run.Bricks.end(), bricks->GetPointer(0));
  vtkFieldData* fd = output->GetFieldData();
  fd->AddArray(bricks);
  fd->AddArray(run.FineRadiance);
  fd->AddArray(run.FineDirection);
}

//------------------------------------------------------------------------------
void vtkPhotonTracer::PrintVolumeCaustic(ostream& os, vtkIndent indent)
{
  os << indent << "VolumeCausticSubdivision: " << this->VolumeCausticSubdivision << "\n";
  os << indent << "MaximumNumberOfVolumeCausticVoxels: "
     << this->MaximumNumberOfVolumeCausticVoxels << "\n";
  os << indent << "VolumeCausticPiecesPerFineVoxel: " << this->VolumeCausticPiecesPerFineVoxel
     << "\n";
  os << indent << "LastVolumeCausticSubdivision: " << this->LastVolumeCausticSubdivision << " ("
     << this->LastNumberOfVolumeCausticBricks << " bricks)\n";
}
