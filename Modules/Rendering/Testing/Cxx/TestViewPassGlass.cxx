// Glass (dielectric surfaces) in the view pass (Kernels/view_pass.cl, REFRACTA_DIELECTRIC).
//
// Every image is compared with an independent double-precision trace written here: ray-triangle
// tests on the same meshes, corner normals computed from the meshes (area-weighted face normals
// within 30 degrees, Physics.md), Snell's law and the unpolarised Fresnel reflectance from their
// textbook formulas, both legs followed at every interface to depth 12.
// - A glass ball (n = 1.5) in front of a checker floor, seen from above and obliquely ("glass
//   over a floor"): pixel by pixel against the trace; the error and time of each
//   DielectricSplitDepth (0..3) against the trace are printed (Physics.md's table).
// - A glass block under a grazing camera, with a black plane inside it: every pixel on its top
//   face is R(theta) B exactly (B the background), R the Fresnel formula at the pixel's angle.
// - A right-angle prism: rays entering its top face meet the hypotenuse at 45 degrees (beyond the
//   critical 41.8 degrees): total internal reflection turns them onto a wall beside the prism;
//   the bright floor under the prism leaks in nothing; pixel by pixel against the trace.
// - No NaN or Inf anywhere.
#include "SurfaceTestScene.h"

#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkFieldData.h"
#include "vtkMath.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkRefractaViewPass.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
using Vec = std::array<double, 3>;

Vec Add(const Vec& a, const Vec& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
Vec Sub(const Vec& a, const Vec& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
Vec Mul(double s, const Vec& a)
{
  return { s * a[0], s * a[1], s * a[2] };
}
double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec Cross(const Vec& a, const Vec& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
Vec Unit(const Vec& a)
{
  return Mul(1.0 / std::sqrt(Dot(a, a)), a);
}

// Textbook unpolarised Fresnel reflectance from etaI into etaT at incidence cos c (1 under TIR).
double Fresnel(double c, double etaI, double etaT)
{
  const double s2 = (etaI / etaT) * (etaI / etaT) * (1 - c * c);
  if (s2 >= 1)
  {
    return 1;
  }
  const double ct = std::sqrt(1 - s2);
  const double rs = (etaI * c - etaT * ct) / (etaI * c + etaT * ct);
  const double rp = (etaI * ct - etaT * c) / (etaI * ct + etaT * c);
  return 0.5 * (rs * rs + rp * rp);
}

// One triangle of the reference scene.
struct Tri
{
  Vec p[3];
  Vec n[3];      // corner normals (glass), outward
  bool glass;    // dielectric (inside 1.5, outside 1) or Lambertian with radiance `albedo`
  double albedo; // radiance of a Lambertian triangle (E = pi in the tests, so L = rho)
};

// A mesh as triangles with corner normals: area-weighted mean of the face normals at the point,
// kept within 30 degrees of the face normal, else the face normal (smooth = false: face normals).
void AddMesh(vtkPolyData* mesh, bool glass, double albedo, bool smooth, std::vector<Tri>& out)
{
  const vtkIdType np = mesh->GetNumberOfPoints();
  std::vector<Vec> pointNormal(np, Vec{ 0, 0, 0 });
  std::vector<std::array<vtkIdType, 3>> cells;
  vtkCellArray* polys = mesh->GetPolys();
  vtkIdType n;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    if (n != 3)
    {
      continue;
    }
    cells.push_back({ ids[0], ids[1], ids[2] });
    Vec p[3];
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(ids[k], p[k].data());
    }
    const Vec area = Cross(Sub(p[1], p[0]), Sub(p[2], p[0])); // twice the area, times the normal
    for (int k = 0; k < 3; ++k)
    {
      pointNormal[ids[k]] = Add(pointNormal[ids[k]], area);
    }
  }
  for (const auto& c : cells)
  {
    Tri t;
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(c[k], t.p[k].data());
    }
    const Vec face = Unit(Cross(Sub(t.p[1], t.p[0]), Sub(t.p[2], t.p[0])));
    for (int k = 0; k < 3; ++k)
    {
      const Vec m = Unit(pointNormal[c[k]]);
      t.n[k] = smooth && Dot(m, face) >= std::cos(vtkMath::RadiansFromDegrees(30.0)) ? m : face;
    }
    t.glass = glass;
    t.albedo = albedo;
    out.push_back(t);
  }
}

