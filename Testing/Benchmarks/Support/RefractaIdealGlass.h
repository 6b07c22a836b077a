/**
 * @file    RefractaIdealGlass.h
 * @brief   Ideal geometric optics of refracta-render's default scene (issue 20): the exact glass
 *          sphere, Snell's law and unpolarised Fresnel at both surfaces, the spot light; the
 *          light through the ball as straight beams, which BenchmarkGlassOptics bins on the
 *          floor (the caustic) and in the fog (the light shaft below the ball).
 *
 * Units are the scene's world units; powers are for a spot light of intensity I0 = 1 on its axis
 * (I(theta) = cos(theta) within 12 degrees), so every figure computed from them is a ratio or is
 * scaled by the light's real intensity.
 */
#ifndef RefractaIdealGlass_h
#define RefractaIdealGlass_h

#include <array>
#include <functional>
#include <vector>

namespace RefractaIdealGlass
{
using V3 = std::array<double, 3>;

/// The default scene's ball, floor, light and fog.
extern const V3 BallCentre;      ///< (0, 0.05, 0)
extern const double BallRadius;  ///< 0.42
extern const double Index;       ///< 1.5
extern const double FloorY;      ///< -0.8 (the floor plane y = -0.8)
extern const V3 LightPosition;   ///< (0, 3, 0), pointing straight down
extern const double ConeDegrees; ///< 12
/// The medium's box (the voxelizer's bounds): fog exists only inside it.
extern const double BoxMin[3], BoxMax[3];

V3 Add(const V3& a, const V3& b, double s = 1.0);
double Dot(const V3& a, const V3& b);
V3 Unit(V3 a);

/// Unpolarised Fresnel reflectance for cosine cosI of incidence from index etaI into etaT (1
/// past the critical angle).
double Fresnel(double cosI, double etaI, double etaT);

/// Distance along the unit d from o to the sphere (its far side when `inside`); < 0: none.
double HitBall(const V3& o, const V3& d, bool inside);

/// Spot intensity (I0 = 1) in the direction d: -d_y within the cone, 0 outside.
double SpotIntensity(const V3& d);

/// Length of the part of the ray o + t d, 0 <= t <= tMax, inside the medium's box.
double LengthInBox(const V3& o, const V3& d, double tMax);

/// A straight piece of light outside the ball after it met the ball: from Origin along the unit
/// Direction, carrying Power (I0 = 1 times its solid angle at the light, times the Fresnel
/// weights, times the fog's transmittance from the box's top to the ball); the fog's attenuation
/// along the piece itself is left to the user.
struct Beam
{
  V3 Origin;
  V3 Direction;
  double Power;
};

/**
 * Traces the light's rays that meet the ball, rays x rays directions stratified over the cone
 * (uniform in the cosine and the azimuth, so each carries I(theta) d omega), through the exact
 * sphere, following both Fresnel branches up to `depth` interfaces, and calls `visit` for every
 * piece that leaves the ball for good (and every piece outside it when the depth runs out).
 * `fogExtinction` (sigma_t of the fog in the box, 0 for none) attenuates the first piece, from
 * the box's top to the ball; the glass's own extinction is neglected (0.02 / unit, 1.7% through
 * the ball's centre).
 */
void TraceThroughBall(
  int rays, int depth, double fogExtinction, const std::function<void(const Beam&)>& visit);

/// The default scene's fog (inside the box, outside the ball).
struct Fog
{
  double Extinction = 0.35; ///< sigma_t per unit length
  double Albedo = 0.9;      ///< sigma_s / sigma_t
  double Anisotropy = 0.3;  ///< Henyey-Greenstein g
};

/// Henyey-Greenstein phase function (per steradian) of the cosine between travel directions.
double PhaseHG(double g, double cosTheta);

/// A pinhole camera of Size x Size square pixels, pixel (i, j) covering [i, i + 1) x [j, j + 1)
/// in pixel coordinates, row 0 at the bottom; Tan = tan(vertical view angle / 2).
struct Pinhole
{
  V3 Eye, Forward, Right, Up;
  double Tan = 0;
  int Size = 0;
  V3 Ray(double x, double y) const; ///< unit direction through pixel coordinates (x, y)
  /// Pixel coordinates of a world point; false when it is behind the eye.
  bool Project(const V3& p, double& x, double& y) const;
  double PixelSolidAngle(int i, int j) const; ///< steradians
};

/**
 * The shaft: light through the ball in the fog, from Beam pieces (TraceThroughBall with the fog's
 * extinction). Each piece runs from the ball to the floor or out of the box, attenuated by the
 * fog along it. Two results:
 * - Image: the single-scattered radiance per pixel (thin fog: the integral along the pixel's view
 *   rays of T_view sigma_s p(g, cos) phi), the mean over each pixel, computed per beam as
 *   sum sigma_s p w T_light T_view ds / r^2 / Omega_pixel at sub-pixel steps ds (the beam's
 *   scattered intensity seen from the eye at distance r; cos between the beam's direction and the
 *   direction to the eye). Pixels whose view rays meet the ball are not special-cased.
 * - Planes: the fluence phi(x, z) on horizontal planes y = Heights[k], phi = sum w T / |d_y| / c^2
 *   over the pieces crossing a cell c x c (cells centred on multiples of c), in the band
 *   |x| <= HalfWidth, |z| <= HalfDepth; and per plane the fluence integrated over rings of width
 *   RingWidth about the axis (sum w T / |d_y|, out to HalfWidth), for EncircledRadius().
 */
class IdealShaft
{
public:
  IdealShaft(const Pinhole& camera, const Fog& fog, const std::vector<double>& heights, double cell,
    double halfWidth, double halfDepth);
  void AddToPlanes(const Beam& beam);
  void AddToImage(const Beam& beam);
  /// Divides the image by the pixels' solid angles and the planes by the cells' areas; call once.
  void Finish();

  std::vector<double> Image;
  std::vector<double> Heights;
  std::vector<std::vector<double>> Planes; ///< per height: cell (i, k) at i + Nx * k
  std::vector<std::vector<double>> Rings;  ///< per height: integral of phi over each ring
  double RingWidth = 0.001;
  double Cell;
  int Nx, Nz; ///< cells along x and z (odd: the middle one is centred on the axis)

  /// Fluence at cell (i, k) of plane `plane` (after Finish()).
  double Phi(int plane, int i, int k) const { return this->Planes[plane][i + this->Nx * k]; }

  /// The radius about the axis within which plane `plane` holds `fraction` of the integral of phi
  /// out to HalfWidth (linear within a ring).
  double EncircledRadius(int plane, double fraction) const;

  /// phi along x at z = 0 on plane `plane` as a lattice of spacing h with points at (i + 1/2) h
  /// (symmetric about the axis, as the render's) would hold it: the mean over each voxel's h x h
  /// square (the photons' deposit), the photon pass's (1, 2, 1) / 4 smoothing along x and z, and
  /// linear interpolation to z = 0 (the mean of z = +-h/2); not averaged along y. Needs
  /// HalfDepth >= 2 h.
  std::vector<double> ProfileOnLattice(int plane, double h) const;

private:
  Pinhole Camera;
  Fog Medium;
  void Splat(const Beam& beam, double length);
  static double Length(const Beam& beam); ///< to the floor or out of the box
};
}

#endif
