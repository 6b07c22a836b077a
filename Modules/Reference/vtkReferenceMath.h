/**
 * Internal to RefractaReference (a private header: not wrapped, not installed). The double
 * precision vector of the reference renderer, GLM's glm::dvec3, and the few helpers GLM lacks.
 *
 * glm::dot, glm::cross and glm::length evaluate exactly as the hand-written vector they replaced
 * (same products, same order of the sums, sqrt(dot)), so the renderer's output is bit-identical.
 * glm::dvec3's default constructor leaves the components uninitialised: write Vec3(0.0).
 */
#ifndef vtkReferenceMath_h
#define vtkReferenceMath_h

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <limits>

namespace refracta
{
namespace reference
{
using Vec3 = glm::dvec3;

constexpr double Pi = 3.14159265358979323846;
constexpr double Inf = std::numeric_limits<double>::infinity();

/// The vector (p[0], p[1], p[2]).
inline Vec3 ToVec3(const double* p)
{
  return Vec3(p[0], p[1], p[2]);
}

/// a / |a|, or (0, 0, 1) for the zero vector. Not glm::normalize: that multiplies by
/// inversesqrt (the same arithmetic) but has no zero check.
inline Vec3 Normalized(const Vec3& a)
{
  const double l = glm::length(a);
  return l > 0 ? (1.0 / l) * a : Vec3(0, 0, 1);
}

/// 1 - cos of the angle between unit vectors, without cancellation near 0: |a - b|^2 / 2.
inline double OneMinusCos(const Vec3& a, const Vec3& b)
{
  const Vec3 d = a - b;
  return 0.5 * glm::dot(d, d);
}

/// Orthonormal basis (t, b) completing the unit vector n (Duff et al. 2017, branchless).
inline void Basis(const Vec3& n, Vec3& t, Vec3& b)
{
  const double s = std::copysign(1.0, n.z);
  const double a = -1.0 / (s + n.z);
  const double c = n.x * n.y * a;
  t = Vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = Vec3(c, s + n.y * n.y * a, -n.y);
}
} // namespace reference
} // namespace refracta

#endif