// Moller-Trumbore in double; t in (1e-9, best).
bool HitTriangle(const Tri& tri, const Vec& o, const Vec& d, double& t, double& u, double& v)
{
  const Vec e1 = Sub(tri.p[1], tri.p[0]), e2 = Sub(tri.p[2], tri.p[0]);
  const Vec p = Cross(d, e2);
  const double det = Dot(e1, p);
  if (std::abs(det) < 1e-15)
  {
    return false;
  }
  const Vec s = Sub(o, tri.p[0]);
  u = Dot(s, p) / det;
  const Vec q = Cross(s, e1);
  v = Dot(d, q) / det;
  t = Dot(e2, q) / det;
  return u >= 0 && v >= 0 && u + v <= 1 && t > 1e-9;
}

struct Reference
{
  std::vector<Tri> tris;
  double background = 0;
  int tirEvents = 0; // interfaces where the trace met total internal reflection
  // A sphere bounding the glass triangles: rays that miss it skip them (speed only).
  Vec glassCentre{ 0, 0, 0 };
  double glassRadius = -1;

  void BoundGlass()
  {
    Vec lo{ 1e300, 1e300, 1e300 }, hi{ -1e300, -1e300, -1e300 };
    for (const Tri& tri : this->tris)
    {
      for (int k = 0; tri.glass && k < 3; ++k)
      {
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = std::min(lo[a], tri.p[k][a]);
          hi[a] = std::max(hi[a], tri.p[k][a]);
        }
      }
    }
    this->glassCentre = Mul(0.5, Add(lo, hi));
    this->glassRadius = 0.5 * std::sqrt(Dot(Sub(hi, lo), Sub(hi, lo))) * 1.001 + 1e-9;
  }

  bool MayHitGlass(const Vec& o, const Vec& d) const
  {
    const Vec oc = Sub(o, this->glassCentre);
    const double b = Dot(oc, d), c = Dot(oc, oc) - this->glassRadius * this->glassRadius;
    return c <= 0 || (b < 0 && b * b >= c);
  }

  // Radiance along o + t d (one channel: the scenes are grey).
  double Trace(const Vec& o, const Vec& d, int depth)
  {
    double best = 1e300, bu = 0, bv = 0;
    const Tri* hit = nullptr;
    if (this->glassRadius < 0)
    {
      this->BoundGlass();
    }
    const bool mayHitGlass = this->MayHitGlass(o, d);
    for (const Tri& tri : this->tris)
    {
      double t, u, v;
      if ((!tri.glass || mayHitGlass) && HitTriangle(tri, o, d, t, u, v) && t < best)
      {
        best = t;
        bu = u;
        bv = v;
        hit = &tri;
      }
    }
    if (!hit)
    {
      return this->background;
    }
    if (!hit->glass)
    {
      return hit->albedo;
    }
    if (depth >= 12)
    {
      return 0;
    }
    const Vec x = Add(o, Mul(best, d));
    const Vec ng = Unit(Cross(Sub(hit->p[1], hit->p[0]), Sub(hit->p[2], hit->p[0])));
    const Vec ns =
      Unit(Add(Add(Mul(1 - bu - bv, hit->n[0]), Mul(bu, hit->n[1])), Mul(bv, hit->n[2])));
    const bool entering = Dot(d, ng) < 0;
    const double etaI = entering ? 1.0 : 1.5, etaT = entering ? 1.5 : 1.0;
    const Vec fg = entering ? ng : Mul(-1, ng);
    const Vec fs = entering ? ns : Mul(-1, ns);
    Vec nf = Dot(d, fs) < 0 ? fs : fg;
    double r = 1;
    Vec refl{}, refr{};
    bool refracts = false;
    for (int attempt = 0; attempt < 2; ++attempt)
    {
      const double c = -Dot(d, nf);
      r = Fresnel(c, etaI, etaT);
      refl = Sub(d, Mul(2 * Dot(d, nf), nf));
      const double eta = etaI / etaT, s2 = eta * eta * (1 - c * c);
      refracts = s2 < 1;
      if (refracts)
      {
        refr = Unit(Add(Mul(eta, d), Mul(eta * c - std::sqrt(1 - s2), nf)));
      }
      if ((Dot(refl, fg) > 0 && (!refracts || Dot(refr, fg) < 0)) || attempt == 1)
      {
        break;
      }
      nf = fg;
    }
    const double eps = 1e-7;
    double sum = r * this->Trace(Add(x, Mul(eps, fg)), refl, depth + 1);
    if (refracts)
    {
      sum += (1 - r) * this->Trace(Sub(x, Mul(eps, fg)), refr, depth + 1);
    }
    else
    {
      ++this->tirEvents;
    }
    return sum;
  }
};

