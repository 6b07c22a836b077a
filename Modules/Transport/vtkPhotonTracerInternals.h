// Private to vtkPhotonTracer (not installed): the helpers and the per-run state that
// vtkPhotonTracer.cxx (the device stages) and vtkPhotonTracerSetup.cxx (medium, lights, octree)
// share.
#ifndef vtkPhotonTracerInternals_h
#define vtkPhotonTracerInternals_h

#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSmartPointer.h"
#include "vtkWeakPointer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

class vtkImageData;
class vtkLight;
class vtkRefractaGridCuts;
class vtkRefractaGridFrame;
class vtkRefractaSurfaceSet;

namespace vtkPhotonTracerDetail
{
using Clock = std::chrono::steady_clock;
inline double Seconds(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline cl_int4 Int4(const int d[3])
{
  cl_int4 v;
  v.s[0] = d[0];
  v.s[1] = d[1];
  v.s[2] = d[2];
  v.s[3] = 0;
  return v;
}

inline cl_float4 Float4(double x, double y, double z, double w = 0.0)
{
  cl_float4 v;
  v.s[0] = static_cast<float>(x);
  v.s[1] = static_cast<float>(y);
  v.s[2] = static_cast<float>(z);
  v.s[3] = static_cast<float>(w);
  return v;
}

inline cl_float4 Float4(const double a[3], double w = 0.0)
{
  return Float4(a[0], a[1], a[2], w);
}

inline uint32_t SplitMix(uint64_t& state)
{
  uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return static_cast<uint32_t>((z ^ (z >> 31)) >> 32);
}

// Fixed-point S_ms accumulators per voxel (photon_trace.cl): S_ms and its direction sums
// interleaved, six per voxel (one cache line a deposit); with the first-collision split then the
// lattice's source (3 per voxel) and its direction sums (3 per voxel), each a block of its own
// (photon_hand_to_lattice).
inline size_t MultipleAccumulatorsPerVoxel(int splitOrders)
{
  return splitOrders > 0 ? 12 : 6;
}

inline double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline bool Normalize(double a[3])
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
inline void Basis(const double a[3], double b1[3], double b2[3])
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
  std::vector<float> Anisotropy; // g per voxel (analog scattering only)
  bool HasGradient = false;
  bool Curved = false;
  bool Attenuates = false;
  bool Scatters = false;
  // sigma_t bends steeply at some node (SteepExtinctionKinks): the walk cuts voxels at node planes.
  bool NodeCuts = false;
  // Values per voxel of the device's extinction and albedo: 1 where every voxel's three channels
  // are equal (a grey medium: the march gathers a third as much), else 3 (DeviceChannels).
  int ExtinctionChannels = 3;
  int AlbedoChannels = 3;
  double Lo[3], Hi[3];           // domain box, grid-local
  double ProxyLo[3], ProxyHi[3]; // photon start box, grid-local
};
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
  // Positional: how far along their rays the photons start (short of the box's bounding sphere;
  // Origin is then the light's position + Lead Axis).
  double Lead = 0.0;
  unsigned int Photons = 0;
  bool Environment = false; // the environment light (vtkPhotonTracer::Internals::Env*)
};

// The environment light of one run: radiance per texel (RGB and luminance), the luminance x solid
// angle CDFs (marginal over rows, conditional within each row), its basis and emission sphere in
// the grid-local frame, and the power factor pi R^2 S (S = sum of luminance x solid angle).
struct EnvironmentSetup
{
  int Size[2] = { 0, 0 };
  std::vector<cl_float4> Texels;
  std::vector<float> Marginal, Conditional;
  double Right[3], Up[3], Front[3];
  double Centre[3], Radius = 0;
  double PowerFactor = 0;
};

// The scratch buffers (created without data: accumulators, photon state, the resolve's and the
// smoothing's work arrays) of the last run, kept for the next (vtkPhotonTracer::
// ReuseScratchBuffers). A run borrows a kept buffer of the same name, flags and size that it has
// not borrowed yet, else creates one and keeps it; EndRun() drops what the run did not borrow, so
// the pool holds one run's scratch at most. Why: on a CPU device a fresh buffer's first fill
// faults every page in (a 128^3 light move filled 240 MiB of fresh buffers in 0.83 s).
struct ScratchPool
{
  struct Entry
  {
    std::string What;
    cl_mem_flags Flags;
    size_t Bytes;
    vtkOpenCLBuffer Buffer;
    bool Borrowed;
  };
  vtkOpenCLContext* Context = nullptr;
  std::vector<Entry> Entries;

