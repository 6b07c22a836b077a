#include "vtkMeshVoxelizer.h"

#include "vtkMeshVoxelizerMesh.h"

#include "vtkNew.h"

#include "vtkAlgorithmOutput.h"
#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMediumMaterial.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRefractaMedium.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numeric>
#include <sstream>

#if defined(__linux__)
#include <sys/mman.h> // madvise
#endif

vtkStandardNewMacro(vtkMeshVoxelizer);

namespace
{
using refracta_voxelize::Crossing;
using refracta_voxelize::PreparedMesh;
using Clock = std::chrono::steady_clock;

constexpr std::uint16_t SurfaceLabel = 0xFFFF;
constexpr int MaxMeshes = 0xFFFE;

double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

struct Grid
{
  int N[3];
  double O[3];
  double S[3];
  vtkIdType Id(int i, int j, int k) const
  {
    return i + static_cast<vtkIdType>(this->N[0]) * (j + static_cast<vtkIdType>(this->N[1]) * k);
  }
};

// Range of voxel indices along one axis whose closed box overlaps [lo, hi]; empty when first >
// last. Slightly conservative (a voxel too many only costs a test).
void VoxelRange(double lo, double hi, double origin, double spacing, int n, int& first, int& last)
{
  const double a = std::ceil((lo - origin) / spacing - 0.5 - 1e-9);
  const double b = std::floor((hi - origin) / spacing + 0.5 + 1e-9);
  first = static_cast<int>(std::max(0.0, std::min(a, static_cast<double>(n))));
  last = static_cast<int>(std::max(-1.0, std::min(b, static_cast<double>(n - 1))));
}

// Triangles per grid line (j, k) of one mesh, compressed rows: the candidates for crossings and
// for surface voxels along that line.
struct RowBuckets
{
  std::vector<vtkIdType> Offsets;
  std::vector<vtkIdType> Ids;
  void Build(const PreparedMesh& mesh, const Grid& g)
  {
    const vtkIdType rows = static_cast<vtkIdType>(g.N[1]) * g.N[2];
    this->Offsets.assign(rows + 1, 0);
    const vtkIdType numTris = static_cast<vtkIdType>(mesh.Triangles.size());
    std::vector<int> ranges(4 * numTris);
    for (int pass = 0; pass < 2; ++pass)
    {
      std::vector<vtkIdType> fill;
      if (pass == 1)
      {
        std::partial_sum(this->Offsets.begin(), this->Offsets.end(), this->Offsets.begin());
        this->Ids.resize(this->Offsets[rows]);
        fill.assign(this->Offsets.begin(), this->Offsets.end() - 1);
      }
      for (vtkIdType t = 0; t < numTris; ++t)
      {
        int* r = &ranges[4 * t];
        if (pass == 0)
        {
          double b[6];
          mesh.GetTriangleBounds(t, b);
          VoxelRange(b[2], b[3], g.O[1], g.S[1], g.N[1], r[0], r[1]);
          VoxelRange(b[4], b[5], g.O[2], g.S[2], g.N[2], r[2], r[3]);
        }
        for (int k = r[2]; k <= r[3]; ++k)
        {
          for (int j = r[0]; j <= r[1]; ++j)
          {
            const vtkIdType row = j + static_cast<vtkIdType>(g.N[1]) * k;
            if (pass == 0)
            {
              ++this->Offsets[row + 1];
            }
            else
            {
              this->Ids[fill[row]++] = t;
            }
          }
        }
      }
    }
  }
};

// Inside state of one mesh along one sample line (parallel to x), walked in increasing x.
struct LineWalker
{
  const PreparedMesh* Mesh = nullptr;
  std::vector<Crossing> Crossings;
  size_t Cursor = 0;
  int Parity = 0;
  bool Fallback = false;
  double Y = 0, Z = 0, Tolerance = 0;

  // Crossings of the line (., y, z) with the candidate triangles; false -> fallback.
  void Start(const PreparedMesh* mesh, const vtkIdType* ids, size_t count, double y, double z,
    double tolerance, std::atomic<vtkIdType>& fallbacks)
  {
    this->Mesh = mesh;
    this->Crossings.clear();
    this->Cursor = 0;
    this->Parity = 0;
    this->Y = y;
    this->Z = z;
    this->Tolerance = tolerance;
    this->Fallback = count > 0 && !mesh->LineCrossings(ids, count, y, z, this->Crossings);
    if (this->Fallback)
    {
      ++fallbacks;
    }
    std::sort(this->Crossings.begin(), this->Crossings.end());
  }