vtkSmartPointer<vtkPolyData> Quads(const std::vector<std::array<Vec, 4>>& quads)
{
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  for (const auto& q : quads)
  {
    const vtkIdType base = points->GetNumberOfPoints();
    for (const Vec& p : q)
    {
      points->InsertNextPoint(p.data());
    }
    const vtkIdType a[3] = { base, base + 1, base + 2 }, b[3] = { base, base + 2, base + 3 };
    cells->InsertNextCell(3, a);
    cells->InsertNextCell(3, b);
  }
  poly->SetPoints(points);
  poly->SetPolys(cells);
  return poly;
}

vtkSmartPointer<vtkRefractaSurfaceMaterial> Lambertian(double albedo)
{
  auto m = vtkSmartPointer<vtkRefractaSurfaceMaterial>::New();
  m->SetAlbedo(albedo, albedo, albedo);
  return m;
}

vtkSmartPointer<vtkRefractaSurfaceMaterial> Glass(bool smooth)
{
  auto m = vtkSmartPointer<vtkRefractaSurfaceMaterial>::New();
  m->SetKindToDielectric();
  m->SetIndexInside(1.5);
  m->SetIndexOutside(1.0);
  m->SetSmoothNormals(smooth);
  return m;
}

// The checker floor z = z0 over [-2, 2]^2, 8 x 8 squares of albedo 0.15 and 0.85, as two
// surfaces (exact edges); `squares` receives both meshes.
void CheckerFloor(double z0, vtkRefractaSurfaceSet* set, std::vector<Tri>& tris)
{
  std::vector<std::array<Vec, 4>> dark, light;
  for (int i = 0; i < 8; ++i)
  {
    for (int j = 0; j < 8; ++j)
    {
      const double x0 = -2 + 0.5 * i, y0 = -2 + 0.5 * j;
      std::array<Vec, 4> q = { Vec{ x0, y0, z0 }, Vec{ x0 + 0.5, y0, z0 },
        Vec{ x0 + 0.5, y0 + 0.5, z0 }, Vec{ x0, y0 + 0.5, z0 } };
      ((i + j) % 2 ? light : dark).push_back(q);
    }
  }
  auto d = Quads(dark), l = Quads(light);
  set->AddSurface(d, Lambertian(0.15));
  set->AddSurface(l, Lambertian(0.85));
  AddMesh(d, false, 0.15, false, tris);
  AddMesh(l, false, 0.85, false, tris);
}

// Surface irradiance pi on every texel: a Lambertian surface then shows its albedo.
vtkSmartPointer<vtkImageData> UnitLighting(vtkImageData* medium, vtkRefractaSurfaceSet* set)
{
  return refracta_test::Lighting(
    medium, set, [](const double*, double e[3]) { e[0] = e[1] = e[2] = vtkMath::Pi(); });
}

