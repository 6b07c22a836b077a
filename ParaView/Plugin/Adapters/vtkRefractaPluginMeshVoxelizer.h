/**
 * @class   vtkRefractaPluginMeshVoxelizer
 * @brief   vtkMeshVoxelizer with its materials and grid given as numbers (ParaView properties).
 *
 * This is vtkMeshVoxelizer itself (a subclass: the same voxelization, validation, smoothing and
 * output); it only adds setters that a ParaView proxy can call:
 * - SetMaterialParameters(connection, ...) gives the mesh on input connection `connection` a
 *   homogeneous vtkMediumMaterial from MATERIAL_VALUES numbers: refractive index (>= 1),
 *   extinction RGB (per world unit, >= 0), albedo RGB ([0, 1]), Henyey-Greenstein g
 *   ((-1, 1)), emission RGB (radiance per world unit, >= 0); RemoveAllMaterials() clears them
 *   (connections without a row get vacuum, as in vtkMeshVoxelizer).
 * - SetSurroundingMaterialParameters(...) the material outside every mesh (default vacuum).
 * - SetGridDimensions() and SetGridSpacing() store the two grid sizes without choosing the
 *   sizing mode, so that a proxy can push both and choose with SetSizingMode() (vtkMeshVoxelizer's
 *   SetDimensions()/SetSpacing() select their mode, which depends on the order they are called).
 *   A grid spacing of 0 in the SPACING mode is reported by vtkMeshVoxelizer as a bad grid.
 *
 * Bad meshes are reported by vtkMeshVoxelizer (once per execution) and leave the output without
 * arrays (on the requested extent); the execution then counts as done for the pipeline, so ParaView
 * does not run the filter (and repeat the message) again on every render until an input or a
 * property changes.
 */
#ifndef vtkRefractaPluginMeshVoxelizer_h
#define vtkRefractaPluginMeshVoxelizer_h

#include "RefractaParaViewAdaptersModule.h" // for export macro
#include "vtkMeshVoxelizer.h"

class REFRACTAPARAVIEWADAPTERS_EXPORT vtkRefractaPluginMeshVoxelizer : public vtkMeshVoxelizer
{
public:
  static vtkRefractaPluginMeshVoxelizer* New();
  vtkTypeMacro(vtkRefractaPluginMeshVoxelizer, vtkMeshVoxelizer);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Numbers per material row: n, extinction RGB, albedo RGB, g, emission RGB.
   */
  static constexpr int MATERIAL_VALUES = 11;

  /**
   * Homogeneous material of the mesh on input connection `connection` (see the class comment).
   */
  void SetMaterialParameters(int connection, double n, double extinctionR, double extinctionG,
    double extinctionB, double albedoR, double albedoG, double albedoB, double g, double emissionR,
    double emissionG, double emissionB);

  /**
   * Forget every material set so far (each connection falls back to vacuum).
   */
  void RemoveAllMaterials();

  /**
   * Homogeneous material outside every mesh. Default vacuum (1, 0 0 0, 0 0 0, 0, 0 0 0).
   */
  void SetSurroundingMaterialParameters(double n, double extinctionR, double extinctionG,
    double extinctionB, double albedoR, double albedoG, double albedoB, double g, double emissionR,
    double emissionG, double emissionB);

  /**
   * Voxels per axis used in the DIMENSIONS mode (each >= 1); default 64^3. Does not change the
   * sizing mode.
   */
  void SetGridDimensions(int nx, int ny, int nz);

  /**
   * Voxel size (world units) used in the SPACING mode; default (0, 0, 0) = unset. Does not change
   * the sizing mode.
   */
  void SetGridSpacing(double sx, double sy, double sz);

protected:
  vtkRefractaPluginMeshVoxelizer();
  ~vtkRefractaPluginMeshVoxelizer() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkRefractaPluginMeshVoxelizer(const vtkRefractaPluginMeshVoxelizer&) = delete;
  void operator=(const vtkRefractaPluginMeshVoxelizer&) = delete;
};

#endif
