// The host-side set-up stages of vtkPhotonTracer: reading the medium, sharing out the photons, the
// memory plan, the octree (BuildOctree and its stage), and the medium kept between runs.
#include "vtkPhotonTracer.h"
#include "vtkPhotonTracerInternals.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkOpenCLMemoryPlan.h"
#include "vtkPointData.h"
#include "vtkRefractaMedium.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <sstream>
#include <string>

namespace vtkPhotonTracerDetail
{
namespace
{
void CopyArray(
  vtkDataArray* array, int comps, float fallback, size_t voxels, std::vector<float>& out)
{
  vtkRefractaMedium::ReadArray(array, static_cast<vtkIdType>(voxels), comps, fallback, out);
}
}

vtkOpenCLBuffer ScratchPool::Borrow(
  vtkOpenCLContext* ctx, cl_mem_flags flags, size_t bytes, const char* what, vtkObject* reporter)
{
  if (ctx != this->Context)
  {
    this->Entries.clear(); // another context's buffers are of no use here
    this->Context = ctx;
  }
  const std::string name = what ? what : "";
  auto kept = std::find_if(this->Entries.begin(), this->Entries.end(),
    [&](const Entry& e)
    { return !e.Borrowed && e.Flags == flags && e.Bytes == bytes && e.What == name; });
  if (kept == this->Entries.end())
  {
    vtkOpenCLBuffer created = ctx->CreateBuffer(flags, bytes, nullptr, what, reporter);
    if (!created)
    {
      return created;
    }
    this->Entries.push_back({ name, flags, bytes, std::move(created), false });
    kept = this->Entries.end() - 1;
  }
  kept->Borrowed = true;
  clRetainMemObject(kept->Buffer.Get());
  return vtkOpenCLBuffer(kept->Buffer.Get());
}

void ScratchPool::EndRun()
{
  this->Entries.erase(std::remove_if(this->Entries.begin(), this->Entries.end(),
                        [](const Entry& e) { return !e.Borrowed; }),
    this->Entries.end());
  for (Entry& e : this->Entries)
  {
    e.Borrowed = false;
  }
}

namespace
{
// Spreads the low 16 bits of v to the even bits.
uint32_t SpreadBits(uint32_t v)
{
  v &= 0xffffu;
  v = (v | (v << 8)) & 0x00ff00ffu;
  v = (v | (v << 4)) & 0x0f0f0f0fu;
  v = (v | (v << 2)) & 0x33333333u;
  v = (v | (v << 1)) & 0x55555555u;
  return v;
}
}

void CoherentLatticeOrder(uint32_t count, uint32_t first, uint32_t r1, uint32_t r2, uint32_t* order)
{
  // photon_generate.cl's R2 generators (PHOTON_R2_A1, PHOTON_R2_A2).
  constexpr uint32_t a1 = 3242174889u, a2 = 2447445413u;
  first = std::min(first, count);
  std::iota(order, order + first, 0u);
  const uint32_t sorted = count - first;
  int bits = 1;
  while (bits < 10 && (uint64_t(1) << (2 * (bits + 1))) <= sorted / 4)
  {
    ++bits;
  }
  const uint32_t shift = 32 - bits;
  std::vector<uint32_t> code(sorted);
  std::vector<uint32_t> start((size_t(1) << (2 * bits)) + 1, 0);
  for (uint32_t k = 0; k < sorted; ++k)
  {
    const uint32_t i = first + k;
    const uint32_t x = (r1 + (i + 1u) * a1) >> shift;
    const uint32_t y = (r2 + (i + 1u) * a2) >> shift;
    code[k] = SpreadBits(x) | (SpreadBits(y) << 1);
    ++start[code[k] + 1];
  }
  for (size_t c = 1; c < start.size(); ++c)
  {
    start[c] += start[c - 1];
  }
  for (uint32_t k = 0; k < sorted; ++k)
  {
    order[first + start[code[k]]++] = first + k; // stable: equal cells keep the lattice's order
  }
  // Whole work-groups dealt out with a golden-ratio stride: a group's photons stay together, but
  // the costly regions (through the glass, into dense fog) are spread over the launch instead of
  // queueing at its end with one core left idle (0.84-0.91x at 2^12 photons on a 32^3 grid
  // without it; the same at 2^16 to 2^20 on 128^3).
  const uint32_t groups = sorted / PhotonWorkGroup;
  if (groups > 2)
  {
    uint32_t stride = static_cast<uint32_t>(groups * 0.6180339887) | 1u;
    while (std::gcd(stride, groups) != 1)
    {
      stride += 2;
    }
    const std::vector<uint32_t> sortedOrder(
      order + first, order + first + groups * PhotonWorkGroup);
    for (uint32_t g = 0; g < groups; ++g)
    {
      const uint64_t to = (uint64_t(g) * stride) % groups;
      std::copy_n(sortedOrder.begin() + size_t(g) * PhotonWorkGroup, PhotonWorkGroup,
        order + first + to * PhotonWorkGroup);
    }
  }
}

const std::vector<uint32_t>& PhotonStreams::Update(size_t photons,
  const std::vector<LightSetup>& lights, const std::vector<std::array<uint32_t, 2>>& rotations,
  bool coherent, bool pilot)
{
  std::vector<uint64_t> key = { (coherent ? 1u : 0u) | (pilot ? 2u : 0u), photons };
  for (size_t l = 0; l < lights.size(); ++l)
  {
    key.push_back((uint64_t(lights[l].Photons) << 1) | (lights[l].Environment ? 1u : 0u));
    key.push_back((uint64_t(rotations[l][0]) << 32) | rotations[l][1]);
  }
  if (key == this->Key)
  {
    return this->Streams;
  }
  // Slot w's stream is w where the photons keep the lattice order (the sky's, every light's with
  // `coherent` off, slots no light fills); a light's coherent order overwrites its slots.
  this->Streams.resize(photons);
  std::iota(this->Streams.begin(), this->Streams.end(), 0u);
  size_t offset = 0;
  for (size_t l = 0; l < lights.size() && offset < photons; ++l)
  {
    const uint32_t count =
      static_cast<uint32_t>(std::min<size_t>(lights[l].Photons, photons - offset));
    if (coherent && !lights[l].Environment)
    {
      uint32_t* slots = this->Streams.data() + offset;
      const uint32_t first = pilot ? static_cast<uint32_t>(VolumeCausticPilot(count)) : 0;
      CoherentLatticeOrder(count, first, rotations[l][0], rotations[l][1], slots);
      for (uint32_t w = 0; w < count; ++w)
      {
        slots[w] += static_cast<uint32_t>(offset);
      }
    }
    offset += count;
  }
  this->Key = std::move(key);
  return this->Streams;
}

const std::vector<float>& DeviceChannels(
  const std::vector<float>& rgb, int channels, std::vector<float>& grey)
{
  if (channels == 3)
  {
    return rgb;
  }
  grey.resize(rgb.size() / 3);
  for (size_t v = 0; v < grey.size(); ++v)
  {
    grey[v] = rgb[3 * v];
  }
  return grey;
}

namespace
{
// Whether the trilinear sigma_t bends so steeply at some node that one midpoint sample per voxel
// misplaces light: a piece of a voxel's width centred on node i along an axis misses
// |sigma_(i-1) - 2 sigma_i + sigma_(i+1)| h / 8 of optical depth (the slope's jump there, times
// h^2 / 8). Above NodeCutDepth (0.02) the photon walk cuts voxels at their node planes (a dense
// body's face: 0.07 in the accuracy benchmark's cube; a smooth cloud, a uniform fog, a clear glass
// ball in fog: below).
constexpr double NodeCutDepth = 0.02;

bool SteepExtinctionKinks(const Medium& m)
{
  const size_t strides[3] = { 1, static_cast<size_t>(m.Dims[0]),
    static_cast<size_t>(m.Dims[0]) * m.Dims[1] };
  for (size_t v = 0; v < m.Voxels; ++v)
  {
    const int ijk[3] = { static_cast<int>(v % m.Dims[0]),
      static_cast<int>((v / m.Dims[0]) % m.Dims[1]),
      static_cast<int>(v / (static_cast<size_t>(m.Dims[0]) * m.Dims[1])) };
    for (int a = 0; a < 3; ++a)
    {
      if (ijk[a] == 0 || ijk[a] == m.Dims[a] - 1)
      {
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        const double bend = m.Extinction[3 * (v - strides[a]) + c] - 2.0 * m.Extinction[3 * v + c] +
          m.Extinction[3 * (v + strides[a]) + c];
        if (std::abs(bend) * m.Spacing[a] / 8.0 > NodeCutDepth)
        {
          return true;
        }
      }
    }
  }
  return false;
}
}

bool ScattersAnisotropically(const Medium& m)
{
  for (size_t v = 0; v < m.Voxels && v < m.Anisotropy.size(); ++v)
  {
    if (m.Anisotropy[v] != 0.0f)
    {
      for (int c = 0; c < 3; ++c)
      {
        if (m.Extinction[3 * v + c] > 0.0f && m.Albedo[3 * v + c] > 0.0f)
        {
          return true;
        }
      }
    }
  }
  return false;
}

std::vector<int> GroupLightsByDirection(
  const std::vector<std::array<double, 3>>& travel, const std::vector<double>& strength, int lobes)
{
  const int lights = static_cast<int>(travel.size());
  std::vector<int> lobe(lights, 0);
  if (lights <= lobes)
  {
    std::iota(lobe.begin(), lobe.end(), 0);
    return lobe;
  }
  std::vector<int> seeds = { static_cast<int>(
    std::max_element(strength.begin(), strength.end()) - strength.begin()) };
  // The seed nearest to light l in angle (largest cosine), and that cosine.
  auto nearest = [&](int l, double& cosine)
  {
    int best = 0;
    cosine = -2.0;
    for (int s = 0; s < static_cast<int>(seeds.size()); ++s)
    {
      const double c = Dot(travel[l].data(), travel[seeds[s]].data());
      if (c > cosine)
      {
        cosine = c;
        best = s;
      }
    }
    return best;
  };
  while (static_cast<int>(seeds.size()) < lobes)
  {
    int farthest = -1;
    double lowest = 2.0;
    for (int l = 0; l < lights; ++l)
    {
      double c;
      nearest(l, c);
      if (c < lowest && std::find(seeds.begin(), seeds.end(), l) == seeds.end())
      {
        lowest = c;
        farthest = l;
      }
    }
    seeds.push_back(farthest);
  }
  for (int l = 0; l < lights; ++l)
  {
    double c;
    lobe[l] = nearest(l, c);
  }
  return lobe;
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
  CopyArray(pd->GetArray(vtkRefractaMedium::AnisotropyName()), 1, 0.0f, m.Voxels, m.Anisotropy);
  m.HasGradient = g != nullptr;
  if (g)
  {
    CopyArray(g, 3, 0.0f, m.Voxels, m.Gradient);
  }
  // Paths curve only where grad n is non-zero. A given gradient that is zero everywhere (a medium
  // voxelized with exact interfaces: n jumps only across the meshes, which the surfaces' BVH
  // refracts) bends no path, so the march is straight between surfaces: curved steps would trace
  // the same lines at many times the cost.
  const auto range = std::minmax_element(m.N.begin(), m.N.end());
  m.Curved = *range.second > *range.first &&
    (!m.HasGradient ||
      std::any_of(m.Gradient.begin(), m.Gradient.end(), [](float g) { return g != 0.0f; }));
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
  m.NodeCuts = m.Attenuates && SteepExtinctionKinks(m);
  m.ExtinctionChannels = vtkRefractaMedium::IsGrey(m.Extinction) ? 1 : 3;
  m.AlbedoChannels = vtkRefractaMedium::IsGrey(m.Albedo) ? 1 : 3;
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

bool Run1D(vtkOpenCLContext* ctx, cl_kernel kernel, size_t count, const char* label, vtkObject* r)
{
  const size_t local = PhotonWorkGroup;
  const size_t global = std::max<size_t>(count, 1);
  return ctx->RunKernel(kernel, 1, &global, &local, label, r);
}

bool RunOctree(vtkOpenCLContext* ctx, vtkObject* reporter, Allocator& alloc, cl_mem nBuffer,
  const int dims[3], double eps, double eps2, vtkOpenCLBuffer& octree)
{
  const std::string options = "-DREFRACTA_EPS=" + vtkOpenCLContext::FloatLiteral(eps) +
    " -DREFRACTA_EPS2=" + vtkOpenCLContext::FloatLiteral(eps2);
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

using namespace vtkPhotonTracerDetail;

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
bool vtkPhotonTracer::TakeCachedMedium(Internals& run)
{
  MediumCache* c = this->Cache.get();
  const bool same = c && c->Input == run.Input && c->InputTime == run.Input->GetMTime() &&
    c->Context == this->GetContext() && c->PrimaryTolerance == this->PrimaryTolerance &&
    c->SecondaryTolerance == this->SecondaryTolerance &&
    c->AdaptiveStepping == this->AdaptiveStepping && c->UseProxyBounds == this->UseProxyBounds;
  // Glass bodies that attenuate or scatter where the kept medium's variant does neither: reload.
  bool bodyAttenuates, bodyScatters;
  BodyMedia(this->Surfaces, bodyAttenuates, bodyScatters);
  if (!same || (bodyAttenuates && !c->M.Attenuates) || (bodyScatters && !c->M.Scatters))
  {
    this->Cache.reset(); // releases the old medium's device buffers now
    return false;
  }
  run.M = std::move(c->M);
  run.NBuffer = std::move(c->NBuffer);
  run.GradBuffer = std::move(c->GradBuffer);
  run.Octree = std::move(c->Octree);
  run.ExtBuffer = std::move(c->ExtBuffer);
  run.AlbBuffer = std::move(c->AlbBuffer);
  run.Alloc.Bytes += c->Bytes;
  run.ReusedMedium = true;
  this->Cache.reset();
  return true;
}

void vtkPhotonTracer::KeepMedium(Internals& run)
{
  auto c = std::make_unique<MediumCache>();
  c->Input = run.Input;
  c->InputTime = run.Input->GetMTime();
  c->Context = run.Context;
  c->PrimaryTolerance = this->PrimaryTolerance;
  c->SecondaryTolerance = this->SecondaryTolerance;
  c->AdaptiveStepping = this->AdaptiveStepping;
  c->UseProxyBounds = this->UseProxyBounds;
  // The device bytes of the kept buffers, as the allocator counted them when they were made.
  const Medium& m = run.M;
  auto rounded = [](size_t bytes)
  { return static_cast<double>((std::max<size_t>(bytes, 1) + 15) / 16 * 16); };
  const size_t v = m.Voxels;
  c->Bytes = rounded((m.Curved ? v : 1) * 4) + rounded(m.Curved ? v * 12 : 16) +
    rounded(this->UsedOctree ? v : 16) +
    rounded((m.Attenuates ? v * m.ExtinctionChannels : 1) * 4) +
    rounded((m.Scatters ? v * m.AlbedoChannels : 1) * 4);
  c->M = std::move(run.M);
  c->NBuffer = std::move(run.NBuffer);
  c->GradBuffer = std::move(run.GradBuffer);
  c->Octree = std::move(run.Octree);
  c->ExtBuffer = std::move(run.ExtBuffer);
  c->AlbBuffer = std::move(run.AlbBuffer);
  this->Cache = std::move(c);
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

using namespace vtkPhotonTracerDetail;

namespace
{
// Progress at the end of the octree stage (vtkPhotonTracer.cxx has the other stages' shares).
constexpr double ProgressOctree = 0.01;
}

//------------------------------------------------------------------------------
// Before any allocation: the run's device buffers and host copies against the device's limits.
bool vtkPhotonTracer::PlanMemory(Internals& run)
{
  const Medium& m = run.M;
  const double v = static_cast<double>(m.Voxels);
  const double p = static_cast<double>(run.Photons);
  std::ostringstream gridText, photonText;
  gridText << "grid " << m.Dims[0] << " x " << m.Dims[1] << " x " << m.Dims[2];
  photonText << run.Photons << " photons";
  const std::string grid = gridText.str(), photons = photonText.str();
  const std::string gridSetting = "the grid size", photonSetting = "NumberOfPhotons";
  vtkNew<vtkOpenCLMemoryPlan> plan;
  plan->Reset("photon pass");
  if (!run.ReusedMedium)
  {
    plan->AddDeviceBuffer(grid, "refractive index", (m.Curved ? v : 1) * 4, gridSetting);
    plan->AddDeviceBuffer(grid, "index gradient", m.Curved ? v * 12 : 16, gridSetting);
    if (m.Curved && this->AdaptiveStepping)
    {
      // The level array, and the min/max pyramid (8 bytes a node, 8/7 of the voxels in all).
      plan->AddDeviceBuffer(grid, "octree", v, gridSetting);
      plan->AddDeviceBuffer(grid, "octree pyramid", v * 8 * 8 / 7, gridSetting);
    }
    plan->AddDeviceBuffer(
      grid, "extinction", (m.Attenuates ? v * m.ExtinctionChannels : 1) * 4, gridSetting);
    plan->AddDeviceBuffer(grid, "albedo", (m.Scatters ? v * m.AlbedoChannels : 1) * 4, gridSetting);
  }
  for (const char* what : { "photon positions", "photon directions", "photon powers" })
  {
    plan->AddDeviceBuffer(photons, what, p * 16, photonSetting);
  }
  plan->AddDeviceBuffer(photons, "photon streams", p * 4, photonSetting);
  if (this->StepsPerChunk > 0)
  {
    plan->AddDeviceBuffer(photons, "photon state (chunked march)", p * 128, photonSetting);
    plan->AddDeviceBuffer(photons, "photon status (chunked march)", p * 16, photonSetting);
  }
  const double accumulators = m.Scatters ? v * 6 * 8 * run.DepositBlocks() : 8;
  plan->AddDeviceBuffer(grid, "radiance and direction accumulators", accumulators, gridSetting);
  // Analog scattering: every order with surfaces (the lattice knows none), the first
  // ScatteringOrders ones for the first-collision split (vtkPhotonTracer.h).
  const bool everyOrder =
    (this->AnalogScattering && run.Surfaces) || this->ScatteringOrders == EVERY_ORDER;
  run.Analog = m.Scatters && (everyOrder || this->ScatteringOrders > 0);
  run.SplitOrders = run.Analog && !everyOrder ? this->ScatteringOrders : 0;
  if (run.Analog)
  {
    plan->AddDeviceBuffer(grid, "anisotropy", v * 4, gridSetting);
    // S_ms and its direction sums, then the split's source and its direction sums.
    plan->AddDeviceBuffer(grid,
      run.SplitOrders > 0 ? "S_ms, direction and lattice source accumulators"
                          : "S_ms and direction accumulators",
      v * MultipleAccumulatorsPerVoxel(run.SplitOrders) * 8, gridSetting);
    plan->AddHostMemory(
      grid, "MultipleScattering", v * 12 * (run.SplitOrders > 0 ? 4 : 2), gridSetting);
  }
  if (m.Scatters)
  {
    // Each resolved field (ResolveDeposits: Radiance, its direction, S_ms, its direction and the
    // split's source and its direction) and its smoothed copy. They are made one field at a time,
    // so this is an upper bound, like the allocator's count it is compared with.
    const int fields =
      2 + (run.Analog ? (run.SplitOrders > 0 ? 4 : 2) : 0) + (run.Lobes > 1 ? 2 * run.Lobes : 0);
    plan->AddDeviceBuffer(
      grid, "resolved fields", fields * (this->Smoothing ? 2 : 1) * v * 12, gridSetting);
  }
  // The volume caustic (vtkPhotonTracerVolumeCaustic.cxx), where it may apply: the brick map,
  // the pilot's piece counts and at most its budget of fine voxels (PHOTON_FINE_LONGS longs each;
  // 24 bytes each in the output).
  if (this->VolumeCausticSubdivision > 1 && m.Scatters && this->StepsPerChunk == 0 &&
    run.Surfaces && run.Surfaces->GetNumberOfDielectricTriangles() > 0)
  {
    const double c = this->VolumeCausticSubdivision;
    const double fine = std::min(double(this->MaximumNumberOfVolumeCausticVoxels), v * c * c * c);
    plan->AddDeviceBuffer(grid, "volume caustic bricks and pilot counts", v * 8, gridSetting);
    plan->AddDeviceBuffer(grid, "volume caustic accumulators (at most)", fine * 64, gridSetting);
    plan->AddHostMemory(grid, "volume caustic (at most)", fine * (64 + 24), gridSetting);
  }
  // Host: the medium's float copies (index, gradient, extinction, albedo) and the two outputs.
  plan->AddHostMemory(
    grid, "medium copies", v * 4 * (1 + 3 + 3 + (m.HasGradient ? 3 : 0)), gridSetting);
  plan->AddHostMemory(grid, "Radiance and RadianceDirection (and each lobe's)",
    v * 12 * 2 * run.DepositBlocks(), gridSetting);
  // The photon order (kept between runs) and, while it is sorted, a code per photon.
  plan->AddHostMemory(photons, "photon streams and their sort", p * 8, photonSetting);
  this->PlannedDeviceMemoryBytes =
    plan->GetDeviceBytes() + (run.ReusedMedium ? run.Alloc.Bytes : 0);
  this->PlannedHostMemoryBytes = plan->GetHostBytes();
  if (!plan->Fits(run.Context))
  {
    vtkErrorMacro(<< plan->GetMessage());
    return false;
  }
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
  if (run.ReusedMedium)
  {
    return this->ReportProgress(
      run, ProgressOctree); // index, gradient and octree are on the device
  }
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
