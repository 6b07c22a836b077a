#include "vtkMeshVoxelizer.h"

#include "vtkMeshVoxelizerMesh.h"
#include "vtkMeshVoxelizerRaster.h"

#include "vtkNew.h"

#include "vtkAlgorithmOutput.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMediumMaterial.h"
#include "vtkMediumValidator.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSettings.h"
#include "vtkSMPTools.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <new>
#include <numeric>
#include <sstream>

vtkStandardNewMacro(vtkMeshVoxelizer);
vtkRefractaCxxSetClampMacro(vtkMeshVoxelizer, Padding, 0.0, VTK_DOUBLE_MAX);
vtkRefractaCxxSetClampMacro(vtkMeshVoxelizer, SmoothingSigma, 0.0, VTK_DOUBLE_MAX);

void vtkMeshVoxelizer::SetSmoothingWindow(int value)
{
  const int window = std::min(std::max(value, 1), 63);
  if (window % 2 == 0)
  {
    vtkErrorMacro("SetSmoothingWindow(" << value << "): the window must be odd (1, 3, ..., 63; "
                                        << "1 disables smoothing); it stays "
                                        << this->SmoothingWindow << ".");
    return;
  }
  if (window != this->SmoothingWindow)
  {
    this->SmoothingWindow = window;
    this->Modified();
  }
}

namespace
{
using namespace refracta_voxelize;
using Clock = std::chrono::steady_clock;

constexpr int MaxMeshes = 0xFFFE;

double Seconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double>(b - a).count();
}