  // A second reference to the kept buffer (the run's is released with the run, the pool's kept).
  vtkOpenCLBuffer Borrow(
    vtkOpenCLContext* ctx, cl_mem_flags flags, size_t bytes, const char* what, vtkObject* reporter);
  void EndRun();
};

// Device buffers with bookkeeping of the bytes allocated; scratch buffers come from `Pool` where
// there is one.
struct Allocator
{
  vtkOpenCLContext* Context;
  vtkObject* Reporter;
  ScratchPool* Pool = nullptr;
  double Bytes = 0;
  // `kept`: the buffer outlives the run (a device copy of an output array), so it is never a
  // borrowed scratch buffer, which the next run would overwrite.
  vtkOpenCLBuffer Make(
    cl_mem_flags flags, size_t bytes, const void* data, const char* what, bool kept = false)
  {
    // CreateBuffer rounds the device allocation up to 16 bytes; `data` holds exactly `bytes`.
    this->Bytes += static_cast<double>((std::max<size_t>(bytes, 1) + 15) / 16 * 16);
    if (this->Pool && !data && !kept)
    {
      return this->Pool->Borrow(this->Context, flags, bytes, what, this->Reporter);
    }
    return this->Context->CreateBuffer(flags, bytes, data, what, this->Reporter);
  }
};

// Work-items per work-group of the photon kernels (Run1D).
constexpr uint32_t PhotonWorkGroup = 64;

// The order in which a light's `count` photons are marched: slot w takes point order[w] of the
// generation's rank-1 lattice (photon_generate.cl: point i is (xi1, xi2) = the top bits of
// r1 + (i + 1) a1 and r2 + (i + 1) a2). Slots below `first` keep points 0 .. first - 1 (the volume
// caustic's pilot marches them: a low-discrepancy sample of the whole footprint); the others are
// sorted by the Morton code of their cell in a 2^b x 2^b grid over (xi1, xi2) with about four
// points per cell (counting sort, O(count)), in work-groups dealt out with a golden-ratio stride.
// Neighbouring slots then start close together (on the light's footprint or in its cone), follow
// nearby paths and find the voxels the photon before them touched still in the cache; which points
// are traced, and each one's random stream, do not change (the deposits are the same to the bit).
void CoherentLatticeOrder(
  uint32_t count, uint32_t first, uint32_t r1, uint32_t r2, uint32_t* order);

// How many of a light's `photons` the volume caustic's pilot marches (its first slots).
size_t VolumeCausticPilot(size_t photons);

// Every photon slot's random stream, offset + i for lattice point i of the light whose photons
// start at `offset` (photon_generate.cl, photon_march.cl): each light's points in coherent order
// (CoherentLatticeOrder; with `pilot`, the volume caustic's pilot slots in lattice order), the
// sky's in lattice order. Kept for the next run with the same photon counts, rotations and kinds
// of light (a light move does not sort again: 20 ms at 2^20).
struct PhotonStreams
{
  std::vector<uint64_t> Key;
  std::vector<uint32_t> Streams;
  const std::vector<uint32_t>& Update(size_t photons, const std::vector<LightSetup>& lights,
    const std::vector<std::array<uint32_t, 2>>& rotations, bool coherent, bool pilot);
};

// Reads the medium's arrays (defaults for missing ones), the plan facts and the proxy box.
void LoadMedium(vtkImageData* image, bool useProxy, Medium& m);

// Whether some voxel of `m` scatters (sigma_t albedo > 0 in a channel) with anisotropy g != 0:
// only then does the direction of the light matter to the view pass's phase function.
bool ScattersAnisotropically(const Medium& m);

// S1's lobes (vtkRefractaLightingVolume::RadianceLobeName): the lobe of each light, given each
// light's unit travel direction at the medium and its strength there, into `lobes` groups. One
// light per lobe while there are no more lights than lobes; else the strongest light seeds lobe 0,
// each further seed is the light farthest in angle from every seed (the lowest largest cosine),
// and every light joins the seed nearest in angle (ties: the first).
std::vector<int> GroupLightsByDirection(
  const std::vector<std::array<double, 3>>& travel, const std::vector<double>& strength, int lobes);
// `rgb` (3 values per voxel) as the device takes it: itself with 3 channels, its first channel
// (copied into `grey`) with 1.
const std::vector<float>& DeviceChannels(
  const std::vector<float>& rgb, int channels, std::vector<float>& grey);