  // 1 inside, 0 outside, 0.5 exactly on the surface. x must not decrease between calls.
  double StateAt(double x)
  {
    const double p[3] = { x, this->Y, this->Z };
    if (this->Fallback)
    {
      return this->Mesh->Classify(p);
    }
    const size_t n = this->Crossings.size();
    while (this->Cursor < n && this->Crossings[this->Cursor].X < x - this->Tolerance)
    {
      this->Parity ^= 1;
      ++this->Cursor;
    }
    int parity = this->Parity;
    // Crossings within rounding distance: decide exactly which side of the face p is on.
    for (size_t c = this->Cursor; c < n && this->Crossings[c].X <= x + this->Tolerance; ++c)
    {
      const int side = this->Mesh->SideAlongX(this->Crossings[c].Triangle, p);
      if (side == 0)
      {
        return 0.5;
      }
      parity ^= side > 0 ? 1 : 0;
    }
    return parity;
  }
};

// Properties of one material at one point.
struct Props
{
  double N, Ext[3], Alb[3], G, Em[3];
};

// Mixes the materials of a voxel from the fractions owned by each (index 0: surroundings).
class Mixer
{
public:
  std::vector<vtkMediumMaterial*> Materials;
  std::vector<Props> Cached;
  std::vector<bool> Heterogeneous;
  float *N, *Ext, *Alb, *G, *Em, *Occ;

  void Init()
  {
    this->Cached.resize(this->Materials.size());
    this->Heterogeneous.resize(this->Materials.size());
    for (size_t m = 0; m < this->Materials.size(); ++m)
    {
      this->Heterogeneous[m] = this->Materials[m]->IsHeterogeneous();
      Props& p = this->Cached[m];
      this->Materials[m]->GetPropertiesAtDensity(1.0, p.N, p.Ext, p.Alb, p.G, p.Em);
    }
  }

  void Get(size_t m, const double x[3], Props& p) const
  {
    if (!this->Heterogeneous[m])
    {
      p = this->Cached[m];
      return;
    }
    const double d = this->Materials[m]->EvaluateDensity(x);
    this->Materials[m]->GetPropertiesAtDensity(d, p.N, p.Ext, p.Alb, p.G, p.Em);
  }

  // fractions[m] for every material; they sum to 1.
  void Mix(const double* fractions, const double x[3], vtkIdType v) const
  {
    double n = 0, st[3] = { 0, 0, 0 }, ss[3] = { 0, 0, 0 }, alb[3] = { 0, 0, 0 };
    double em[3] = { 0, 0, 0 }, gw = 0, w = 0, gOcc = 0;
    Props p;
    for (size_t m = 0; m < this->Materials.size(); ++m)
    {
      const double f = fractions[m];
      if (f <= 0.0)
      {
        continue;
      }
      this->Get(m, x, p);
      n += f * p.N;
      double meanScattering = 0.0;
      for (int c = 0; c < 3; ++c)
      {
        st[c] += f * p.Ext[c];
        ss[c] += f * p.Alb[c] * p.Ext[c];
        alb[c] += f * p.Alb[c];
        em[c] += f * p.Em[c];
        meanScattering += p.Alb[c] * p.Ext[c] / 3.0;
      }
      gw += f * meanScattering * p.G;
      w += f * meanScattering;
      gOcc += f * p.G;
    }
    this->N[v] = static_cast<float>(std::max(1.0, n));
    for (int c = 0; c < 3; ++c)
    {
      this->Ext[3 * v + c] = static_cast<float>(st[c]);
      const double a = st[c] > 0.0 ? ss[c] / st[c] : alb[c];
      this->Alb[3 * v + c] = static_cast<float>(std::min(1.0, std::max(0.0, a)));
      this->Em[3 * v + c] = static_cast<float>(em[c]);
    }
    const double g = w > 0.0 ? gw / w : gOcc;
    this->G[v] = static_cast<float>(std::min(0.9999, std::max(-0.9999, g)));
    this->Occ[v] = static_cast<float>(std::min(1.0, std::max(0.0, 1.0 - fractions[0])));
  }
};

// Ask Linux for transparent huge pages on a large fresh buffer: first-touching 60 bytes per voxel
// in 4 KiB pages costs seconds at 256^3 on machines with expensive page faults (VMs).
void AdviseHugePages(void* data, size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const std::uintptr_t huge = 2u << 20;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + huge - 1) & ~(huge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(huge - 1);
  if (end > begin)
  {
    madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
#else
  (void)data;
  (void)bytes;
#endif
}

vtkSmartPointer<vtkFloatArray> NewArray(int id, vtkIdType tuples)
{
  auto a = vtkSmartPointer<vtkFloatArray>::New();
  a->SetName(vtkRefractaMedium::GetArrayName(id));
  a->SetNumberOfComponents(vtkRefractaMedium::GetNumberOfComponents(id));
  a->SetNumberOfTuples(tuples);
  return a;
}

// One pass of a separable convolution along `axis`, edge voxels replicated.
void SmoothAxis(float* data, const Grid& g, int axis, const std::vector<double>& weights)
{
  const int half = static_cast<int>(weights.size() / 2);
  const int n = g.N[axis];
  const vtkIdType stride[3] = { 1, g.N[0], static_cast<vtkIdType>(g.N[0]) * g.N[1] };
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  const vtkIdType lines = static_cast<vtkIdType>(g.N[a1]) * g.N[a2];
  vtkSMPTools::For(0, lines,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<double> line(n);
      for (vtkIdType l = begin; l < end; ++l)
      {
        const vtkIdType u = l % g.N[a1], w = l / g.N[a1];
        float* base = data + u * stride[a1] + w * stride[a2];
        for (int i = 0; i < n; ++i)
        {
          line[i] = base[i * stride[axis]];
        }
        for (int i = 0; i < n; ++i)
        {
          double sum = 0.0;
          for (int t = -half; t <= half; ++t)
          {
            sum += weights[t + half] * line[std::min(n - 1, std::max(0, i + t))];
          }
          base[i * stride[axis]] = static_cast<float>(sum);
        }
      }
    });
}
} // namespace

