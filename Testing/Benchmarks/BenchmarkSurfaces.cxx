// BenchmarkSurfaces: vtkRefractaBVH build time and closest-hit traversal rates (host, double;
// OpenCL device, float, through Kernels/refracta_surfaces_tests.cl) for spheres of about 10k,
// 100k and 1M triangles (vtkSphereSource). Rays start on a sphere of radius 3 around the unit
// mesh and aim at random points within radius 1.2 of its centre (about 70% hit). Medians of
// --runs runs.
//
// Usage: BenchmarkSurfaces [--quick] [--runs 3] [--rays 200000] [--csv surfaces_benchmark.csv]
//   --quick: only the 10k mesh, 20000 rays, one run (the smoke test).
#include "RefractaBenchmark.h"

#include "vtkCellArray.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkPolyData.h"
#include "vtkRefractaBVH.h"
#include "vtkSphereSource.h"

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

int main(int argc, char* argv[])
{
  bool quick = false;
  int runs = 3;
  int rays = 200000;
  std::string csv = "surfaces_benchmark.csv";
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
    else
    {
      std::cerr << "usage: BenchmarkSurfaces [--quick] [--runs n] [--rays n] [--csv file]\n";
      return 2;
    }
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