// Runs rows(begin, end) over [0, rows) in vtkSMPTools blocks, reporting progress from `from` to
// `to` on `algorithm` after each tenth.
template <typename RowFunction>
void ForRowsWithProgress(
  vtkIdType rows, double from, double to, vtkAlgorithm* algorithm, const RowFunction& function)
{
  const int progressBlocks = 10;
  for (int block = 0; block < progressBlocks; ++block)
  {
    vtkSMPTools::For(rows * block / progressBlocks, rows * (block + 1) / progressBlocks,
      std::max<vtkIdType>(1, rows / 256), function);
    algorithm->UpdateProgress(from + (to - from) * (block + 1) / progressBlocks);
  }
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
void vtkMeshVoxelizer::SetMeshName(int connection, const std::string& name)
{
  if (connection < 0 || connection >= MaxMeshes)
  {
    vtkErrorMacro(
      "SetMeshName: connection " << connection << " is out of range [0, " << MaxMeshes - 1 << "]");
    return;
  }
  if (static_cast<size_t>(connection) >= this->MeshNames.size())
  {
    this->MeshNames.resize(connection + 1);
  }
  if (this->MeshNames[connection] != name)
  {
    this->MeshNames[connection] = name;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
std::string vtkMeshVoxelizer::GetMeshName(int connection) const
{
  if (connection >= 0 && static_cast<size_t>(connection) < this->MeshNames.size() &&
    !this->MeshNames[connection].empty())
  {
    return this->MeshNames[connection];
  }
  return "Input connection " + std::to_string(connection);
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

namespace
{
// The material outside mesh m (materials: 0 the surroundings, k + 1 mesh k): the innermost
// other mesh (smallest enclosed volume) that contains m's first vertex, else the surroundings.
size_t OuterMaterial(const std::vector<std::unique_ptr<PreparedMesh>>& meshes, size_t m)
{
  const double* p = meshes[m]->Points.data();
  size_t outer = 0;
  double volume = VTK_DOUBLE_MAX;
  for (size_t k = 0; k < meshes.size(); ++k)
  {
    if (k != m && meshes[k]->Volume >= meshes[m]->Volume && meshes[k]->Volume < volume &&
      meshes[k]->Classify(p) > 0.5)
    {
      outer = k + 1;
      volume = meshes[k]->Volume;
    }
  }
  return outer;
}

// One InterfaceMaterials tuple (vtkRefractaMedium): the medium filling a mesh, homogeneous
// unless its material has a density field (then flagged 0: the passes use the grid inside).
// The grid mixes a cut voxel's materials by occupancy; with this record the passes need not.
void InsideMedium(vtkMediumMaterial* material, double body[])
{
  double n, g;
  material->GetPropertiesAtDensity(1.0, n, body, body + 3, g, body + 7);
  body[6] = g;
  body[10] = material->IsHeterogeneous() ? 0.0 : 1.0;
}

// The refractive indices inside and outside mesh m (the innermost other mesh whose volume holds
// it, or the surroundings).
std::array<double, 2> IndexPair(const std::vector<std::unique_ptr<PreparedMesh>>& meshes,
  const std::vector<vtkMediumMaterial*>& materials, size_t m)
{
  return { materials[m + 1]->GetRefractiveIndex(),
    materials[OuterMaterial(meshes, m)]->GetRefractiveIndex() };
}

// Whether mesh m is an optical interface: an index-matched mesh (the same n on both sides)
// neither refracts nor reflects, and its medium is left to the grid's occupancy mix.
bool IsInterface(const std::vector<std::unique_ptr<PreparedMesh>>& meshes,
  const std::vector<vtkMediumMaterial*>& materials, size_t m)
{
  const std::array<double, 2> pair = IndexPair(meshes, materials, m);
  return std::abs(pair[0] - pair[1]) > 1e-9 * std::max(pair[0], pair[1]);
}

// The meshes with an index step as exact interfaces in the output's field data (vtkRefractaMedium's
// names).
void WriteInterfaces(const std::vector<std::unique_ptr<PreparedMesh>>& meshes,
  const std::vector<vtkMediumMaterial*>& materials, vtkImageData* output)
{
  vtkNew<vtkDoubleArray> points, indices, bodies;
  vtkNew<vtkIdTypeArray> triangles;
  bodies->SetName(vtkRefractaMedium::InterfaceMaterialsName());
  bodies->SetNumberOfComponents(vtkRefractaMedium::InterfaceMaterialComponents);
  points->SetName(vtkRefractaMedium::InterfacePointsName());
  points->SetNumberOfComponents(3);
  triangles->SetName(vtkRefractaMedium::InterfaceTrianglesName());
  triangles->SetNumberOfComponents(3);
  indices->SetName(vtkRefractaMedium::InterfaceIndicesName());
  indices->SetNumberOfComponents(2);
  for (size_t m = 0; m < meshes.size(); ++m)
  {
    if (!IsInterface(meshes, materials, m))
    {
      continue;
    }
    const vtkIdType first = points->GetNumberOfTuples();
    const auto& mesh = *meshes[m];
    for (size_t p = 0; p < mesh.Points.size() / 3; ++p)
    {
      points->InsertNextTuple(&mesh.Points[3 * p]);
    }
    const std::array<double, 2> pair = IndexPair(meshes, materials, m);
    double body[vtkRefractaMedium::InterfaceMaterialComponents];
    InsideMedium(materials[m + 1], body);
    for (const auto& t : mesh.Triangles)
    {
      const vtkIdType ids[3] = { first + t[0], first + t[1], first + t[2] };
      triangles->InsertNextTypedTuple(ids);
      indices->InsertNextTuple(pair.data());
      bodies->InsertNextTuple(body);
    }
  }
  output->GetFieldData()->AddArray(points);
  output->GetFieldData()->AddArray(triangles);
  output->GetFieldData()->AddArray(indices);
  output->GetFieldData()->AddArray(bodies);
}
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
        vtkErrorMacro(<< this->GetMeshName(static_cast<int>(m) - 1)
                      << ": its material has an unusable density field: " << why);
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
    meshes[c]->Prepare(vtkPolyData::GetData(inputVector[0], c), this->GetMeshName(c),
      this->CheckSelfIntersections, errors, warnings);
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
  // The big allocations (60 bytes per voxel in the arrays, 2 in the labels) happen here, on this
  // thread, where a failure is caught and named: a grid too large for the memory or for a
  // process limit (ulimit -v) aborted inside VTK before.
  vtkSmartPointer<vtkFloatArray> nArray, gradArray, extArray, albArray, gArray, emArray, occArray;
  Rasterizer raster(meshes, g, this->Supersampling, this->SupersampleSurfaceOnly);
  bool allocated = true;
  try
  {
    nArray = vtkRefractaMedium::NewArrayOrNull(vtkRefractaMedium::REFRACTIVE_INDEX, numVoxels);
    gradArray =
      vtkRefractaMedium::NewArrayOrNull(vtkRefractaMedium::REFRACTIVE_INDEX_GRADIENT, numVoxels);
    extArray = vtkRefractaMedium::NewArrayOrNull(vtkRefractaMedium::EXTINCTION, numVoxels);
    albArray = vtkRefractaMedium::NewArrayOrNull(vtkRefractaMedium::ALBEDO, numVoxels);
    gArray = vtkRefractaMedium::NewArrayOrNull(vtkRefractaMedium::ANISOTROPY, numVoxels);
    emArray = vtkRefractaMedium::NewArrayOrNull(vtkRefractaMedium::EMISSION, numVoxels);
    occArray = vtkRefractaMedium::NewArrayOrNull(vtkRefractaMedium::OCCUPANCY, numVoxels);
    raster.Labels.assign(numVoxels, 0);
  }
  catch (const std::bad_alloc&)
  {
    allocated = false;
  }
  for (vtkFloatArray* a : { nArray.Get(), gradArray.Get(), extArray.Get(), albArray.Get(),
         gArray.Get(), emArray.Get(), occArray.Get() })
  {
    allocated = allocated && a && a->GetNumberOfTuples() == numVoxels;
  }
  if (!allocated)
  {
    vtkErrorMacro("Cannot allocate the medium of the grid "
      << g.N[0] << " x " << g.N[1] << " x " << g.N[2] << " (" << numVoxels * 62.0 / (1 << 30)
      << " GiB at 62 bytes per voxel): not enough memory. Use fewer voxels (smaller grid "
         "dimensions or a larger spacing).");
    output->Initialize(); // an empty output, not a grid without arrays
    return 0;
  }
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

  // ---- Inside test: one sample per voxel, and which voxels touch a surface. ----
  t0 = Clock::now();
  raster.Prepare();
  const vtkIdType numRows = raster.GetNumberOfRows();
  ForRowsWithProgress(numRows, 0.05, 0.25, this,
    [&](vtkIdType begin, vtkIdType end) { raster.ClassifyRows(begin, end); });
  this->StageTimes[STAGE_INSIDE] = Seconds(t0, Clock::now());

  // ---- Supersampling of the surface voxels, and their materials. ----
  t0 = Clock::now();
  ForRowsWithProgress(numRows, 0.25, 0.7, this,
    [&](vtkIdType begin, vtkIdType end) { raster.SupersampleRows(begin, end, mixer); });
  this->NumberOfSupersampledVoxels = raster.Supersampled;
  this->NumberOfFallbackLines = raster.Fallbacks;
  this->StageTimes[STAGE_SUPERSAMPLING] = Seconds(t0, Clock::now());

  // Exact interfaces: the voxels a surface touches, where grad n must not see the jump.
  bool densityIndex = false;
  for (const vtkMediumMaterial* m : materials)
  {
    densityIndex =
      densityIndex || const_cast<vtkMediumMaterial*>(m)->GetDensityScalesRefractiveIndex();
  }
  bool anyInterface = false;
  for (size_t m = 0; m < meshes.size(); ++m)
  {
    anyInterface = anyInterface || IsInterface(meshes, materials, m);
  }
  this->WroteInterfaces = this->InterfaceMode == EXACT_INTERFACES && !densityIndex && anyInterface;
  if (this->InterfaceMode == EXACT_INTERFACES && densityIndex)
  {
    vtkWarningMacro("EXACT_INTERFACES needs one refractive index per material, but a material "
                    "scales its index by a density field (DensityScalesRefractiveIndex): this "
                    "grid is voxelized with SMOOTHED_INDEX instead.");
  }
  std::vector<std::uint8_t> cut;
  if (this->WroteInterfaces)
  {
    cut.resize(raster.Labels.size());
    for (size_t v = 0; v < cut.size(); ++v)
    {
      cut[v] = raster.Labels[v] == SurfaceLabel ? 1 : 0;
    }
  }

  // ---- Materials of the voxels wholly inside one mesh or outside all. ----
  t0 = Clock::now();
  raster.MixInteriorVoxels(mixer);
  this->StageTimes[STAGE_MATERIALS] = Seconds(t0, Clock::now());
  this->UpdateProgress(0.75);

  // ---- Gaussian smoothing of n (separable), and its gradient. ----
  t0 = Clock::now();
  const int window = this->SmoothingWindow;
  if (window > 1 && !this->WroteInterfaces)
  {
    SmoothIndex(nArray->GetPointer(0), g, window, this->SmoothingSigma);
  }
  this->StageTimes[STAGE_SMOOTHING] = Seconds(t0, Clock::now());
  this->UpdateProgress(0.9);
  t0 = Clock::now();
  IndexGradient(nArray->GetPointer(0), gradArray->GetPointer(0), g,
    this->WroteInterfaces ? cut.data() : nullptr);
  if (this->WroteInterfaces)
  {
    WriteInterfaces(meshes, materials, output);
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
  if (!this->CheckOutputValues(output))
  {
    output->Initialize();
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkMeshVoxelizer::CheckOutputValues(vtkImageData* output)
{
  // Every material value is finite and in range (vtkMediumMaterial's setters), but a coefficient
  // times its density field can overflow a float. The consumers validate the same arrays, and
  // the validator remembers arrays that passed, so this scan is not repeated downstream.
  vtkNew<vtkMediumValidator> validator;
  if (validator->Validate(output))
  {
    return true;
  }
  vtkErrorMacro("The voxelized medium is not valid (a material's value times its density field "
                "left the range a medium allows):\n"
    << validator->GetErrorMessage());
  return false;
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
  for (size_t m = 0; m < this->MeshNames.size(); ++m)
  {
    os << indent << "MeshName " << m << ": " << this->GetMeshName(static_cast<int>(m)) << "\n";
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
  os << indent << "InterfaceMode: "
     << (this->InterfaceMode == EXACT_INTERFACES ? "EXACT_INTERFACES" : "SMOOTHED_INDEX") << "\n";
  os << indent << "CheckSelfIntersections: " << this->CheckSelfIntersections << "\n";
  for (int s = 0; s < NUMBER_OF_STAGES; ++s)
  {
    os << indent << "StageTime(" << GetStageName(s) << "): " << this->StageTimes[s] << " s\n";
  }
  os << indent << "NumberOfSupersampledVoxels: " << this->NumberOfSupersampledVoxels << "\n";
  os << indent << "NumberOfFallbackLines: " << this->NumberOfFallbackLines << "\n";
}
