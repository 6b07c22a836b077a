// BenchmarkSurfaces: vtkRefractaBVH build time and closest-hit traversal rates (host, double;
// OpenCL device, float, through Kernels/refracta_surfaces_tests.cl) for spheres of about 10k,
// 100k and 1M triangles (vtkSphereSource). Rays start on a sphere of radius 3 around the unit
// mesh and aim at random points within radius 1.2 of its centre (about 70% hit). Medians of
// --runs runs.
//
// Usage: BenchmarkSurfaces [--quick] [--runs 3] [--rays 200000] [--csv surfaces_benchmark.csv]
//                          [--texel-sweep] [--direct-light] [--grid-cuts]
//   --quick: only the 10k mesh, 20000 rays, one run (the smoke test).
//   --texel-sweep: instead, the irradiance atlas's resolution against the photon count (the
//     justification of the automatic texel size): a black 20 x 20 plane under a point light of
//     intensity I = 2 at height h = 5 (the plane of RefractaTransport.PhotonSurfaces); texel sizes
//     0.1, 0.22 (what the automatic rule, the bounds' diagonal / 128, gives this plane alone) and
//     0.5; photon counts 2^18, 2^20, 2^22; per texel within rho < 5 of the axis, the relative
//     error of E against I h / (h^2 + rho^2)^(3/2) at the texel's centre: RMS (noise and blur) and
//     mean (the blur's bias).
//   --direct-light: instead, on that plane at texels 0.22 and 2^16, 2^18, 2^20 photons, the
//     same errors and seconds with photons alone and with the direct light from light rays
//     (vtkPhotonTracer::SkipDirectSurfaceLight + vtkLightRaySingleScattering::
//     ComputeSurfaceIrradiance, what the pipeline does), in one run.
//   --grid-cuts: instead, vtkRefractaGridCuts's search (medians of --runs): a sphere of radius
//     0.4 (about 10k triangles) in a 256^3 grid over the unit cube, and 400 large random
//     triangles (corners anywhere in the cube: overlapping, oblique) in a 160^3 grid; then the
//     same search with the owned volumes (vtkRefractaGridCuts::GetScaledVoxels) counted.
#include "RefractaBenchmark.h"

#include "vtkCellArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightRaySingleScattering.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPhotonTracer.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRefractaBVH.h"
#include "vtkRefractaGridCuts.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSurfaceMaterial.h"
#include "vtkRefractaSurfaceSet.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace
{
std::vector<double> SphereTriangles(int theta, int phi)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(theta);
  sphere->SetPhiResolution(phi);
  sphere->SetRadius(1.0);
  sphere->Update();
  vtkPolyData* mesh = sphere->GetOutput();
  std::vector<double> out;
  vtkCellArray* polys = mesh->GetPolys();
  vtkIdType n;
  const vtkIdType* ids;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
  {
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      for (vtkIdType id : { ids[0], ids[k], ids[k + 1] })
      {
        double p[3];
        mesh->GetPoint(id, p);
        out.insert(out.end(), p, p + 3);
      }
    }
  }
  return out;
}

// Rays (origin, direction) as float4 pairs in the BVH's frame.
void MakeRays(int count, const double* frame, std::vector<float>& origins, std::vector<float>& dirs)
{
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  origins.assign(4 * size_t(count), 0.0f);
  dirs.assign(4 * size_t(count), 0.0f);
  for (int i = 0; i < count; ++i)
  {
    double o[3], t[3], m = 0, q = 0;
    for (int a = 0; a < 3; ++a)
    {
      o[a] = gauss(rng);
      t[a] = gauss(rng);
      m += o[a] * o[a];
      q += t[a] * t[a];
    }
    const double r = 1.2 * std::cbrt(unit(rng));
    for (int a = 0; a < 3; ++a)
    {
      o[a] *= 3.0 / std::sqrt(m);
      t[a] *= r / std::sqrt(q);
      origins[4 * i + a] = static_cast<float>(o[a] - frame[a]);
      dirs[4 * i + a] = static_cast<float>(t[a] - o[a]);
    }
  }
}
}

