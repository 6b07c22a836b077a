/**
 * @class   vtkRefractaDielectric
 * @brief   The optics of a dielectric interface on the host: Fresnel reflectance (unpolarised),
 *          mirror reflection, Snell refraction and the reflect-or-refract choice.
 *
 * The twin, step for step in double, of the functions of Kernels/refracta_surfaces.cl
 * (refracta_fresnel_reflectance, refracta_reflect, refracta_refract, refracta_dielectric_sample)
 * for the CPU passes (the reference renderer) and the tests. Documentation/Physics.md,
 * "Dielectric interfaces", gives the conventions: directions and normals are unit vectors, the
 * winding normal of an interface points outside (to the side of nOutside).
 *
 * Static methods only; the class is never instantiated by the passes.
 */
#ifndef vtkRefractaDielectric_h
#define vtkRefractaDielectric_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkObject.h"

class REFRACTACORE_EXPORT vtkRefractaDielectric : public vtkObject
{
public:
  static vtkRefractaDielectric* New();
  vtkTypeMacro(vtkRefractaDielectric, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Unpolarised Fresnel reflectance from index etaI into etaT at cos(incidence) cosI (clamped to
   * [0, 1]): (Rs + Rp) / 2; exactly 1 from the critical angle on (total internal reflection).
   */
  static double FresnelReflectance(double cosI, double etaI, double etaT);

  /**
   * Mirror direction r of d about the unit normal n.
   */
  static void Reflect(const double d[3], const double n[3], double r[3]);

  /**
   * Snell's law for unit d and the unit normal nf facing it (d . nf < 0), eta = etaI / etaT:
   * false (t untouched) under total internal reflection, else t the unit refracted direction.
   */
  static bool Refract(const double d[3], const double nf[3], double eta, double t[3]);

  /**
   * Result of Sample().
   */
  struct Event
  {
    double Direction[3]; ///< unit outgoing direction
    bool Transmitted;    ///< refracted (true) or reflected
    double Reflectance;  ///< the Fresnel R used: the probability of the reflected branch
    double EtaFrom;      ///< index on the incident side
    double EtaTo;        ///< index on the other side
  };

  /**
   * One choice at an interface: unit d meets a triangle with unit winding normal ng and shading
   * normal ns, between nInside and nOutside; xi uniform in [0, 1). Reflected when xi < R (Fresnel
   * with the shading normal), else refracted; redone about ng when the shading normal would
   * send the ray to the wrong side of the plane (see refracta_dielectric_sample).
   */
  static Event Sample(const double d[3], const double ng[3], const double ns[3], double nInside,
    double nOutside, double xi);

protected:
  vtkRefractaDielectric() = default;
  ~vtkRefractaDielectric() override = default;

private:
  vtkRefractaDielectric(const vtkRefractaDielectric&) = delete;
  void operator=(const vtkRefractaDielectric&) = delete;
};

#endif
