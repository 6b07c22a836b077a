// Private to vtkMeshVoxelizer (not installed): the rasterisation of the prepared meshes onto the
// output grid. The inside test (one sample per voxel along grid lines, exact crossings, surface
// voxels found by exact triangle-box tests), the supersampling of the surface voxels into
// material fractions, the material mixing, and the smoothing and gradient of n. vtkMeshVoxelizer
// runs these stages in order and times them; CGAL stays in vtkMeshVoxelizerMesh.cxx.
#ifndef vtkMeshVoxelizerRaster_h
#define vtkMeshVoxelizerRaster_h

#include "vtkMeshVoxelizerMesh.h"
#include "vtkType.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

class vtkMediumMaterial;

namespace refracta_voxelize
{
constexpr std::uint16_t SurfaceLabel = 0xFFFF;

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
void VoxelRange(double lo, double hi, double origin, double spacing, int n, int& first, int& last);

// Triangles per grid line (j, k) of one mesh, compressed rows: the candidates for crossings and
// for surface voxels along that line.
struct RowBuckets
{
  std::vector<vtkIdType> Offsets;
  std::vector<vtkIdType> Ids;
  void Build(const PreparedMesh& mesh, const Grid& g);
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
    double tolerance, std::atomic<vtkIdType>& fallbacks);

  // 1 inside, 0 outside, 0.5 exactly on the surface. x must not decrease between calls.
  double StateAt(double x);
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

  void Init();
  void Get(size_t m, const double x[3], Props& p) const;
  // fractions[m] for every material; they sum to 1. Writes voxel v of the output arrays.
  void Mix(const double* fractions, const double x[3], vtkIdType v) const;
};

// The voxel labels and the per-row work of the inside test and of the supersampling. Labels: 0
// outside every mesh, m + 1 wholly inside mesh m (the innermost when nested), SurfaceLabel for a
// voxel a surface touches (its materials come from the supersampling).
class Rasterizer
{
public:
  Rasterizer(const std::vector<std::unique_ptr<PreparedMesh>>& meshes, const Grid& grid,
    int supersampling, bool surfaceOnly);

  // Buckets the triangles by grid line and fixes the sample offsets and the crossing tolerance.
  void Prepare();
  // Inside test of rows [begin, end) (row = j + N[1] k): sets their labels.
  void ClassifyRows(vtkIdType begin, vtkIdType end);
  // Supersampling of the surface voxels of rows [begin, end) into material fractions, mixed.
  void SupersampleRows(vtkIdType begin, vtkIdType end, const Mixer& mixer);
  // Materials of every voxel wholly inside one mesh or outside all; frees the labels.
  void MixInteriorVoxels(const Mixer& mixer);

  vtkIdType GetNumberOfRows() const;
  std::vector<std::uint16_t> Labels;
  std::atomic<vtkIdType> Fallbacks{ 0 };
  std::atomic<vtkIdType> Supersampled{ 0 };

private:
  const std::vector<std::unique_ptr<PreparedMesh>>& Meshes;
  const Grid& G;
  const int S;
  const bool SurfaceOnly;
  std::vector<int> InnermostFirst; // owner order: the smallest enclosed volume first
  std::vector<RowBuckets> Buckets;
  std::vector<double> Offsets; // sample offsets inside a voxel, in voxels
  double Tolerance = 0.0;
};

// Ask Linux for transparent huge pages on a large fresh buffer.
void AdviseHugePages(void* data, size_t bytes);

// Separable Gaussian smoothing of n (window voxels, odd; sigma in voxels, 0: window / 6), edge
// voxels replicated.
void SmoothIndex(float* n, const Grid& g, int window, double sigma);

// Gradient of n by central differences (one-sided on the grid's faces), 3 floats per voxel. With
// `cut` (one flag per voxel, nullptr: none), the component along an axis is 0 wherever the
// stencil along it holds a flagged voxel (exact interfaces: the jump is not a gradient).
void IndexGradient(
  const float* n, float* gradient, const Grid& g, const std::uint8_t* cut = nullptr);
}

#endif