// Per texel of `set` within rho < 5 of the light's axis, the relative error of `e` against the
// point light's I h / (h^2 + rho^2)^(3/2) at the texel's centre: RMS and mean.
void PlaneErrors(vtkRefractaSurfaceSet* set, vtkDataArray* e, double h, double intensity,
  long& count, double& rms, double& mean)
{
  vtkRefractaBVH* bvh = set->GetBVH();
  const auto& info = set->GetTriangleInfo();
  double sum2 = 0, sum = 0;
  count = 0;
  for (vtkIdType k = 0; k < set->GetNumberOfTriangles(); ++k)
  {
    const double* t = &bvh->GetTriangles()[9 * k];
    const int first = info[4 * k], n = info[4 * k + 1];
    for (int i = 0; i < n * n; ++i)
    {
      double c[6];
      vtkRefractaSurfaceSet::GetTexelCorners(i, n, c);
      const double u = (c[0] + c[2] + c[4]) / 3, v = (c[1] + c[3] + c[5]) / 3;
      double x[3];
      for (int a = 0; a < 3; ++a)
      {
        x[a] = (1 - u - v) * t[a] + u * t[3 + a] + v * t[6 + a] + bvh->GetFrameOrigin()[a];
      }
      const double rho = std::hypot(x[0], x[1]);
      if (rho >= 5)
      {
        continue;
      }
      const double expected = intensity * h / std::pow(h * h + rho * rho, 1.5);
      // The light reaches one side; the other stays dark, so both sides together are that side.
      const double both = vtkRefractaLightingVolume::GetSurfaceSideValue(
                            e, first + i, vtkRefractaLightingVolume::FRONT_SIDE, 0, 3) +
        vtkRefractaLightingVolume::GetSurfaceSideValue(
          e, first + i, vtkRefractaLightingVolume::BACK_SIDE, 0, 3);
      const double r = both / expected - 1;
      sum += r;
      sum2 += r * r;
      ++count;
    }
  }
  rms = count > 0 ? std::sqrt(sum2 / count) : 0.0;
  mean = count > 0 ? sum / count : 0.0;
}

// The sweeps' scene: a black 20 x 20 plane at z = 0 under a point light of intensity 2 at
// height 5, and a small vacuum box around the light (the photon pass needs a medium).
struct LitPlane
{
  const double H = 5.0, Intensity = 2.0;
  vtkNew<vtkImageData> Medium;
  vtkNew<vtkPlaneSource> Plane;
  vtkNew<vtkRefractaSurfaceMaterial> Black;
  vtkNew<vtkLight> Light;

  LitPlane()
  {
    this->Medium->SetDimensions(8, 8, 8);
    this->Medium->SetSpacing(0.5, 0.5, 0.5);
    this->Medium->SetOrigin(-1.75, -1.75, this->H - 1.75);
    for (const char* name :
      { vtkRefractaMedium::ExtinctionName(), vtkRefractaMedium::AlbedoName() })
    {
      vtkNew<vtkFloatArray> a;
      a->SetName(name);
      a->SetNumberOfComponents(3);
      a->SetNumberOfTuples(this->Medium->GetNumberOfPoints());
      a->Fill(0.0);
      this->Medium->GetPointData()->AddArray(a);
    }
    this->Plane->SetOrigin(-10, -10, 0);
    this->Plane->SetPoint1(10, -10, 0);
    this->Plane->SetPoint2(-10, 10, 0);
    this->Plane->Update();
    this->Black->SetAlbedo(0, 0, 0);
    this->Light->SetPositional(true);
    this->Light->SetPosition(0, 0, this->H);
    this->Light->SetFocalPoint(0, 0, 0);
    this->Light->SetConeAngle(180);
    this->Light->SetIntensity(this->Intensity);
  }