// Whether the glass bodies of `set` (dielectric surfaces with an inside medium; nullptr: none)
// attenuate (sigma_t > 0) and scatter (sigma_t albedo > 0): the kernel variant must include them
// even where the grid does neither (vtkPhotonTracerSurfaces.cxx).
void BodyMedia(vtkRefractaSurfaceSet* set, bool& attenuates, bool& scatters);

// A vtkLight in the grid-local frame as every light pass reads it (the one conversion):
// colour x intensity, position, the unit axis from position to focal point (directional and spot
// lights; 0 for point lights), whether it is positional and a spot (positional, cone < 90).
struct LocalLight
{
  bool Positional = false;
  bool Spot = false;
  double Position[3] = { 0, 0, 0 };
  double Axis[3] = { 0, 0, 0 };
  double Colour[3] = { 0, 0, 0 };
};

// Reads `light` (number `index` of its collection) through `grid` (vtkPhotonTracer.cxx's light
// conventions, Documentation/Physics.md "Lights"); false with `error` for an invalid light
// (vtkMediumValidator::CheckLight; a directional or spot light whose position equals its focal
// point; a spot cone outside (0, 90) degrees).
bool ReadLocalLight(
  vtkLight* light, int index, vtkRefractaGridFrame* grid, LocalLight& out, std::string& error);

bool Run1D(vtkOpenCLContext* ctx, cl_kernel kernel, size_t count, const char* label, vtkObject* r);

// Builds the octree level array of `nBuffer` into `octree` (one byte per voxel).
bool RunOctree(vtkOpenCLContext* ctx, vtkObject* reporter, Allocator& alloc, cl_mem nBuffer,
  const int dims[3], double eps, double eps2, vtkOpenCLBuffer& octree);
}

