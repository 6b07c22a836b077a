/**
 * @class   vtkMeshVoxelizer
 * @brief   Closed triangle meshes, each filled with a vtkMediumMaterial, into a Refracta medium.
 *
 * The Init pass of Sun et al. 2008 (section 4.1) and Bernabei et al. (section III-A): every mesh
 * on the repeatable input port 0 (one vtkPolyData per connection, AddInputData() or
 * AddInputConnection()) is paired with the material set by SetMaterial(connection, material);
 * the space outside every mesh holds the SurroundingMaterial (default vacuum: n = 1, nothing
 * else). The output is a vtkImageData whose point data carries every array of a medium
 * (vtkRefractaMedium): RefractiveIndex, RefractiveIndexGradient, Extinction, Albedo, Anisotropy,
 * Emission, Occupancy, all float, and which passes vtkMediumValidator.
 *
 * **Grid.** Voxel (i, j, k) is centred on point (i, j, k) and is a box of size `spacing` around
 * it (Documentation/Physics.md). The voxels cover the box given by Bounds when it is valid
 * (xmin < xmax etc.), else the union of the meshes' bounds grown by Padding (world units) on
 * every side. In the DIMENSIONS sizing mode (default, 64^3) the box is divided into Dimensions
 * voxels exactly; in the SPACING mode the grid has voxels of Spacing and ceil(extent / spacing)
 * voxels per axis, centred on the box. SetDimensions() and SetSpacing() select their mode. The
 * output's direction matrix is the identity. Because the grid depends on the meshes' bounds, the
 * inputs are brought up to date during RequestInformation when Bounds is not set.
 *
 * **Occupancy.** Each voxel box is sampled on a regular Supersampling^3 lattice (default 4^3,
 * as in the paper; samples at the centres of the sub-boxes). Only voxels whose box touches a
 * triangle (exact triangle-box test) are supersampled; every other voxel lies entirely on one
 * side of every surface and is classified by one sample. The inside test runs along grid lines
 * parallel to x: proper crossings with the triangles are found with exact orientation
 * predicates (CGAL), sorted, and counted (parity). A line that passes exactly through an edge
 * or vertex of a triangle's projection, or lies in a face, falls back to CGAL's
 * Side_of_triangle_mesh for its samples. A sample exactly on a surface counts as half inside
 * (so a face through voxel centres gives occupancy 1/2 there, never speckle).
 *
 * **Overlaps (innermost wins).** Where meshes nest (an elephant inside a sphere), each sample
 * belongs to the smallest-volume mesh that contains it; for equal volumes, the later
 * connection wins. The same rule decides partial overlaps: the overlap belongs to the mesh with
 * the smaller enclosed volume. A sample on the surface of the winning mesh is shared half and
 * half with the next mesh (or the surroundings). Occupancy is the fraction of the voxel inside
 * any mesh (never above 1).
 *
 * **Materials per voxel.** With f_m the fraction of the voxel owned by mesh m (and f_0 the
 * surroundings'), each material evaluated at the voxel centre (density fields, see
 * vtkMediumMaterial): n = sum f_m n_m; sigma_t = sum f_m sigma_t,m; sigma_s = sum f_m sigma_s,m
 * and Albedo = sigma_s / sigma_t per channel (so that scattering and absorption are both
 * conserved; occupancy-weighted albedo where sigma_t = 0); Anisotropy = sum w_m g_m / sum w_m
 * with w_m = f_m * mean sigma_s,m (the mean cosine of the mixed phase function;
 * occupancy-weighted where nothing scatters); Emission = sum f_m eps_m.
 *
 * **Smoothing and gradient** (InterfaceMode SMOOTHED_INDEX). n is smoothed by a separable Gaussian
 * of SmoothingWindow^3 voxels (default 9, odd; 1 disables smoothing) with sigma = SmoothingSigma
 * voxels (default 0, meaning window / 6 as in the paper), edge voxels replicated. RefractiveIndex
 * is the smoothed n; RefractiveIndexGradient its central differences in world units (one-sided at
 * the grid's faces). The other arrays are not smoothed.
 *
 * **Exact interfaces.** InterfaceMode EXACT_INTERFACES (the default; SMOOTHED_INDEX is the
 * paper's smoothing above, for comparison and for meshes meant as graded blobs) leaves n unsmoothed
 * and sets its gradient to 0 along an axis wherever the central-difference stencil touches a voxel
 * that a triangle touches, so that grad n never holds the jump at a surface; the jump is carried by
 * the meshes themselves, written to the output's field data
 * (vtkRefractaMedium::InterfacePointsName(), InterfaceTrianglesName(), InterfaceIndicesName():
 * world points, outward-wound triangles and per triangle the index inside and outside, outside
 * being the innermost other mesh whose volume contains the mesh's first vertex, or the
 * surroundings) for vtkRefractaSurfaceSet::AddMediumInterfaces, and InterfaceMaterialsName(): per
 * triangle the mesh's own medium (extinction, albedo, anisotropy, emission; flagged 0 for a
 * material with a density field), which the passes use inside the mesh instead of the grid's
 * occupancy mix (Physics.md "Glass bodies"). A mesh with the same index inside and outside
 * (index-matched: a fog blob with n = 1 in air) is no interface: it is left out, and its medium is
 * the grid's occupancy mix like SMOOTHED_INDEX's. A material whose index follows a density field
 * (DensityScalesRefractiveIndex) has no single index at its surface: then the grid is
 * SMOOTHED_INDEX, with a warning. vtkRefractaRenderPipeline (so the mapper, the CLI and ParaView)
 * adds the interfaces to the scene's surfaces by itself. Documentation/Physics.md, "Dielectric
 * interfaces".
 *
 * **Validation.** Each mesh is checked before voxelizing (CGAL and exact predicates); errors
 * (no output): null or empty mesh, cells that refer to missing points (ids out of range), NaN,
 * infinite or too large coordinates (beyond +-1e100), degenerate (collinear) faces,
 * open surfaces (boundary edges), non-manifold edges or vertices, non-orientable surfaces,
 * self-intersections (CheckSelfIntersections, default on), zero volume. Warnings (repaired):
 * polygons and strips triangulated, faces with a repeated vertex dropped, faces oriented
 * against their neighbours flipped, inside-out meshes flipped, line/vertex cells ignored.
 * Exactly coincident points are merged silently. Each message names the mesh (SetMeshName,
 * default the input connection). The output is validated (vtkMediumValidator) before it is
 * returned: a material coefficient times its density field that overflows a float is an error
 * naming the array and the first bad voxel, with an empty output.
 *
 * Multi-threaded with vtkSMPTools; reports progress. Timings of the last run per stage are
 * available (GetStageTime()).
 */