  // The plane's irradiance with texels of `size` from `photons` photons, with the direct light
  // from light rays instead when `rays`; its errors (PlaneErrors) and seconds. False on failure.
  bool Run(
    double size, int photons, bool rays, long& count, double& rms, double& mean, double& seconds)
  {
    vtkNew<vtkRefractaSurfaceSet> set;
    set->AddSurface(this->Plane->GetOutput(), this->Black);
    set->SetTexelSize(size);
    vtkNew<vtkPhotonTracer> tracer;
    tracer->SetInputData(this->Medium);
    tracer->SetSurfaces(set);
    tracer->AddLight(this->Light);
    tracer->SetNumberOfPhotons(photons);
    tracer->SetSkipDirectSurfaceLight(rays);
    const auto start = std::chrono::steady_clock::now();
    tracer->Update();
    vtkDataArray* e = tracer->GetOutput()->GetFieldData()->GetArray(
      vtkRefractaLightingVolume::SurfaceIrradianceName());
    if (!e)
    {
      std::cerr << "no irradiance: the photon pass failed\n";
      return false;
    }
    vtkNew<vtkFloatArray> sum;
    sum->DeepCopy(e);
    if (rays)
    {
      vtkNew<vtkLightRaySingleScattering> direct;
      direct->AddLight(this->Light);
      direct->SetSurfaces(set);
      std::vector<float> irradiance;
      if (!direct->ComputeSurfaceIrradiance(this->Medium, irradiance))
      {
        std::cerr << "the direct light failed\n";
        return false;
      }
      for (size_t i = 0; i < irradiance.size(); ++i)
      {
        sum->SetValue(
          static_cast<vtkIdType>(i), sum->GetValue(static_cast<vtkIdType>(i)) + irradiance[i]);
      }
    }
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    PlaneErrors(set, sum, this->H, this->Intensity, count, rms, mean);
    return true;
  }
};

// The texel-size x photon-count sweep (see the header). Returns the process status.
int TexelSweep(const std::string& csv)
{
  LitPlane scene;
  refracta::bench::Table table(
    { "texel_size", "photons", "texels_rho<5", "rms_error", "mean_error", "seconds" });
  for (double size : { 0.1, 0.22, 0.5 })
  {
    for (int log2 : { 18, 20, 22 })
    {
      long count = 0;
      double rms = 0, mean = 0, seconds = 0;
      if (!scene.Run(size, 1 << log2, false, count, rms, mean, seconds))
      {
        return 1;
      }
      table.AddRow(
        { refracta::bench::Table::Format(size), refracta::bench::Table::Format(double(1 << log2)),
          refracta::bench::Table::Format(double(count)), refracta::bench::Table::Format(rms),
          refracta::bench::Table::Format(mean), refracta::bench::Table::Format(seconds) });
    }
  }
  table.Print("Irradiance atlas: texel size x photons, black 20 x 20 plane, point light at h = 5");
  return table.WriteCsv(csv) ? 0 : 1;
}

// Photons alone against light rays for the direct light (vtkRefractaRenderPipeline's
// DirectSurfaceLightByRays) at the automatic texel size, same run. Returns the process status.
int DirectLightComparison(const std::string& csv)
{
  LitPlane scene;
  refracta::bench::Table table(
    { "direct_light", "photons", "texels_rho<5", "rms_error", "mean_error", "seconds" });
  for (int log2 : { 16, 18, 20 })
  {
    for (bool rays : { false, true })
    {
      long count = 0;
      double rms = 0, mean = 0, seconds = 0;
      if (!scene.Run(0.22, 1 << log2, rays, count, rms, mean, seconds))
      {
        return 1;
      }
      table.AddRow(
        { rays ? "light_rays" : "photons", refracta::bench::Table::Format(double(1 << log2)),
          refracta::bench::Table::Format(double(count)), refracta::bench::Table::Format(rms),
          refracta::bench::Table::Format(mean), refracta::bench::Table::Format(seconds) });
    }
  }
  table.Print("Direct light on a black 20 x 20 plane, point light at h = 5, texels 0.22");
  return table.WriteCsv(csv) ? 0 : 1;
}