struct Scene
{
  vtkNew<vtkRefractaSurfaceSet> set;
  Reference reference;
  vtkSmartPointer<vtkImageData> medium;
  vtkNew<vtkRefractaViewPass> pass;
  vtkNew<vtkCamera> camera;
  int w = 80, h = 80;

  // A clear medium far from the glass (the view pass needs one; straight rays), or `given`.
  void Prepare(double background, vtkImageData* given = nullptr)
  {
    const double origin[3] = { 5, 5, 5 };
    this->medium = given;
    if (!given)
    {
      this->medium = refracta_test::MakeGrid(4, 4, 4, 0.1, origin);
    }
    if (!given)
    {
      refracta_test::AddConstant(this->medium, "Extinction", 3, 0, 0, 0);
    }
    this->reference.background = background;
    this->pass->SetBackgroundColor(background, background, background);
    this->pass->SetDielectricSupersampling(1); // one centre ray per pixel, as the trace
    ASSERT_TRUE(this->pass->SetMedium(this->medium));
    ASSERT_TRUE(this->pass->SetLighting(UnitLighting(this->medium, this->set)));
    this->pass->SetSurfaces(this->set);
  }

  // The world ray of pixel (i, j).
  void Ray(int i, int j, Vec& o, Vec& d)
  {
    vtkRefractaViewPass::RayFrame f;
    ASSERT_TRUE(vtkRefractaViewPass::ComputeRayFrame(
      this->camera, this->medium, nullptr, this->w, this->h, f));
    const double sx = 2.0 * (i + 0.5) / this->w - 1.0, sy = 2.0 * (j + 0.5) / this->h - 1.0;
    double origin[3];
    this->medium->GetOrigin(origin);
    for (int a = 0; a < 3; ++a)
    {
      o[a] = f.Eye[a] + origin[a];
      d[a] = f.W[a] + sx * f.U[a] + sy * f.V[a];
    }
    d = Unit(d);
  }

  std::vector<double> ReferenceImage()
  {
    std::vector<double> image(static_cast<size_t>(this->w) * this->h);
    for (int j = 0; j < this->h; ++j)
    {
      for (int i = 0; i < this->w; ++i)
      {
        Vec o, d;
        this->Ray(i, j, o, d);
        image[i + static_cast<size_t>(this->w) * j] = this->reference.Trace(o, d, 0);
      }
    }
    return image;
  }

  // Renders with split depth `depth`; seconds = the median of 3 renders.
  std::vector<float> Render(int depth, double* seconds = nullptr)
  {
    this->pass->SetDielectricSplitDepth(depth);
    std::vector<float> hdr;
    std::vector<double> times;
    for (int k = 0; k < (seconds ? 3 : 1); ++k)
    {
      const auto t0 = std::chrono::steady_clock::now();
      EXPECT_TRUE(this->pass->Render(this->camera, this->w, this->h, nullptr, nullptr, hdr));
      times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(times.begin(), times.end());
    if (seconds)
    {
      *seconds = times[times.size() / 2];
    }
    for (float v : hdr)
    {
      EXPECT_TRUE(std::isfinite(v)) << "no NaN or Inf";
    }
    return hdr;
  }
};

struct Error
{
  double mean = 0, max = 0, badFraction = 0; // badFraction: pixels off by more than 0.02
};

Error Compare(const std::vector<float>& hdr, const std::vector<double>& ref)
{
  Error e;
  for (size_t p = 0; p < ref.size(); ++p)
  {
    double worst = 0;
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max(worst, std::abs(hdr[4 * p + c] - ref[p]));
    }
    e.mean += worst;
    e.max = std::max(e.max, worst);
    e.badFraction += worst > 0.02 ? 1 : 0;
  }
  e.mean /= ref.size();
  e.badFraction /= ref.size();
  return e;
}