//------------------------------------------------------------------------------
// The state one run of RequestData passes from stage to stage.
struct vtkPhotonTracer::Internals
{
  vtkImageData* Input = nullptr;
  vtkPhotonTracerDetail::Medium M;
  std::vector<vtkPhotonTracerDetail::LightSetup> Lights;
  // Lights aim at this box (grid-local): the proxy box, grown by the surfaces' bounds.
  double EmitLo[3] = { 0, 0, 0 }, EmitHi[3] = { 0, 0, 0 };
  // Surfaces (nullptr when none): the built set, its device arrays, the irradiance accumulator,
  // the rows of the grid-local -> surface-frame map, the offset of reflected photons.
  vtkRefractaSurfaceSet* Surfaces = nullptr;
  vtkOpenCLBuffer SurfNodes, SurfTriangles, SurfInfo, SurfAlbedo, SurfIrradiance;
  vtkOpenCLBuffer SurfNormals, SurfInterfaces; // dielectric corner normals and index pairs
  vtkOpenCLBuffer SurfBodies;                  // the glass bodies' inside media
  cl_float4 Frame[3];
  double SurfaceEpsilon = 0;
  // Where opaque surfaces cut the grid (vtkRefractaGridCuts; nullptr: nowhere this run) and its
  // links and near-surface bits on the device, uploaded once per run for the march's sided
  // deposits (REFRACTA_SIDED_DEPOSITS) and the smoothing (vtkPhotonTracerOutput.cxx, SmoothAxes).
  vtkRefractaGridCuts* Cuts = nullptr;
  vtkOpenCLBuffer CutLinksBuffer;
  // Its owned volumes (GetScaledVoxels, GetVolumeScales), applied to the resolved deposits.
  vtkOpenCLBuffer ScaledVoxels, VolumeScales;
  cl_uint NumberOfScaledVoxels = 0;
  vtkNew<vtkFloatArray> Irradiance;
  // Caustic atlas (vtkPhotonTracer::CausticSubdivision): c of this run, 1 when off (no
  // dielectric surfaces); its accumulators follow the coarse ones in SurfIrradiance.
  int Caustic = 1;
  vtkNew<vtkFloatArray> CausticIrradiance;
  vtkNew<vtkIdTypeArray> CausticPhotons; // caustic photons per atlas texel
  // Analog scattering (vtkPhotonTracer::AnalogScattering, ScatteringOrders): whether this run
  // uses it, the split order k (0: every order), g per voxel on the device, the accumulators
  // (fixed point: S_ms, 3 per voxel; then, every order by photons, S_ms's direction sums, 3 per
  // voxel; with the split instead the lattice's source and its direction sums, 3 + 3 per voxel)
  // and the resolved arrays.
  bool Analog = false;
  int SplitOrders = 0;
  vtkOpenCLBuffer AnisotropyBuffer, MultipleFixed;
  vtkNew<vtkFloatArray> Multiple;
  vtkNew<vtkFloatArray> MultipleDirection; // F / phi_ms (every order by photons)
  vtkNew<vtkFloatArray> LatticeSource;
  vtkNew<vtkFloatArray> LatticeSourceDirection;
  // Volume caustic (vtkPhotonTracer::VolumeCausticSubdivision): whether the kernels have it, c of
  // this run's bricks (1: none placed), each voxel's brick (-1: none), the device's brick map and
  // fine accumulators (PHOTON_FINE_LONGS per fine voxel), the resolved fine S1 and directions;
  // the byte sizes of the accumulators the pilot march dirtied and the run clears again.
  bool VolumeCaustic = false;
  int VolumeCausticSub = 1;
  std::vector<int> Bricks;
  vtkIdType NumberOfBricks = 0;
  vtkOpenCLBuffer BrickBuffer, FineFixed;
  vtkNew<vtkFloatArray> FineRadiance, FineDirection;
  size_t MultipleBytes = 0, SurfIrradianceBytes = 0;
  vtkPhotonTracerDetail::EnvironmentSetup Env;
  double TotalBound = 0; // sum of the lights' power bounds towards the box
  size_t Photons = 0;
  vtkOpenCLContext* Context = nullptr;
  vtkPhotonTracerDetail::Allocator Alloc{ nullptr, nullptr };
  double Unit = 1.0;  // the device's unit of power (TotalBound)
  double Scale = 1.0; // fixed-point scale of the tallies, in host units
  cl_program Trace = nullptr;
  vtkOpenCLBuffer NBuffer, GradBuffer, Octree;
  vtkOpenCLBuffer Pos, Dirs, Power;
  vtkOpenCLBuffer Streams; // per slot: the photon's random stream (and lattice point + offset)
  // Deposits: six cl_long per voxel (the Radiance accumulator's RGB, then the direction sums).
  vtkOpenCLBuffer ExtBuffer, AlbBuffer, Deposits, Tallies, Counters;
  std::vector<cl_long> Tally, Count;
  vtkNew<vtkFloatArray> Radiance;
  vtkNew<vtkFloatArray> Direction;
  // S1's lobes (vtkPhotonTracer::MaximumRadianceLobes): 1 (none), or K >= 2 with each light's
  // lobe (index as in Lights), `Deposits` then K more blocks of six per voxel after the first,
  // and each lobe's resolved S1 and direction.
  int Lobes = 1;
  std::vector<int> LightLobes;
  std::vector<vtkSmartPointer<vtkFloatArray>> LobeRadiance, LobeDirection;
  // The blocks of six accumulators per voxel in `Deposits`: all of S1, then each lobe's.
  size_t DepositBlocks() const { return this->Lobes > 1 ? this->Lobes + 1 : 1; }
  double Progress = 0.0;     // last value reported, so that progress never goes back
  bool Aborted = false;      // the run stopped because AbortExecute was set
  bool ReusedMedium = false; // M and the medium's buffers came from the MediumCache
};

//------------------------------------------------------------------------------
// The medium a successful run leaves for the next one, and what it was made from.
struct vtkPhotonTracer::MediumCache
{
  vtkImageData* Input = nullptr;
  vtkMTimeType InputTime = 0;
  vtkOpenCLContext* Context = nullptr;
  double PrimaryTolerance = 0, SecondaryTolerance = 0;
  bool AdaptiveStepping = false, UseProxyBounds = false;
  vtkPhotonTracerDetail::Medium M;
  vtkOpenCLBuffer NBuffer, GradBuffer, Octree, ExtBuffer, AlbBuffer;
  double Bytes = 0; // device bytes of those buffers
};

//------------------------------------------------------------------------------
// The surfaces' device arrays a successful run leaves for the next one, and what they were made
// from (the set, its build count, the context).
struct vtkPhotonTracer::SurfaceCache
{
  vtkWeakPointer<vtkRefractaSurfaceSet> Set;
  int Builds = -1;
  vtkOpenCLContext* Context = nullptr;
  vtkOpenCLBuffer Nodes, Triangles, Info, Albedo, Normals, Interfaces, Bodies;
  double Bytes = 0;
};

#endif