// The search of vtkRefractaGridCuts on a sphere and on random large triangles.
int GridCutsSearch(int runs)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.5, 0.5, 0.5);
  sphere->SetRadius(0.4);
  sphere->SetThetaResolution(100);
  sphere->SetPhiResolution(52);
  sphere->Update();
  vtkNew<vtkPolyData> random;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> cells;
  std::mt19937 generator(11);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int t = 0; t < 400; ++t)
  {
    vtkIdType ids[3];
    for (vtkIdType& id : ids)
    {
      id = points->InsertNextPoint(uniform(generator), uniform(generator), uniform(generator));
    }
    cells->InsertNextCell(3, ids);
  }
  random->SetPoints(points);
  random->SetPolys(cells);
  struct Case
  {
    const char* Name;
    vtkPolyData* Mesh;
    int N;
  };
  const Case cases[] = { { "sphere", sphere->GetOutput(), 256 }, { "random", random, 160 } };
  for (const Case& c : cases)
  {
    vtkNew<vtkRefractaSurfaceSet> set;
    vtkNew<vtkRefractaSurfaceMaterial> material;
    set->AddSurface(c.Mesh, material);
    if (!set->Build())
    {
      return 1;
    }
    const int dims[3] = { c.N, c.N, c.N };
    const double h = 1.0 / (c.N - 1);
    const double spacing[3] = { h, h, h };
    size_t marked = 0;
    unsigned long long digest = 0; // of every voxel's bits: the same cuts give the same digest
    const double seconds = refracta::bench::MedianSeconds(runs,
      [&]
      {
        vtkNew<vtkRefractaGridCuts> cuts;
        cuts->Update(set, dims, spacing, nullptr);
        const std::vector<unsigned char>& links = cuts->GetLinks();
        marked = std::count_if(links.begin(), links.end(), [](unsigned char b) { return b != 0; });
        digest = 0;
        for (size_t v = 0; v < links.size(); ++v)
        {
          digest = digest * 1099511628211ull + (v + 1) * links[v];
        }
      });
    std::cout << "grid cuts, " << c.Name << ": " << set->GetBVH()->GetNumberOfTriangles()
              << " triangles, " << c.N << "^3: " << seconds << " s (median of " << runs << "), "
              << marked << " voxels near a triangle or with a cut link, digest " << digest
              << std::endl;
    // The owned volumes the photon pass asks for once per search (64 points per marked voxel).
    size_t scaled = 0;
    const double owned = refracta::bench::MedianSeconds(runs,
      [&]
      {
        vtkNew<vtkRefractaGridCuts> cuts;
        cuts->Update(set, dims, spacing, nullptr);
        scaled = cuts->GetScaledVoxels().size();
      });
    std::cout << "search and owned volumes, " << c.Name << ": " << owned << " s (median of " << runs
              << "; owned volumes " << owned - seconds << " s), " << scaled << " voxels scaled"
              << std::endl;
  }
  return 0;
}

