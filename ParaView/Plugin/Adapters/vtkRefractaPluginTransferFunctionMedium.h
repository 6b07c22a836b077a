/**
 * @class   vtkRefractaPluginTransferFunctionMedium
 * @brief   vtkTransferFunctionMedium driven by ParaView's colour map, opacity function and array
 *          selection.
 *
 * vtkTransferFunctionMedium reads the active point scalars through a vtkVolumeProperty. ParaView
 * hands a filter its transfer functions as separate objects (the colour map, a
 * vtkColorTransferFunction such as vtkPVDiscretizableColorTransferFunction; the opacity, a
 * vtkPiecewiseFunction) and the array as the filter's input array to process. This filter puts
 * them into a vtkVolumeProperty, makes the selected point or cell array the active scalars of a
 * shallow copy of the input, and runs vtkTransferFunctionMedium on it; the output is that
 * filter's output (the medium's arrays, on the input's grid, or on the grid of its cells' centres
 * for a cell array). The mapping, its units and its errors are
 * vtkTransferFunctionMedium's.
 *
 * Knobs (defaults): ColorTransferFunction (nullptr: albedo from vtkVolumeProperty's default, grey
 * ramp), ScalarOpacityFunction (required), ScalarOpacityUnitDistance (world units, > 0, default
 * 1: the thickness the opacity function refers to), Anisotropy (Henyey-Greenstein g, default 0),
 * EmissionScale (default 0), RefractiveIndexFunction (scalar -> n, nullptr: n = 1).
 *
 * Bad input (no selected point or cell array, a field array, no opacity function):
 * vtkErrorMacro naming it, empty output.
 */
#ifndef vtkRefractaPluginTransferFunctionMedium_h
#define vtkRefractaPluginTransferFunctionMedium_h

#include "RefractaParaViewAdaptersModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for members

class vtkColorTransferFunction;
class vtkPiecewiseFunction;
class vtkTransferFunctionMedium;
class vtkVolumeProperty;

class REFRACTAPARAVIEWADAPTERS_EXPORT vtkRefractaPluginTransferFunctionMedium
  : public vtkImageAlgorithm
{
public:
  static vtkRefractaPluginTransferFunctionMedium* New();
  vtkTypeMacro(vtkRefractaPluginTransferFunctionMedium, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Scalar -> albedo (RGB). Default nullptr.
   */
  void SetColorTransferFunction(vtkColorTransferFunction* function);
  vtkColorTransferFunction* GetColorTransferFunction();
  ///@}

  ///@{
  /**
   * Scalar -> opacity of a slab ScalarOpacityUnitDistance thick. Required.
   */
  void SetScalarOpacityFunction(vtkPiecewiseFunction* function);
  vtkPiecewiseFunction* GetScalarOpacityFunction();
  ///@}

  ///@{
  /**
   * Scalar -> refractive index (>= 1). Default nullptr: n = 1.
   */
  void SetRefractiveIndexFunction(vtkPiecewiseFunction* function);
  vtkPiecewiseFunction* GetRefractiveIndexFunction();
  ///@}

  ///@{
  /**
   * World units; clamped to >= 1e-12. Default 1.
   */
  void SetScalarOpacityUnitDistance(double distance);
  double GetScalarOpacityUnitDistance();
  ///@}

  ///@{
  /**
   * Forwarded to vtkTransferFunctionMedium (Henyey-Greenstein g, default 0; emission scale,
   * default 0).
   */
  void SetAnisotropy(double g);
  double GetAnisotropy();
  void SetEmissionScale(double scale);
  double GetEmissionScale();
  ///@}

  /**
   * The vtkTransferFunctionMedium this filter runs.
   */
  vtkTransferFunctionMedium* GetMediumFilter();

  vtkMTimeType GetMTime() override;

protected:
  vtkRefractaPluginTransferFunctionMedium();
  ~vtkRefractaPluginTransferFunctionMedium() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkSmartPointer<vtkTransferFunctionMedium> Medium;
  vtkSmartPointer<vtkVolumeProperty> Property;
  vtkSmartPointer<vtkPiecewiseFunction> ScalarOpacity; // what was set (the property makes one)

private:
  vtkRefractaPluginTransferFunctionMedium(const vtkRefractaPluginTransferFunctionMedium&) = delete;
  void operator=(const vtkRefractaPluginTransferFunctionMedium&) = delete;
};

#endif
