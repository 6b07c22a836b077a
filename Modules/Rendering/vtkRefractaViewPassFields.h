// Private to vtkRefractaViewPass (not installed): host-side conversions of the fields the view
// pass uploads (arrays to floats, world vectors to the grid-local frame, the central-difference
// gradient of the refractive index, the environment image to linear RGB floats, checks of the
// lighting arrays) and the compile options of the kernel variant (Kernels/view_pass.cl).
#ifndef vtkRefractaViewPassFields_h
#define vtkRefractaViewPassFields_h

#include "vtkType.h" // for vtkIdType

#include "vtkOpenCLContext.h" // for cl_kernel

#include <string> // for the error message and the options
#include <vector> // for the values

class vtkDataArray;
class vtkObject;
class vtkImageData;
class vtkRefractaGridFrame;

namespace vtkRefractaViewPassDetail
{
// Copies an array's values into floats, `comps` components per tuple (fast path for floats).
void FetchFloats(vtkDataArray* array, int comps, std::vector<float>& out);

// (sigma, emission RGB) per voxel from a grey extinction and an emission (3 components each, the
// same number of tuples), as the kernel's REFRACTA_PACKED_MEDIUM reads them.
std::vector<float> PackGreyMedium(
  const std::vector<float>& extinction, const std::vector<float>& emission);

// Rotates world-frame vectors (3 per tuple) into the grid-local frame.
void RotateToLocal(const vtkRefractaGridFrame* grid, std::vector<float>& vectors);

// grad n along the grid axes (grid-local frame) by central differences, one-sided at the edges;
// `index` holds n per voxel (x fastest), the result 3 floats per voxel.
std::vector<float> CentralDifferenceGradient(
  const std::vector<float>& index, const int dims[3], const double spacing[3]);

// The environment map for the device: an image map as linear RGB floats (unsigned char divided
// by 255; non-finite or negative values as 0) and its size (W, H); a procedural checkerboard
// (vtkRefractaEnvironmentMap::GetChecker) as its two colours (6 floats) and squares (nu, nv),
// with `checker` true (how the kernel's REFRACTA_CHECKER_ENVIRONMENT reads them). False with
// `error` set for an image that is not W x H x 1 with 3- or 4-component point scalars.
bool EnvironmentToRGB(
  vtkImageData* image, std::vector<float>& rgb, int size[2], bool& checker, std::string& error);

// Whether a lighting point array has 3 components, `tuples` tuples and finite (and, when asked,
// non-negative) values; else false with `error` naming the array and what is wrong.
bool CheckLightingArray(
  vtkDataArray* array, const char* name, vtkIdType tuples, bool nonNegative, std::string& error);

// What a view-pass kernel is compiled for (each flag one -D option of Kernels/view_pass.cl).
struct KernelVariant
{
  bool Curved = false;         // REFRACTA_CURVED
  bool Parallel = false;       // REFRACTA_PARALLEL
  bool IndexVaries = false;    // REFRACTA_INDEX_WEIGHT (sources / n^2 per step)
  double UniformIndex = 1;     // else REFRACTA_SOURCE_SCALE = 1 / n^2 when n != 1
  bool Single = false;         // REFRACTA_HAS_SINGLE
  int RadianceLobes = 0;       // REFRACTA_RADIANCE_LOBES=K (K >= 2: S1 in K lobes)
  bool Multiple = false;       // REFRACTA_HAS_MULTIPLE
  bool MultipleDirection = false; // REFRACTA_MULTIPLE_DIRECTION (F / phi after S_ms)
  bool Emission = false;       // REFRACTA_HAS_EMISSION
  bool Packed = false;         // REFRACTA_PACKED_MEDIUM (grey extinction and emission, float4)
  bool Environment = false;    // REFRACTA_HAS_ENVIRONMENT
  bool Checker = false;        // REFRACTA_CHECKER_ENVIRONMENT (with Environment)
  bool DepthLimit = false;     // REFRACTA_HAS_DEPTH_LIMIT
  bool Skip = false;           // REFRACTA_SKIP
  bool Surfaces = false;       // REFRACTA_HAS_SURFACES
  bool NearestTexel = false;   // REFRACTA_SURFACE_NEAREST
  bool Dielectric = false;     // REFRACTA_DIELECTRIC (glass triangles)
  bool Sided = false;          // REFRACTA_SIDED_LOOKUPS (opaque surfaces cut the grid)
  int SplitDepth = 1;          // REFRACTA_SPLIT_DEPTH (interfaces where both legs are followed)
  int Caustic = 1;             // REFRACTA_CAUSTIC_SUBDIVISION (c > 1: the caustic atlas is read)
  long long CausticOffset = 0; // REFRACTA_CAUSTIC_OFFSET (atlas texels before the fine ones)
  bool LaneMarching = false;   // REFRACTA_VIEW_LANES: the kernel refracta_view_pass_lanes
};

// The build options of a kernel variant.
std::string KernelOptions(const KernelVariant& variant);

// Whether the eight-lane kernel (Kernels/view_lanes.cl) can render `variant` (no surfaces) on a
// device (not a GPU: it runs its rays in lanes of its own) for a grid of `voxels`
// voxels (its corner indices are 32-bit).
bool LaneMarchingApplies(const KernelVariant& variant, bool gpu, vtkIdType voxels);

// The environment's basis (vtkRefractaEnvironmentMap: right, up, front = up x right, in world)
// rotated into the grid-local frame by the linear part of `worldToLocal` and re-normalised:
// out[0] right, out[1] up, out[2] front, so the kernel's dot products are the world ones.
void EnvironmentBasisLocal(
  const double up[3], const double right[3], const double worldToLocal[4][4], double out[3][3]);

}

// How the view pass launches a kernel: the kernel and its name (for the profile), the work-group
// of side x side pixels and the pixels per work-item (8 for refracta_view_pass_lanes: work-groups
// of 1 x side items, each a row of 8 pixels).
struct vtkRefractaViewLaunch
{
  cl_kernel Kernel = nullptr;
  const char* Name = "refracta_view_pass";
  int GroupSide = 8;
  int PixelsPerItem = 1;
};

#endif