int main(int argc, char* argv[])
{
  bool gridCuts = false;
  bool quick = false;
  int runs = 3;
  int rays = 200000;
  std::string csv = "surfaces_benchmark.csv";
  bool texelSweep = false;
  bool directLight = false;
  for (int a = 1; a < argc; ++a)
  {
    const std::string arg = argv[a];
    auto next = [&]() { return a + 1 < argc ? std::string(argv[++a]) : std::string(); };
    if (arg == "--quick")
    {
      quick = true;
    }
    else if (arg == "--runs")
    {
      runs = std::max(1, std::stoi(next()));
    }
    else if (arg == "--rays")
    {
      rays = std::max(1, std::stoi(next()));
    }
    else if (arg == "--csv")
    {
      csv = next();
    }
    else if (arg == "--texel-sweep")
    {
      texelSweep = true;
    }
    else if (arg == "--direct-light")
    {
      directLight = true;
    }
    else if (arg == "--grid-cuts")
    {
      gridCuts = true;
    }
    else
    {
      std::cerr << "usage: BenchmarkSurfaces [--quick] [--runs n] [--rays n] [--csv file] "
                   "[--texel-sweep] [--direct-light] [--grid-cuts]\n";
      return 2;
    }
  }
  if (gridCuts)
  {
    return GridCutsSearch(runs);
  }
  if (directLight)
  {
    return DirectLightComparison(csv);
  }
  if (texelSweep)
  {
    return TexelSweep(csv);
  }
  if (quick)
  {
    runs = 1;
    rays = 20000;
  }
  struct Mesh
  {
    int Theta, Phi;
  };
  std::vector<Mesh> meshes = { { 100, 52 }, { 320, 160 }, { 1000, 502 } };
  if (quick)
  {
    meshes.resize(1);
  }
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  const bool device = context->Initialize();
  refracta::bench::Table table(
    { "triangles", "nodes", "depth", "build_s", "host_Mrays_s", "device_Mrays_s", "hit_fraction" });
  for (const Mesh& m : meshes)
  {
    const std::vector<double> tri = SphereTriangles(m.Theta, m.Phi);
    const vtkIdType n = static_cast<vtkIdType>(tri.size() / 9);
    vtkNew<vtkRefractaBVH> bvh;
    std::vector<double> builds;
    for (int r = 0; r < runs; ++r)
    {
      bvh->Build(tri.data(), n);
      builds.push_back(bvh->GetBuildSeconds());
    }
    std::vector<float> origins, dirs;
    MakeRays(rays, bvh->GetFrameOrigin(), origins, dirs);
    int hits = 0;
    const double hostSeconds = refracta::bench::MedianSeconds(runs,
      [&]
      {
        hits = 0;
        for (int i = 0; i < rays; ++i)
        {
          const double* f = bvh->GetFrameOrigin();
          const double o[3] = { origins[4 * i] + f[0], origins[4 * i + 1] + f[1],
            origins[4 * i + 2] + f[2] };
          const double d[3] = { dirs[4 * i], dirs[4 * i + 1], dirs[4 * i + 2] };
          double hit[3];
          hits += bvh->IntersectRay(o, d, 1e30, hit) >= 0 ? 1 : 0;
        }
      });
    double deviceRate = 0;
    if (device)
    {
      cl_program program =
        context->GetProgram({ "refracta_surfaces.cl", "refracta_surfaces_tests.cl" }, "");
      vtkOpenCLKernel kernel = context->CreateKernel(program, "refracta_test_trace");
      const auto& nodes = bvh->GetNodes();
      const auto& ft = bvh->GetFloatTriangles();
      const cl_uint count = static_cast<cl_uint>(rays);
      std::vector<float> tMax(count, 1e30f);
      vtkOpenCLBuffer nb =
        context->CreateBuffer(CL_MEM_READ_ONLY, nodes.size() * 4, (void*)nodes.data(), "nodes");
      vtkOpenCLBuffer tb =
        context->CreateBuffer(CL_MEM_READ_ONLY, ft.size() * 4, (void*)ft.data(), "triangles");
      vtkOpenCLBuffer ob =
        context->CreateBuffer(CL_MEM_READ_ONLY, origins.size() * 4, origins.data(), "o");
      vtkOpenCLBuffer db =
        context->CreateBuffer(CL_MEM_READ_ONLY, dirs.size() * 4, dirs.data(), "d");
      vtkOpenCLBuffer mb = context->CreateBuffer(CL_MEM_READ_ONLY, count * 4, tMax.data(), "tmax");
      vtkOpenCLBuffer hb = context->CreateBuffer(CL_MEM_WRITE_ONLY, count * 16, nullptr, "hits");
      vtkOpenCLBuffer cb = context->CreateBuffer(CL_MEM_WRITE_ONLY, count * 4, nullptr, "occ");
      const cl_int nodeCount = static_cast<cl_int>(bvh->GetNumberOfNodes());
      vtkOpenCLSetKernelArgs(kernel.Get(), nb.Get(), nodeCount, tb.Get(), ob.Get(), db.Get(),
        mb.Get(), hb.Get(), cb.Get(), count);
      const size_t global = count;
      context->RunKernel(kernel.Get(), 1, &global, nullptr, "warm-up");
      context->Finish();
      // The kernel does a closest-hit and an any-hit query per ray: two traversals.
      const double seconds = refracta::bench::MedianSeconds(runs,
        [&]
        {
          context->RunKernel(kernel.Get(), 1, &global, nullptr, "trace");
          context->Finish();
        });
      deviceRate = 2.0 * rays / seconds / 1e6;
    }
    table.AddRow({ refracta::bench::Table::Format(double(n)),
      refracta::bench::Table::Format(double(bvh->GetNumberOfNodes())),
      refracta::bench::Table::Format(bvh->GetDepth()),
      refracta::bench::Table::Format(refracta::bench::Median(builds)),
      refracta::bench::Table::Format(rays / hostSeconds / 1e6),
      device ? refracta::bench::Table::Format(deviceRate) : std::string("n/a"),
      refracta::bench::Table::Format(double(hits) / rays) });
  }
  std::cout << "device: " << (device ? std::string(context->GetDeviceName()) : "none") << "\n";
  table.Print("BVH build (binned SAH, 16 bins) and closest-hit rays per second");
  if (!table.WriteCsv(csv))
  {
    std::cerr << "could not write " << csv << "\n";
    return 1;
  }
  std::cout << "CSV: " << csv << "\n";
  return 0;
}