void BallOverFloor(Scene& s, vtkImageData* medium = nullptr)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(0.5);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  sphere->Update();
  s.set->AddSurface(sphere->GetOutput(), Glass(true));
  AddMesh(sphere->GetOutput(), true, 0, true, s.reference.tris);
  CheckerFloor(-1.0, s.set, s.reference.tris);
  s.Prepare(0.4, medium);
}
}

//------------------------------------------------------------------------------
// The ball from above and obliquely (glass over a floor): deep splitting agrees with the trace
// pixel by pixel; the error of each split depth is printed with its time.
TEST(ViewPassGlass, BallOverCheckerAgreesWithDoublePrecisionTrace)
{
  for (int view = 0; view < 2; ++view)
  {
    Scene s;
    BallOverFloor(s);
    if (view == 0)
    {
      s.camera->SetPosition(0.05, 0.1, 3.0);
    }
    else
    {
      s.camera->SetPosition(0.0, -2.6, 1.2);
    }
    s.camera->SetFocalPoint(0, 0, -0.3);
    s.camera->SetViewUp(0, 1, 0);
    s.camera->SetViewAngle(40);
    const std::vector<double> ref = s.ReferenceImage();
    const Error deep = Compare(s.Render(8), ref);
    std::printf("view %d: split depth 8: mean %.2e max %.3f, %.2f%% of pixels off by > 0.02\n",
      view, deep.mean, deep.max, 100 * deep.badFraction);
    EXPECT_LT(deep.mean, 2e-3);
    EXPECT_LT(deep.badFraction, 0.01) << "pixel by pixel, but for float rounding at edges";
    for (int depth = 0; depth <= 3; ++depth)
    {
      double seconds = 0;
      const Error e = Compare(s.Render(depth, &seconds), ref);
      std::printf("view %d: split depth %d: mean %.2e max %.3f (>0.02: %.2f%%), %.1f ms\n", view,
        depth, e.mean, e.max, 100 * e.badFraction, 1e3 * seconds);
    }
    double deepSeconds = 0;
    s.Render(8, &deepSeconds);
    std::printf("view %d: split depth 8: %.1f ms\n", view, 1e3 * deepSeconds);
  }
}

//------------------------------------------------------------------------------
// Curved rays: the ball inside a medium grid whose index is that of the material owning each
// voxel centre (1.5 in the ball, 1 outside) with grad n = 0 (the exact-interface field of
// Physics.md): after each interface the march goes on in the medium on the new side, straight
// since grad n = 0, and the image equals the trace's.
TEST(ViewPassGlass, CurvedMarchContinuesOnTheNewSide)
{
  const double origin[3] = { -1.2, -1.2, -1.2 };
  auto medium = refracta_test::MakeGrid(25, 25, 25, 0.1, origin);
  refracta_test::AddConstant(medium, "Extinction", 3, 0, 0, 0);
  vtkFloatArray* n =
    refracta_test::AddConstant(medium, vtkRefractaMedium::RefractiveIndexName(), 1, 1.0);
  refracta_test::AddConstant(medium, vtkRefractaMedium::RefractiveIndexGradientName(), 3, 0, 0, 0);
  for (vtkIdType p = 0; p < medium->GetNumberOfPoints(); ++p)
  {
    double x[3];
    medium->GetPoint(p, x);
    n->SetValue(p, vtkMath::Norm(x) < 0.5 ? 1.5f : 1.0f);
  }
  Scene s;
  BallOverFloor(s, medium);
  s.pass->SetRayMode(vtkRefractaViewPass::CURVED);
  s.camera->SetPosition(0.05, 0.1, 3.0);
  s.camera->SetFocalPoint(0, 0, -0.3);
  s.camera->SetViewUp(0, 1, 0);
  s.camera->SetViewAngle(40);
  const Error e = Compare(s.Render(8), s.ReferenceImage());
  std::printf("curved: mean %.2e max %.3f, %.2f%% of pixels off by > 0.02\n", e.mean, e.max,
    100 * e.badFraction);
  EXPECT_LT(e.mean, 2e-3);
  EXPECT_LT(e.badFraction, 0.01);
}

