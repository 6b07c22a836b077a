/**
 * @file    vtkRefractaSettings.h
 * @brief   Setters of floating-point settings that refuse NaN: vtkSetClampMacro's semantics,
 *          with an error instead of a silent NaN.
 *
 * VTK's vtkSetClampMacro lets NaN through (neither comparison with the bounds holds), and a NaN
 * step size, exposure or tolerance renders a black image or runs forever without a word. Every
 * Refracta class declares such setters as plain methods (`void SetStepSize(double);`, which the
 * wrappers read like any method) and defines them with the macros below:
 *
 * @code
 * vtkRefractaCxxSetClampMacro(vtkRefractaViewPass, StepSize, 0.01, 16.0);
 * vtkRefractaCxxSetVector3Macro(vtkRefractaViewPass, BackgroundColor);
 * @endcode
 *
 * A finite value (or an infinite one, for a range) is clamped into [lo, hi] as vtkSetClampMacro
 * does; a NaN, or a non-finite component of a vector, is an error (vtkErrorMacro on the object,
 * naming the setter, the value and what would be valid) and leaves the setting unchanged.
 */
#ifndef vtkRefractaSettings_h
#define vtkRefractaSettings_h

#ifndef __VTK_WRAP__

#include "RefractaCoreModule.h" // for export macro

class vtkObject;

namespace vtkRefractaSettings
{
/**
 * Clamps `value` into [lo, hi] and stores it in `target`; NaN is an error on `caller` naming
 * Set<property>. Returns whether `target` changed (the caller then calls Modified()).
 */
REFRACTACORE_EXPORT bool SetClamped(
  vtkObject* caller, const char* property, double& target, double value, double lo, double hi);

/**
 * The same per component of a 3-vector; a component that is not finite is an error and leaves
 * all three unchanged.
 */
REFRACTACORE_EXPORT bool SetClamped3(vtkObject* caller, const char* property, double target[3],
  const double value[3], double lo, double hi);
}

#define vtkRefractaCxxSetClampMacro(cls, name, lo, hi)                                             \
  void cls::Set##name(double value)                                                                \
  {                                                                                                \
    if (vtkRefractaSettings::SetClamped(this, #name, this->name, value, lo, hi))                   \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }

#define vtkRefractaCxxSetVector3Macro(cls, name)                                                   \
  void cls::Set##name(double x, double y, double z)                                                \
  {                                                                                                \
    const double value[3] = { x, y, z };                                                           \
    if (vtkRefractaSettings::SetClamped3(                                                          \
          this, #name, this->name, value, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX))                        \
    {                                                                                              \
      this->Modified();                                                                            \
    }                                                                                              \
  }                                                                                                \
  void cls::Set##name(const double value[3])                                                       \
  {                                                                                                \
    this->Set##name(value[0], value[1], value[2]);                                                 \
  }

#endif // __VTK_WRAP__
#endif