//------------------------------------------------------------------------------
vtkMeshVoxelizer::vtkMeshVoxelizer()
{
  this->SurroundingMaterial = vtkSmartPointer<vtkMediumMaterial>::New();
}

//------------------------------------------------------------------------------
vtkMeshVoxelizer::~vtkMeshVoxelizer() = default;

//------------------------------------------------------------------------------
void vtkMeshVoxelizer::SetMaterial(int connection, vtkMediumMaterial* material)
{
  if (connection < 0 || connection >= MaxMeshes)
  {
    vtkErrorMacro(
      "SetMaterial: connection " << connection << " is out of range [0, " << MaxMeshes - 1 << "]");
    return;
  }
  if (static_cast<size_t>(connection) >= this->Materials.size())
  {
    this->Materials.resize(connection + 1);
  }
  if (this->Materials[connection] != material)
  {
    this->Materials[connection] = material;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkMediumMaterial* vtkMeshVoxelizer::GetMaterial(int connection)
{
  return connection >= 0 && static_cast<size_t>(connection) < this->Materials.size()
    ? this->Materials[connection].Get()
    : nullptr;
}

//------------------------------------------------------------------------------
void vtkMeshVoxelizer::SetSurroundingMaterial(vtkMediumMaterial* material)
{
  vtkSmartPointer<vtkMediumMaterial> m = material;
  if (!m)
  {
    m = vtkSmartPointer<vtkMediumMaterial>::New();
  }
  if (m != this->SurroundingMaterial)
  {
    this->SurroundingMaterial = m;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMeshVoxelizer::SetDimensions(int nx, int ny, int nz)
{
  const int n[3] = { std::max(1, nx), std::max(1, ny), std::max(1, nz) };
  if (n[0] != this->Dimensions[0] || n[1] != this->Dimensions[1] || n[2] != this->Dimensions[2] ||
    this->SizingMode != DIMENSIONS)
  {
    std::copy(n, n + 3, this->Dimensions);
    this->SizingMode = DIMENSIONS;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkMeshVoxelizer::SetSpacing(double sx, double sy, double sz)
{
  if (sx != this->Spacing[0] || sy != this->Spacing[1] || sz != this->Spacing[2] ||
    this->SizingMode != SPACING)
  {
    this->Spacing[0] = sx;
    this->Spacing[1] = sy;
    this->Spacing[2] = sz;
    this->SizingMode = SPACING;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkMTimeType vtkMeshVoxelizer::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  for (const auto& m : this->Materials)
  {
    if (m)
    {
      t = std::max(t, m->GetMTime());
    }
  }
  return std::max(t, this->SurroundingMaterial->GetMTime());
}

//------------------------------------------------------------------------------
double vtkMeshVoxelizer::GetStageTime(int stage) const
{
  return stage >= 0 && stage < NUMBER_OF_STAGES ? this->StageTimes[stage] : -1.0;
}

//------------------------------------------------------------------------------
const char* vtkMeshVoxelizer::GetStageName(int stage)
{
  static const char* names[NUMBER_OF_STAGES] = { "validation", "allocation", "inside",
    "supersampling", "materials", "smoothing", "gradient" };
  return stage >= 0 && stage < NUMBER_OF_STAGES ? names[stage] : nullptr;
}

//------------------------------------------------------------------------------
int vtkMeshVoxelizer::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port != 0)
  {
    return 0;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  // Optional so that "no mesh" reaches RequestData and gets Refracta's message.
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkMeshVoxelizer::ComputeGrid(const double meshBounds[6], int dims[3], double origin[3],
  double spacing[3], std::string& why) const
{
  const bool explicitBounds = this->Bounds[0] < this->Bounds[1] &&
    this->Bounds[2] < this->Bounds[3] && this->Bounds[4] < this->Bounds[5];
  double box[6];
  for (int a = 0; a < 3; ++a)
  {
    box[2 * a] = explicitBounds ? this->Bounds[2 * a] : meshBounds[2 * a] - this->Padding;
    box[2 * a + 1] =
      explicitBounds ? this->Bounds[2 * a + 1] : meshBounds[2 * a + 1] + this->Padding;
  }
  static const char axes[] = "xyz";
  std::ostringstream os;
  for (int a = 0; a < 3; ++a)
  {
    const double extent = box[2 * a + 1] - box[2 * a];
    if (!std::isfinite(box[2 * a]) || !std::isfinite(box[2 * a + 1]) || !(extent > 0.0))
    {
      os << "the box to voxelize has no positive, finite extent along " << axes[a] << " (["
         << box[2 * a] << ", " << box[2 * a + 1]
         << "]); set Padding > 0 or valid Bounds (min < max)";
      why = os.str();
      return false;
    }
    if (!std::isfinite(extent))
    {
      os << "the box to voxelize is too large along " << axes[a] << " ([" << box[2 * a] << ", "
         << box[2 * a + 1] << "]: its extent overflows); use smaller Bounds or coordinates";
      why = os.str();
      return false;
    }
    if (this->SizingMode == DIMENSIONS)
    {
      dims[a] = this->Dimensions[a];
      spacing[a] = extent / dims[a];
      origin[a] = box[2 * a] + 0.5 * spacing[a];
    }
    else
    {
      if (!(this->Spacing[a] > 0.0) || !std::isfinite(this->Spacing[a]))
      {
        os << "Spacing along " << axes[a] << " is " << this->Spacing[a]
           << "; in the SPACING sizing mode every spacing must be finite and > 0";
        why = os.str();
        return false;
      }
      const double n = std::ceil(extent / this->Spacing[a] - 1e-9);
      if (n > 65536.0)
      {
        os << "Spacing " << this->Spacing[a] << " along " << axes[a] << " gives " << n
           << " voxels (more than 65536); use a larger spacing";
        why = os.str();
        return false;
      }
      dims[a] = std::max(1, static_cast<int>(n));
      spacing[a] = this->Spacing[a];
      origin[a] = 0.5 * (box[2 * a] + box[2 * a + 1]) - 0.5 * (dims[a] - 1) * spacing[a];
    }
    // The gradient of n is stored as float: voxels below 1e-30 would overflow it, and a spacing
    // lost in the origin's rounding would put every voxel in one place.
    if (!(spacing[a] >= 1e-30) || origin[a] + spacing[a] == origin[a])
    {
      os << "the voxels are too thin along " << axes[a] << " (spacing " << spacing[a] << " at "
         << origin[a] << ", box [" << box[2 * a] << ", " << box[2 * a + 1]
         << "]); voxels must be at least 1e-30 world units and not lost in the origin's "
            "rounding: use larger Bounds or Spacing, or fewer voxels";
      why = os.str();
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
int vtkMeshVoxelizer::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  double meshBounds[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  const bool explicitBounds = this->Bounds[0] < this->Bounds[1] &&
    this->Bounds[2] < this->Bounds[3] && this->Bounds[4] < this->Bounds[5];
  if (!explicitBounds)
  {
    const int connections = this->GetNumberOfInputConnections(0);
    for (int c = 0; c < connections; ++c)
    {
      // The grid depends on the meshes' bounds, which only exist once the meshes do.
      int producerPort = 0;
      vtkAlgorithm* producer = this->GetInputAlgorithm(0, c, producerPort);
      if (producer)
      {
        producer->Update(producerPort);
      }
      vtkPolyData* mesh = vtkPolyData::GetData(inputVector[0], c);
      std::string badIds; // RequestData reports it; computing bounds would read out of range
      if (mesh && mesh->GetNumberOfPoints() > 0 && PreparedMesh::CheckPointIds(mesh, badIds))
      {
        double b[6];
        mesh->GetBounds(b);
        for (int a = 0; a < 3; ++a)
        {
          meshBounds[2 * a] = std::min(meshBounds[2 * a], b[2 * a]);
          meshBounds[2 * a + 1] = std::max(meshBounds[2 * a + 1], b[2 * a + 1]);
        }
      }
    }
  }
  int dims[3] = { 1, 1, 1 };
  double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  std::string why;
  if (!this->ComputeGrid(meshBounds, dims, origin, spacing, why))
  {
    // RequestData reports the problem with every detail; advertise a one-voxel grid meanwhile.
    dims[0] = dims[1] = dims[2] = 1;
    origin[0] = origin[1] = origin[2] = 0.0;
    spacing[0] = spacing[1] = spacing[2] = 1.0;
  }
  const int extent[6] = { 0, dims[0] - 1, 0, dims[1] - 1, 0, dims[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkMeshVoxelizer::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Every mesh is needed whole, whatever part of the image is requested.
  for (int c = 0; c < inputVector[0]->GetNumberOfInformationObjects(); ++c)
  {
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(c);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkMeshVoxelizer::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector);
  output->Initialize();
  std::fill(this->StageTimes, this->StageTimes + NUMBER_OF_STAGES, 0.0);
  this->NumberOfSupersampledVoxels = 0;
  this->NumberOfFallbackLines = 0;

  const int numMeshes = this->GetNumberOfInputConnections(0);
  if (numMeshes == 0)
  {
    vtkErrorMacro("No input mesh: add at least one closed triangle vtkPolyData with "
                  "AddInputData() or AddInputConnection(), and its material with SetMaterial()");
    return 0;
  }
  if (numMeshes > MaxMeshes)
  {
    vtkErrorMacro("" << numMeshes << " input meshes; at most " << MaxMeshes << " are supported");
    return 0;
  }

  // Materials: index 0 the surroundings, m + 1 the mesh on connection m.
  vtkNew<vtkMediumMaterial> vacuum;
  std::vector<vtkMediumMaterial*> materials{ this->SurroundingMaterial.Get() };
  for (int c = 0; c < numMeshes; ++c)
  {
    vtkMediumMaterial* m = this->GetMaterial(c);
    materials.push_back(m ? m : vacuum.Get());
  }
  for (size_t m = 0; m < materials.size(); ++m)
  {
    std::string why;
    if (!materials[m]->CheckDensity(why))
    {
      if (m == 0)
      {
        vtkErrorMacro("The surrounding material's density field is unusable: " << why);
      }
      else
      {
        vtkErrorMacro("The material of input connection "
          << m - 1 << " has an unusable density field: " << why);
      }
      return 0;
    }
  }

  // Validation and repair of every mesh.
  auto t0 = Clock::now();
  std::vector<std::unique_ptr<PreparedMesh>> meshes(numMeshes);
  std::vector<std::string> errors, warnings;
  for (int c = 0; c < numMeshes; ++c)
  {
    meshes[c].reset(new PreparedMesh);
    meshes[c]->Prepare(
      vtkPolyData::GetData(inputVector[0], c), c, this->CheckSelfIntersections, errors, warnings);
  }
  for (const auto& w : warnings)
  {
    vtkWarningMacro(<< w);
  }
  if (!errors.empty())
  {
    std::ostringstream os;
    for (const auto& e : errors)
    {
      os << "\n  " << e;
    }
    vtkErrorMacro("Cannot voxelize the input meshes:" << os.str());
    return 0;
  }
  this->StageTimes[STAGE_VALIDATION] = Seconds(t0, Clock::now());
  this->UpdateProgress(0.05);

  // Grid.
  double meshBounds[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (const auto& m : meshes)
  {
    for (int a = 0; a < 3; ++a)
    {
      meshBounds[2 * a] = std::min(meshBounds[2 * a], m->Bounds[2 * a]);
      meshBounds[2 * a + 1] = std::max(meshBounds[2 * a + 1], m->Bounds[2 * a + 1]);
    }
  }
  Grid g;
  std::string why;
  if (!this->ComputeGrid(meshBounds, g.N, g.O, g.S, why))
  {
    vtkErrorMacro("Cannot make the output grid: " << why);
    return 0;
  }
  const vtkIdType numVoxels = static_cast<vtkIdType>(g.N[0]) * g.N[1] * g.N[2];
  if (numVoxels > (static_cast<vtkIdType>(1) << 31))
  {
    vtkErrorMacro("The grid " << g.N[0] << " x " << g.N[1] << " x " << g.N[2]
                              << " has more than 2^31 voxels; use fewer");
    return 0;
  }
  output->SetExtent(0, g.N[0] - 1, 0, g.N[1] - 1, 0, g.N[2] - 1);
  output->SetOrigin(g.O);
  output->SetSpacing(g.S);

  t0 = Clock::now();
  auto nArray = NewArray(vtkRefractaMedium::REFRACTIVE_INDEX, numVoxels);
  auto gradArray = NewArray(vtkRefractaMedium::REFRACTIVE_INDEX_GRADIENT, numVoxels);
  auto extArray = NewArray(vtkRefractaMedium::EXTINCTION, numVoxels);
  auto albArray = NewArray(vtkRefractaMedium::ALBEDO, numVoxels);
  auto gArray = NewArray(vtkRefractaMedium::ANISOTROPY, numVoxels);
  auto emArray = NewArray(vtkRefractaMedium::EMISSION, numVoxels);
  auto occArray = NewArray(vtkRefractaMedium::OCCUPANCY, numVoxels);
  // First touch in parallel, in one place: the kernel's page faults on a fresh 60 bytes per
  // voxel would otherwise be charged to whichever stage writes a page first.
  for (vtkFloatArray* a : { nArray.Get(), gradArray.Get(), extArray.Get(), albArray.Get(),
         gArray.Get(), emArray.Get(), occArray.Get() })
  {
    float* data = a->GetPointer(0);
    AdviseHugePages(data, a->GetNumberOfValues() * sizeof(float));
    vtkSMPTools::For(0, a->GetNumberOfValues(),
      [data](vtkIdType begin, vtkIdType end) { std::fill(data + begin, data + end, 0.0f); });
  }
  std::vector<std::uint16_t> labels(numVoxels, 0);
  this->StageTimes[STAGE_ALLOCATION] = Seconds(t0, Clock::now());

  Mixer mixer;
  mixer.Materials = materials;
  mixer.N = nArray->GetPointer(0);
  mixer.Ext = extArray->GetPointer(0);
  mixer.Alb = albArray->GetPointer(0);
  mixer.G = gArray->GetPointer(0);
  mixer.Em = emArray->GetPointer(0);
  mixer.Occ = occArray->GetPointer(0);
  mixer.Init();

  // Owner order: the smallest enclosed volume wins (later connection on ties).
  std::vector<int> innermostFirst(numMeshes);
  std::iota(innermostFirst.begin(), innermostFirst.end(), 0);
  std::sort(innermostFirst.begin(), innermostFirst.end(),
    [&](int a, int b)
    {
      return meshes[a]->Volume < meshes[b]->Volume ||
        (meshes[a]->Volume == meshes[b]->Volume && a > b);
    });

  // ---- Inside test: one sample per voxel, and which voxels touch a surface. ----
  t0 = Clock::now();
  std::vector<RowBuckets> buckets(numMeshes);
  for (int m = 0; m < numMeshes; ++m)
  {
    buckets[m].Build(*meshes[m], g);
  }
  const int S = this->Supersampling;
  std::vector<double> offsets(S); // sample offsets inside a voxel, in voxels
  for (int a = 0; a < S; ++a)
  {
    offsets[a] = (a + 0.5) / S - 0.5;
  }
  std::atomic<vtkIdType> fallbacks(0);
  const vtkIdType numRows = static_cast<vtkIdType>(g.N[1]) * g.N[2];
  // Crossings closer than this to a sample are decided by an exact orientation test; it covers
  // the rounding of the interpolated crossing x (relative to the coordinates' magnitude).
  double maxAbsX = std::max(std::abs(g.O[0] - g.S[0]), std::abs(g.O[0] + g.N[0] * g.S[0]));
  for (const auto& m : meshes)
  {
    maxAbsX = std::max(maxAbsX, std::max(std::abs(m->Bounds[0]), std::abs(m->Bounds[1])));
  }
  const double tolerance = 1e-9 * g.S[0] + 1e-12 * maxAbsX;
  const bool surfaceOnly = this->SupersampleSurfaceOnly;
  const int progressBlocks = 10;

  auto insideRows = [&](vtkIdType begin, vtkIdType end)
  {
    LineWalker walker;
    std::vector<double> state(g.N[0]);
    for (vtkIdType row = begin; row < end; ++row)
    {
      const int j = static_cast<int>(row % g.N[1]), k = static_cast<int>(row / g.N[1]);
      std::uint16_t* label = &labels[g.Id(0, j, k)];
      const double y = g.O[1] + (j + offsets[0]) * g.S[1];
      const double z = g.O[2] + (k + offsets[0]) * g.S[2];
      // Surface voxels: boxes that touch a triangle (exact test), or every voxel.
      for (int m = 0; m < numMeshes; ++m)
      {
        const vtkIdType* ids = buckets[m].Ids.data() + buckets[m].Offsets[row];
        const vtkIdType count = buckets[m].Offsets[row + 1] - buckets[m].Offsets[row];
        for (vtkIdType n = 0; n < count && surfaceOnly; ++n)
        {
          double b[6];
          meshes[m]->GetTriangleBounds(ids[n], b);
          int i0, i1;
          VoxelRange(b[0], b[1], g.O[0], g.S[0], g.N[0], i0, i1);
          for (int i = i0; i <= i1; ++i)
          {
            if (label[i] == SurfaceLabel)
            {
              continue;
            }
            const double box[6] = { g.O[0] + (i - 0.5) * g.S[0], g.O[0] + (i + 0.5) * g.S[0],
              g.O[1] + (j - 0.5) * g.S[1], g.O[1] + (j + 0.5) * g.S[1], g.O[2] + (k - 0.5) * g.S[2],
              g.O[2] + (k + 0.5) * g.S[2] };
            if (meshes[m]->TriangleTouchesBox(ids[n], box))
            {
              label[i] = SurfaceLabel;
            }
          }
        }
      }
      if (!surfaceOnly)
      {
        std::fill(label, label + g.N[0], SurfaceLabel);
        continue;
      }
      // One sample per remaining voxel: the whole box is on that sample's side of every mesh.
      std::fill(state.begin(), state.end(), 0.0);
      for (int r = numMeshes - 1; r >= 0; --r) // outermost first, inner ones overwrite
      {
        const int m = innermostFirst[r];
        const vtkIdType count = buckets[m].Offsets[row + 1] - buckets[m].Offsets[row];
        if (count == 0)
        {
          continue; // the line misses the mesh: outside
        }
        walker.Start(meshes[m].get(), buckets[m].Ids.data() + buckets[m].Offsets[row],
          static_cast<size_t>(count), y, z, tolerance, fallbacks);
        for (int i = 0; i < g.N[0]; ++i)
        {
          if (label[i] != SurfaceLabel && walker.StateAt(g.O[0] + (i + offsets[0]) * g.S[0]) > 0.75)
          {
            label[i] = static_cast<std::uint16_t>(m + 1);
          }
        }
      }
    }
  };
  for (int block = 0; block < progressBlocks; ++block)
  {
    vtkSMPTools::For(numRows * block / progressBlocks, numRows * (block + 1) / progressBlocks,
      std::max<vtkIdType>(1, numRows / 256), insideRows);
    this->UpdateProgress(0.05 + 0.2 * (block + 1) / progressBlocks);
  }
  this->StageTimes[STAGE_INSIDE] = Seconds(t0, Clock::now());

  // ---- Supersampling of the surface voxels, and their materials. ----
  t0 = Clock::now();
  std::atomic<vtkIdType> supersampled(0);
  auto superRows = [&](vtkIdType begin, vtkIdType end)
  {
    std::vector<LineWalker> walkers(numMeshes);
    std::vector<double> fractions; // (numMeshes + 1) per voxel of the row
    std::vector<int> surface;
    std::vector<double> state(numMeshes);
    for (vtkIdType row = begin; row < end; ++row)
    {
      const int j = static_cast<int>(row % g.N[1]), k = static_cast<int>(row / g.N[1]);
      const std::uint16_t* label = &labels[g.Id(0, j, k)];
      surface.clear();
      for (int i = 0; i < g.N[0]; ++i)
      {
        if (label[i] == SurfaceLabel)
        {
          surface.push_back(i);
        }
      }
      if (surface.empty())
      {
        continue;
      }
      supersampled += static_cast<vtkIdType>(surface.size());
      fractions.assign(surface.size() * (numMeshes + 1), 0.0);
      for (int b = 0; b < S; ++b)
      {
        for (int a = 0; a < S; ++a)
        {
          const double y = g.O[1] + (j + offsets[a]) * g.S[1];
          const double z = g.O[2] + (k + offsets[b]) * g.S[2];
          for (int m = 0; m < numMeshes; ++m)
          {
            const vtkIdType count = buckets[m].Offsets[row + 1] - buckets[m].Offsets[row];
            walkers[m].Start(meshes[m].get(), buckets[m].Ids.data() + buckets[m].Offsets[row],
              static_cast<size_t>(count), y, z, tolerance, fallbacks);
          }
          for (size_t s = 0; s < surface.size(); ++s)
          {
            double* f = &fractions[s * (numMeshes + 1)];
            for (int c = 0; c < S; ++c)
            {
              const double x = g.O[0] + (surface[s] + offsets[c]) * g.S[0];
              // Innermost wins: each mesh takes its share of what inner meshes left.
              double remaining = 1.0;
              for (int r = 0; r < numMeshes && remaining > 0.0; ++r)
              {
                const int m = innermostFirst[r];
                const double take = remaining * walkers[m].StateAt(x);
                f[m + 1] += take;
                remaining -= take;
              }
              f[0] += remaining;
            }
          }
        }
      }
      const double norm = 1.0 / (static_cast<double>(S) * S * S);
      for (size_t s = 0; s < surface.size(); ++s)
      {
        double* f = &fractions[s * (numMeshes + 1)];
        for (int m = 0; m <= numMeshes; ++m)
        {
          f[m] *= norm;
        }
        const double x[3] = { g.O[0] + surface[s] * g.S[0], g.O[1] + j * g.S[1],
          g.O[2] + k * g.S[2] };
        mixer.Mix(f, x, g.Id(surface[s], j, k));
      }
    }
  };
  for (int block = 0; block < progressBlocks; ++block)
  {
    vtkSMPTools::For(numRows * block / progressBlocks, numRows * (block + 1) / progressBlocks,
      std::max<vtkIdType>(1, numRows / 256), superRows);
    this->UpdateProgress(0.25 + 0.45 * (block + 1) / progressBlocks);
  }
  this->NumberOfSupersampledVoxels = supersampled;
  this->NumberOfFallbackLines = fallbacks;
  this->StageTimes[STAGE_SUPERSAMPLING] = Seconds(t0, Clock::now());

  // ---- Materials of the voxels wholly inside one mesh or outside all. ----
  t0 = Clock::now();
  vtkSMPTools::For(0, numVoxels,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<double> f(numMeshes + 1, 0.0);
      for (vtkIdType v = begin; v < end; ++v)
      {
        const std::uint16_t l = labels[v];
        if (l == SurfaceLabel)
        {
          continue;
        }
        const int i = static_cast<int>(v % g.N[0]);
        const int j = static_cast<int>((v / g.N[0]) % g.N[1]);
        const int k = static_cast<int>(v / (static_cast<vtkIdType>(g.N[0]) * g.N[1]));
        const double x[3] = { g.O[0] + i * g.S[0], g.O[1] + j * g.S[1], g.O[2] + k * g.S[2] };
        f[l] = 1.0;
        mixer.Mix(f.data(), x, v);
        f[l] = 0.0;
      }
    });
  labels = std::vector<std::uint16_t>();
  this->StageTimes[STAGE_MATERIALS] = Seconds(t0, Clock::now());
  this->UpdateProgress(0.75);

  // ---- Gaussian smoothing of n (separable). ----
  t0 = Clock::now();
  const int window = this->SmoothingWindow | 1; // odd
  if (window > 1)
  {
    const double sigma = this->SmoothingSigma > 0.0 ? this->SmoothingSigma : window / 6.0;
    std::vector<double> weights(window);
    double sum = 0.0;
    for (int t = 0; t < window; ++t)
    {
      const double u = t - window / 2;
      weights[t] = std::exp(-0.5 * u * u / (sigma * sigma));
      sum += weights[t];
    }
    for (double& w : weights)
    {
      w /= sum;
    }
    for (int axis = 0; axis < 3; ++axis)
    {
      SmoothAxis(nArray->GetPointer(0), g, axis, weights);
      this->UpdateProgress(0.75 + 0.05 * (axis + 1));
    }
  }
  this->StageTimes[STAGE_SMOOTHING] = Seconds(t0, Clock::now());

  // ---- Gradient of n by central differences (one-sided on the grid's faces). ----
  t0 = Clock::now();
  {
    const float* n = nArray->GetPointer(0);
    float* grad = gradArray->GetPointer(0);
    const vtkIdType stride[3] = { 1, g.N[0], static_cast<vtkIdType>(g.N[0]) * g.N[1] };
    vtkSMPTools::For(0, numVoxels,
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType v = begin; v < end; ++v)
        {
          const int idx[3] = { static_cast<int>(v % g.N[0]),
            static_cast<int>((v / g.N[0]) % g.N[1]), static_cast<int>(v / stride[2]) };
          for (int a = 0; a < 3; ++a)
          {
            double d = 0.0;
            if (g.N[a] > 1)
            {
              const int lo = std::max(0, idx[a] - 1), hi = std::min(g.N[a] - 1, idx[a] + 1);
              d = (static_cast<double>(n[v + (hi - idx[a]) * stride[a]]) -
                    n[v + (lo - idx[a]) * stride[a]]) /
                ((hi - lo) * g.S[a]);
            }
            grad[3 * v + a] = static_cast<float>(d);
          }
        }
      });
  }
  this->StageTimes[STAGE_GRADIENT] = Seconds(t0, Clock::now());

  vtkPointData* pd = output->GetPointData();
  pd->AddArray(nArray);
  pd->AddArray(gradArray);
  pd->AddArray(extArray);
  pd->AddArray(albArray);
  pd->AddArray(gArray);
  pd->AddArray(emArray);
  pd->AddArray(occArray);
  pd->SetActiveScalars(vtkRefractaMedium::RefractiveIndexName());
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkMeshVoxelizer::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Materials: " << this->Materials.size() << "\n";
  for (size_t m = 0; m < this->Materials.size(); ++m)
  {
    os << indent << "  connection " << m << ": " << this->Materials[m].Get() << "\n";
  }
  os << indent << "SurroundingMaterial: " << this->SurroundingMaterial.Get() << "\n";
  os << indent << "SizingMode: " << (this->SizingMode == DIMENSIONS ? "DIMENSIONS" : "SPACING")
     << "\n";
  os << indent << "Dimensions: (" << this->Dimensions[0] << ", " << this->Dimensions[1] << ", "
     << this->Dimensions[2] << ")\n";
  os << indent << "Spacing: (" << this->Spacing[0] << ", " << this->Spacing[1] << ", "
     << this->Spacing[2] << ")\n";
  os << indent << "Padding: " << this->Padding << "\n";
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "Supersampling: " << this->Supersampling << "\n";
  os << indent << "SupersampleSurfaceOnly: " << this->SupersampleSurfaceOnly << "\n";
  os << indent << "SmoothingWindow: " << this->SmoothingWindow << "\n";
  os << indent << "SmoothingSigma: " << this->SmoothingSigma << "\n";
  os << indent << "CheckSelfIntersections: " << this->CheckSelfIntersections << "\n";
  for (int s = 0; s < NUMBER_OF_STAGES; ++s)
  {
    os << indent << "StageTime(" << GetStageName(s) << "): " << this->StageTimes[s] << " s\n";
  }
  os << indent << "NumberOfSupersampledVoxels: " << this->NumberOfSupersampledVoxels << "\n";
  os << indent << "NumberOfFallbackLines: " << this->NumberOfFallbackLines << "\n";
}