//------------------------------------------------------------------------------
// Glass edges (DielectricSupersampling): a pixel over the ball's rim or silhouette is the mean of
// the n x n rays through its footprint, so with n = 3 it equals the mean of its 3 x 3 pixels in a
// render three times the size with one ray each; every other pixel is its centre ray, exactly as
// with n = 1. The pixels taken lie at the ball's edge: the rim (grazing hits) and the silhouette.
TEST(ViewPassGlass, SupersampledEdgesAreFootprintMeans)
{
  Scene s;
  BallOverFloor(s);
  s.camera->SetPosition(0.05, 0.1, 3.0);
  s.camera->SetFocalPoint(0, 0, -0.3);
  s.camera->SetViewUp(0, 1, 0);
  s.camera->SetViewAngle(40);
  s.w = s.h = 120;
  const std::vector<float> fine = s.Render(2); // one ray per pixel, three times the size
  s.w = s.h = 40;
  const std::vector<float> one = s.Render(2);
  EXPECT_EQ(s.pass->GetLastNumberOfSupersampledPixels(), 0);
  s.pass->SetDielectricSupersampling(3);

  // Grazing cosine 0.5 (default): the rim and the silhouette; 1: every pixel that sees the ball.
  for (double cosine : { 0.5, 1.0 })
  {
    s.pass->SetDielectricGrazingCosine(cosine);
    const std::vector<float> three = s.Render(2);
    const vtkIdType taken = s.pass->GetLastNumberOfSupersampledPixels();
    int asCentre = 0, asMean = 0, neither = 0;
    double rhoMin = 1e9, rhoMax = 0;
    for (int j = 0; j < 40; ++j)
    {
      for (int i = 0; i < 40; ++i)
      {
        const size_t p = i + 40 * static_cast<size_t>(j);
        double toCentre = 0, toMean = 0;
        for (int c = 0; c < 4; ++c)
        {
          double mean = 0;
          for (int b = 0; b < 3; ++b)
          {
            for (int a = 0; a < 3; ++a)
            {
              mean += fine[4 * ((3 * i + a) + 120 * static_cast<size_t>(3 * j + b)) + c] / 9.0;
            }
          }
          toCentre = std::max(toCentre, std::abs(double(three[4 * p + c]) - one[4 * p + c]));
          toMean = std::max(toMean, std::abs(three[4 * p + c] - mean));
        }
        if (toCentre <= 1e-6)
        {
          ++asCentre;
          continue;
        }
        if (toMean > 1e-3)
        {
          ++neither;
          continue;
        }
        ++asMean;
        Vec o, d; // the centre ray's closest approach to the ball's centre, over its radius
        s.Ray(i, j, o, d);
        const double along = -Dot(o, d);
        const double rho = std::sqrt(Dot(Add(o, Mul(along, d)), Add(o, Mul(along, d)))) / 0.5;
        rhoMin = std::min(rhoMin, rho);
        rhoMax = std::max(rhoMax, rho);
      }
    }
    std::printf("grazing cosine %.1f: supersampled %lld pixels: %d footprint means (rho %.3f to "
                "%.3f), %d centre rays, %d neither\n",
      cosine, static_cast<long long>(taken), asMean, rhoMin, rhoMax, asCentre, neither);
    EXPECT_GT(asMean, 20) << "the ball's edge is supersampled";
    EXPECT_LE(asMean, taken) << "only the pixels the pass counts differ from their centre ray";
    EXPECT_LE(neither, 4) << "each pixel is its centre ray or its footprint mean (float rounding)";
    EXPECT_LT(rhoMax, 1.1) << "no pixel away from the ball";
    if (cosine < 1.0)
    {
      // A ray at closest approach rho meets the ball at sin(theta) = rho: grazing (cos < 0.5)
      // from rho = 0.866 on, at one of the footprint's corners, half a diagonal (0.085 here)
      // from its centre.
      EXPECT_GT(rhoMin, 0.866 - 0.09) << "no pixel well inside the ball (no grazing hit there)";
    }
    else
    {
      EXPECT_LT(rhoMin, 0.3) << "the ball's inside is taken too";
    }
  }
}

