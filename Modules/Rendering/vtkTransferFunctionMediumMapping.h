// Private to vtkTransferFunctionMedium (not installed): the medium values of one input tuple
// through a vtkVolumeProperty's transfer functions, for the component layouts VTK's volume
// mappers read (vtkVolumeProperty::IndependentComponents):
// - one component: its opacity, colour (or grey) and index functions;
// - independent components (2 to 4, IndependentComponents on, VTK's default): component c through
//   the property's functions of index c, weighted by ComponentWeight c, as a mixture of species:
//   extinctions add, the albedo is the mixture's (scattering over extinction), emissions add; a
//   species of weight 0 or with a NaN value is left out;
// - two dependent components (IndependentComponents off): the colour function of component 0,
//   the opacity function of component 1;
// - four dependent components: RGB given directly by components 0..2 (integer types divided by
//   their type's maximum, floats taken as they are), the opacity function of component 3.
// The refractive index function reads the component that drives the opacity (0 for independent
// components).
#ifndef vtkTransferFunctionMediumMapping_h
#define vtkTransferFunctionMediumMapping_h

#include <mutex>  // for the colour lock
#include <string> // for messages

class vtkColorTransferFunction;
class vtkDataArray;
class vtkPiecewiseFunction;
class vtkVolumeProperty;

namespace vtkTransferFunctionMediumDetail
{
// The transfer functions of one component of the property.
struct ComponentFunctions
{
  vtkPiecewiseFunction* Opacity = nullptr;
  vtkColorTransferFunction* Colour = nullptr; // nullptr: Grey
  vtkPiecewiseFunction* Grey = nullptr;
  double Unit = 1.0;   // ScalarOpacityUnitDistance (world units)
  double Weight = 1.0; // ComponentWeight (independent components)
};

class TupleMapping
{
public:
  enum Layout
  {
    SINGLE,
    INDEPENDENT,
    COLOUR_OPACITY, // two dependent components
    RGB_OPACITY     // four dependent components
  };

  // The layout of `scalars` under `property`, or false with `why` saying what would be valid.
  bool Configure(vtkVolumeProperty* property, vtkDataArray* scalars, vtkPiecewiseFunction* index,
    double emissionScale, std::string& why);

  // The functions of every component used (ParaView's colour maps rebuild themselves in
  // GetColor(): built here once, then evaluated under ColourLock).
  void PrepareColourFunctions(std::mutex* lock);

  // The values at tuple `s` (GetNumberOfComponents() values, all finite): true, or false with
  // `why` (non-finite or out-of-range results, what would be valid; built only on failure).
  bool Map(const double* s, std::string& why);

  int GetNumberOfComponents() const { return this->Components; }

  // Whether tuple `s` is missing data (empty space): a NaN in a component it reads; independent
  // components: every component of non-zero weight NaN (a NaN species is left out of the mix).
  bool IsMissing(const double* s) const;
  // Whether a component it reads (of non-zero weight) is infinite: an error.
  bool HasInfinite(const double* s) const;
  // Whether the unit distance of every component used is finite and > 0; else false with `why`.
  bool CheckUnitDistances(std::string& why) const;

  // The last Map()'s results.
  double Sigma = 0.0;               // extinction (1 / world unit)
  double Albedo[3] = { 0, 0, 0 };   // in [0, 1]
  double Emission[3] = { 0, 0, 0 }; // EmissionScale x colour x sigma, summed over species
  double RefractiveIndex = 1.0;     // >= 1

private:
  // One component through functions f: extinction and colour (none when `colour` is nullptr).
  // `component` names the property's functions in messages (-1: one set of functions).
  bool MapComponent(double s, const ComponentFunctions& f, int component, double& sigma,
    double colour[3], std::string& why);
  // Whether component c takes part (independent components of weight 0 do not).
  bool Reads(int c) const
  {
    return this->Mode == INDEPENDENT ? this->Functions[c].Weight > 0 : (c < this->Components);
  }
  bool MapIndex(double s, std::string& why);
  // Whether the extinction and emission fit a float; else false with `why` (at scalar s).
  bool CheckRange(double s, std::string& why) const;

  Layout Mode = SINGLE;
  int Components = 1;
  ComponentFunctions Functions[4];
  vtkPiecewiseFunction* Index = nullptr;
  double EmissionScale = 0.0;
  double ColourScale = 1.0; // RGB_OPACITY: 1 / the integer type's maximum, or 1
  std::mutex* ColourLock = nullptr;
};
}

#endif