#ifndef vtkMeshVoxelizer_h
#define vtkMeshVoxelizer_h

#include "RefractaVoxelizeModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for vtkSmartPointer

#include <string> // for std::string
#include <vector> // for std::vector

#include "vtkMediumMaterial.h" // for vtkSmartPointer<vtkMediumMaterial> members

class REFRACTAVOXELIZE_EXPORT vtkMeshVoxelizer : public vtkImageAlgorithm
{
public:
  static vtkMeshVoxelizer* New();
  vtkTypeMacro(vtkMeshVoxelizer, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Material of the mesh on input connection `connection` (0-based). A connection without a
   * material gets a default vtkMediumMaterial (n = 1, nothing else). The material is
   * referenced, not copied.
   */
  void SetMaterial(int connection, vtkMediumMaterial* material);
  vtkMediumMaterial* GetMaterial(int connection);
  ///@}

  ///@{
  /**
   * What the messages call the mesh on input connection `connection` (0-based): a front end's
   * own name for it, e.g. refracta-render's key path `scene.medium.meshes[1]` and file name.
   * Default (or empty): "Input connection <connection>".
   */
  void SetMeshName(int connection, const std::string& name);
  std::string GetMeshName(int connection) const;
  ///@}

  ///@{
  /**
   * Material outside every mesh. Default: vacuum (a default vtkMediumMaterial). Setting nullptr
   * restores vacuum.
   */
  void SetSurroundingMaterial(vtkMediumMaterial* material);
  vtkMediumMaterial* GetSurroundingMaterial() { return this->SurroundingMaterial; }
  ///@}

  enum SizingModes
  {
    DIMENSIONS = 0,
    SPACING = 1
  };

  ///@{
  /**
   * DIMENSIONS (default): the grid has Dimensions voxels; SPACING: voxels of size Spacing.
   */
  vtkSetClampMacro(SizingMode, int, DIMENSIONS, SPACING);
  vtkGetMacro(SizingMode, int);
  void SetSizingModeToDimensions() { this->SetSizingMode(DIMENSIONS); }
  void SetSizingModeToSpacing() { this->SetSizingMode(SPACING); }
  ///@}

  ///@{
  /**
   * Number of voxels per axis (each >= 1); default 64^3. Also selects the DIMENSIONS mode.
   */
  void SetDimensions(int nx, int ny, int nz);
  void SetDimensions(const int n[3]) { this->SetDimensions(n[0], n[1], n[2]); }
  vtkGetVector3Macro(Dimensions, int);
  ///@}

  ///@{
  /**
   * Voxel size per axis (world units, each > 0); default (0, 0, 0) = unset. Also selects the
   * SPACING mode.
   */
  void SetSpacing(double sx, double sy, double sz);
  void SetSpacing(const double s[3]) { this->SetSpacing(s[0], s[1], s[2]); }
  vtkGetVector3Macro(Spacing, double);
  ///@}

  ///@{
  /**
   * Margin added on every side of the meshes' bounds (world units, >= 0); default 0. Ignored
   * when Bounds is valid. A margin of at least half the smoothing window keeps the smoothed
   * interface inside the grid.
   */
  void SetPadding(double value);
  vtkGetMacro(Padding, double);
  ///@}

  ///@{
  /**
   * Explicit box (xmin, xmax, ymin, ymax, zmin, zmax, world units) covered by the voxels. Used
   * when every min < max; default (0, -1, 0, -1, 0, -1): use the meshes' bounds and Padding.
   */
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /**
   * Samples per voxel and axis for fractional occupancy, in [1, 16]; default 4 (64 samples).
   */
  vtkSetClampMacro(Supersampling, int, 1, 16);
  vtkGetMacro(Supersampling, int);
  ///@}

  ///@{
  /**
   * When on (default), only voxels whose box touches a triangle are supersampled (the others
   * are entirely inside or outside, so the result is identical). Off supersamples every voxel
   * (for benchmarks).
   */
  vtkSetMacro(SupersampleSurfaceOnly, bool);
  vtkGetMacro(SupersampleSurfaceOnly, bool);
  vtkBooleanMacro(SupersampleSurfaceOnly, bool);
  ///@}

  ///@{
  /**
   * Width of the Gaussian smoothing window of n in voxels, odd, in [1, 63]; default 9. Values
   * outside are clamped; an even value is an error that keeps the window (as the scene file
   * refuses it). 1 disables smoothing.
   */
  void SetSmoothingWindow(int value);
  vtkGetMacro(SmoothingWindow, int);
  ///@}

  ///@{
  /**
   * Standard deviation of the Gaussian in voxels (>= 0); default 0, meaning window / 6.
   */
  void SetSmoothingSigma(double value);
  vtkGetMacro(SmoothingSigma, double);
  ///@}

  ///@{
  /**
   * Reject self-intersecting meshes (CGAL, O(n log n)); default on.
   */
  vtkSetMacro(CheckSelfIntersections, bool);
  vtkGetMacro(CheckSelfIntersections, bool);
  vtkBooleanMacro(CheckSelfIntersections, bool);
  ///@}

  enum InterfaceModes
  {
    SMOOTHED_INDEX = 0,  ///< n smoothed across the meshes' surfaces (the paper)
    EXACT_INTERFACES = 1 ///< the meshes are exact dielectric interfaces (the default)
  };

  ///@{
  /**
   * EXACT_INTERFACES (default) or SMOOTHED_INDEX (see the class description).
   */
  vtkSetClampMacro(InterfaceMode, int, SMOOTHED_INDEX, EXACT_INTERFACES);
  vtkGetMacro(InterfaceMode, int);
  void SetInterfaceModeToSmoothedIndex() { this->SetInterfaceMode(SMOOTHED_INDEX); }
  void SetInterfaceModeToExactInterfaces() { this->SetInterfaceMode(EXACT_INTERFACES); }
  ///@}

  /**
   * Whether the last execution wrote exact interfaces (EXACT_INTERFACES, no density-scaled
   * index, and at least one mesh with another index inside than outside).
   */
  vtkGetMacro(WroteInterfaces, bool);

  enum Stages
  {
    STAGE_VALIDATION = 0, ///< mesh checks and repairs (CGAL)
    STAGE_ALLOCATION,     ///< allocating and first-touching the output arrays (page faults)
    STAGE_INSIDE,         ///< one-sample inside test of every voxel, surface voxel detection
    STAGE_SUPERSAMPLING,  ///< fractional occupancy and materials of the surface voxels
    STAGE_MATERIALS,      ///< materials of the voxels entirely inside or outside
    STAGE_SMOOTHING,      ///< Gaussian smoothing of n
    STAGE_GRADIENT,       ///< central differences of n
    NUMBER_OF_STAGES
  };

  /**
   * Wall-clock seconds the last execution spent in a stage (Stages), or -1 for a bad id.
   */
  double GetStageTime(int stage) const;

  /**
   * Name of a stage, e.g. "inside", or nullptr for a bad id.
   */
  static const char* GetStageName(int stage);

  /**
   * Voxels supersampled in the last execution.
   */
  vtkGetMacro(NumberOfSupersampledVoxels, vtkIdType);

  /**
   * Grid lines of the last execution whose parity was ambiguous (through an edge or vertex) and
   * that used CGAL's Side_of_triangle_mesh instead.
   */
  vtkGetMacro(NumberOfFallbackLines, vtkIdType);

  /**
   * Modification time including the materials'.
   */
  vtkMTimeType GetMTime() override;

protected:
  vtkMeshVoxelizer();
  ~vtkMeshVoxelizer() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  bool CheckOutputValues(vtkImageData* output);

  /**
   * Grid for the given meshes' bounds (xmin, xmax, ...): dimensions, origin, spacing. Returns
   * false with a reason when no grid can be made.
   */
  bool ComputeGrid(const double meshBounds[6], int dims[3], double origin[3], double spacing[3],
    std::string& why) const;

  std::vector<vtkSmartPointer<vtkMediumMaterial>> Materials;
  std::vector<std::string> MeshNames;
  vtkSmartPointer<vtkMediumMaterial> SurroundingMaterial;
  int SizingMode = DIMENSIONS;
  int Dimensions[3] = { 64, 64, 64 };
  double Spacing[3] = { 0.0, 0.0, 0.0 };
  double Padding = 0.0;
  double Bounds[6] = { 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 };
  int Supersampling = 4;
  bool SupersampleSurfaceOnly = true;
  int SmoothingWindow = 9;
  double SmoothingSigma = 0.0;
  bool CheckSelfIntersections = true;
  int InterfaceMode = EXACT_INTERFACES;
  bool WroteInterfaces = false;
  double StageTimes[NUMBER_OF_STAGES] = {};
  vtkIdType NumberOfSupersampledVoxels = 0;
  vtkIdType NumberOfFallbackLines = 0;

private:
  vtkMeshVoxelizer(const vtkMeshVoxelizer&) = delete;
  void operator=(const vtkMeshVoxelizer&) = delete;
};

#endif