//------------------------------------------------------------------------------
// A glass block (top face z = 0) with a black plane inside, seen at grazing angles: the top face
// shows R(theta) B, B the background, R from the Fresnel formula at the pixel's own angle.
TEST(ViewPassGlass, FresnelReflectionAtGrazingAngles)
{
  Scene s;
  const double a = 3.0;
  std::vector<std::array<Vec, 4>> faces = {
    { Vec{ -a, -a, 0 }, Vec{ a, -a, 0 }, Vec{ a, a, 0 }, Vec{ -a, a, 0 } },     // top, +z
    { Vec{ -a, -a, -1 }, Vec{ -a, a, -1 }, Vec{ a, a, -1 }, Vec{ a, -a, -1 } }, // bottom, -z
    { Vec{ -a, -a, -1 }, Vec{ a, -a, -1 }, Vec{ a, -a, 0 }, Vec{ -a, -a, 0 } }, // -y
    { Vec{ -a, a, -1 }, Vec{ -a, a, 0 }, Vec{ a, a, 0 }, Vec{ a, a, -1 } },     // +y
    { Vec{ -a, -a, -1 }, Vec{ -a, -a, 0 }, Vec{ -a, a, 0 }, Vec{ -a, a, -1 } }, // -x
    { Vec{ a, -a, -1 }, Vec{ a, a, -1 }, Vec{ a, a, 0 }, Vec{ a, -a, 0 } },     // +x
  };
  s.set->AddSurface(Quads(faces), Glass(false));
  const double b = 2.9;
  s.set->AddSurface(
    Quads({ { Vec{ -b, -b, -0.5 }, Vec{ b, -b, -0.5 }, Vec{ b, b, -0.5 }, Vec{ -b, b, -0.5 } } }),
    Lambertian(0.0));
  const double background = 0.8;
  s.Prepare(background);
  s.camera->SetPosition(0, -2.9, 0.35);
  s.camera->SetFocalPoint(0, 0, 0);
  s.camera->SetViewUp(0, 0, 1);
  s.camera->SetViewAngle(30);
  const std::vector<float> hdr = s.Render(2);
  int checked = 0;
  double worst = 0, maxAngle = 0;
  for (int j = 0; j < s.h; ++j)
  {
    for (int i = 0; i < s.w; ++i)
    {
      Vec o, d;
      s.Ray(i, j, o, d);
      const double t = -o[2] / d[2];
      if (!(t > 0) || std::abs(o[0] + t * d[0]) > 2.8 || std::abs(o[1] + t * d[1]) > 2.8)
      {
        continue; // not the top face (or too near its edges)
      }
      const double cosI = -d[2];
      const double expected = Fresnel(cosI, 1.0, 1.5) * background;
      const size_t p = i + static_cast<size_t>(s.w) * j;
      worst = std::max(worst, std::abs(hdr[4 * p] - expected));
      maxAngle = std::max(maxAngle, vtkMath::DegreesFromRadians(std::acos(cosI)));
      EXPECT_NEAR(hdr[4 * p], expected, 1e-3 * background) << "pixel " << i << ", " << j;
      ++checked;
    }
  }
  std::printf("Fresnel at grazing angles: %d pixels up to %.1f degrees, worst error %.2e\n",
    checked, maxAngle, worst);
  EXPECT_GT(checked, s.w * s.h / 4);
  EXPECT_GT(maxAngle, 80.0) << "grazing angles are covered";
}

//------------------------------------------------------------------------------
// A right-angle prism (cross-section (x, z): (-0.5, 0.5), (0.5, 0.5), (-0.5, -0.5), y in
// [-0.5, 0.5]) seen from above: light meets the hypotenuse at 45 degrees > 41.8 and is totally
// reflected onto a checker wall at x = -1.5; a white floor under the prism leaks in nothing.
TEST(ViewPassGlass, TotalInternalReflectionInPrism)
{
  Scene s;
  const double y0 = -0.5, y1 = 0.5;
  const Vec P0{ -0.5, y0, 0.5 }, Q0{ 0.5, y0, 0.5 }, R0{ -0.5, y0, -0.5 };
  const Vec P1{ -0.5, y1, 0.5 }, Q1{ 0.5, y1, 0.5 }, R1{ -0.5, y1, -0.5 };
  auto prism = Quads({
    { Q0, Q1, P1, P0 }, // top, +z
    { P1, R1, R0, P0 }, // left, -x
    { R0, R1, Q1, Q0 }, // hypotenuse, (1, 0, -1)
  });
  // The two triangular ends (outward -y and +y).
  vtkCellArray* polys = prism->GetPolys();
  vtkPoints* pts = prism->GetPoints();
  const vtkIdType e0[3] = { pts->InsertNextPoint(P0.data()), pts->InsertNextPoint(R0.data()),
    pts->InsertNextPoint(Q0.data()) };
  const vtkIdType e1[3] = { pts->InsertNextPoint(P1.data()), pts->InsertNextPoint(Q1.data()),
    pts->InsertNextPoint(R1.data()) };
  polys->InsertNextCell(3, e0);
  polys->InsertNextCell(3, e1);
  s.set->AddSurface(prism, Glass(false));
  AddMesh(prism, true, 0, false, s.reference.tris);
  // Checker wall x = -1.5 (facing +x), 8 x 8 squares over y, z in [-2, 2].
  std::vector<std::array<Vec, 4>> dark, light;
  for (int i = 0; i < 8; ++i)
  {
    for (int j = 0; j < 8; ++j)
    {
      const double ya = -2 + 0.5 * i, za = -2 + 0.5 * j;
      std::array<Vec, 4> q = { Vec{ -1.5, ya, za }, Vec{ -1.5, ya + 0.5, za },
        Vec{ -1.5, ya + 0.5, za + 0.5 }, Vec{ -1.5, ya, za + 0.5 } };
      ((i + j) % 2 ? light : dark).push_back(q);
    }
  }
  auto d = Quads(dark), l = Quads(light),
       floor =
         Quads({ { Vec{ -1.4, -2, -2 }, Vec{ 2, -2, -2 }, Vec{ 2, 2, -2 }, Vec{ -1.4, 2, -2 } } });
  s.set->AddSurface(d, Lambertian(0.15));
  s.set->AddSurface(l, Lambertian(0.5));
  s.set->AddSurface(floor, Lambertian(1.0));
  AddMesh(d, false, 0.15, false, s.reference.tris);
  AddMesh(l, false, 0.5, false, s.reference.tris);
  AddMesh(floor, false, 1.0, false, s.reference.tris);
  s.Prepare(0.0);
  s.camera->SetPosition(0, 0, 4);
  s.camera->SetFocalPoint(0, 0, 0);
  s.camera->SetViewUp(0, 1, 0);
  s.camera->SetViewAngle(12);
  const std::vector<double> ref = s.ReferenceImage();
  EXPECT_GT(s.reference.tirEvents, s.w * s.h / 4) << "the scene exercises total reflection";
  const std::vector<float> hdr = s.Render(8);
  const Error e = Compare(hdr, ref);
  std::printf("prism: mean %.2e max %.3f, %.2f%% of pixels off by > 0.02\n", e.mean, e.max,
    100 * e.badFraction);
  EXPECT_LT(e.mean, 2e-3);
  EXPECT_LT(e.badFraction, 0.01);
  // Through the top face's centre: the floor (radiance 1) leaks nothing; what is seen is the
  // wall (<= 0.5) transmitted twice, plus weak reflections of the black background.
  const size_t centre = s.w / 2 + static_cast<size_t>(s.w) * (s.h / 2);
  EXPECT_LT(hdr[4 * centre], 0.5);
  EXPECT_GT(hdr[4 * centre], 0.15 * 0.9);
}
