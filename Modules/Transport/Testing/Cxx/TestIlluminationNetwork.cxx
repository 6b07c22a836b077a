// Tests of vtkIlluminationNetwork (Szirmay-Kalos et al., papers/002;
// Kernels/illumination_network.cl):
// - the direct light through a column of particles is attenuated by exactly (1 - alpha)^k;
// - the power books close: injected = escaped + absorbed (albedo 1 and albedo 0.8, point light
//   inside the cloud, and sky light), to the convergence tolerance;
// - a warm start after a small light move converges in fewer iterations than a cold start;
// - averaging rotated direction sets reduces the quadrature noise between seeds;
// - bad particle input (negative radius, NaN, missing arrays, empty, a million particles).
#include "vtkCommand.h"
#include "vtkEffectPlan.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIlluminationNetwork.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkOpenCLContext.h"
#include "vtkParticleMediumDeposit.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRefractaParticleMedium.h"
#include "vtkSceneAnalysis.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

namespace
{
using Medium = vtkRefractaParticleMedium;

vtkSmartPointer<vtkFloatArray> MakeArray(
  const char* name, int components, vtkIdType n, double value)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(n);
  array->Fill(value);
  return array;
}

// n particles uniformly in a ball of radius `ball`, all of radius r, extinction sigma, albedo a.
vtkSmartPointer<vtkPolyData> MakeCloud(
  vtkIdType n, double ball, double r, double sigma, double albedo, unsigned seed = 7)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  while (points->GetNumberOfPoints() < n)
  {
    const double x = u(rng), y = u(rng), z = u(rng);
    if (x * x + y * y + z * z <= 1.0)
    {
      points->InsertNextPoint(ball * x, ball * y, ball * z);
    }
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  cloud->GetPointData()->AddArray(MakeArray(Medium::RadiusName(), 1, n, r));
  cloud->GetPointData()->AddArray(MakeArray(Medium::ExtinctionName(), 3, n, sigma));
  cloud->GetPointData()->AddArray(MakeArray(Medium::AlbedoName(), 3, n, albedo));
  return cloud;
}

double Sum(vtkDataArray* array, int c)
{
  double s = 0;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    s += array->GetComponent(i, c);
  }
  return s;
}

void ExpectBooksClose(vtkIlluminationNetwork* network, double tolerance, const char* what)
{
  for (int c = 0; c < 3; ++c)
  {
    const double in = network->GetInjectedPower()[c];
    const double out = network->GetEscapedPower()[c] + network->GetAbsorbedPower()[c];
    ASSERT_GT(in, 0) << what;
    EXPECT_NEAR(out / in, 1.0, tolerance) << what << " channel " << c;
  }
  std::printf("%s: injected %.6g escaped %.6g absorbed %.6g (imbalance %.2e), %d iterations\n",
    what, network->GetInjectedPower()[0], network->GetEscapedPower()[0],
    network->GetAbsorbedPower()[0],
    (network->GetEscapedPower()[0] + network->GetAbsorbedPower()[0]) /
        network->GetInjectedPower()[0] -
      1.0,
    network->GetIterations());
}
}

// A column of particles on the z axis under a directional light travelling along -z: the light
// reaching the k-th particle is the irradiance times (1 - alpha)^k, alpha = 1 - exp(-sigma 4r/3).
TEST(IlluminationNetwork, DirectLightThroughAColumn)
{
  const int n = 6;
  const double r = 0.2, sigma = 2.0;
  vtkNew<vtkPoints> points;
  for (int k = 0; k < n; ++k)
  {
    points->InsertNextPoint(0.0, 0.0, -0.5 * k);
  }
  vtkNew<vtkPolyData> column;
  column->SetPoints(points);
  column->GetPointData()->AddArray(MakeArray(Medium::RadiusName(), 1, n, r));
  column->GetPointData()->AddArray(MakeArray(Medium::ExtinctionName(), 3, n, sigma));
  vtkNew<vtkIlluminationNetwork> network;
  network->SetInputData(column);
  network->SetLightType(vtkIlluminationNetwork::DIRECTIONAL_LIGHT);
  network->SetLightDirection(0, 0, -1);
  network->SetLightIntensity(2.0, 1.0, 0.5);
  network->SetNumberOfDirections(32);
  network->Update();
  vtkDataArray* direct =
    network->GetOutput()->GetPointData()->GetArray(Medium::DirectFluenceName());
  ASSERT_NE(direct, nullptr);
  const double transmit = std::exp(-sigma * Medium::MeanChord(r));
  for (int k = 0; k < n; ++k)
  {
    EXPECT_NEAR(direct->GetComponent(k, 0), 2.0 * std::pow(transmit, k), 1e-6) << k;
    EXPECT_NEAR(direct->GetComponent(k, 2), 0.5 * std::pow(transmit, k), 1e-6) << k;
  }
  // Albedo 0: nothing scatters, so the network stays dark.
  vtkDataArray* multiple =
    network->GetOutput()->GetPointData()->GetArray(Medium::MultipleFluenceName());
  EXPECT_EQ(Sum(multiple, 0), 0.0);
}

// Power books (see Documentation/Physics.md): every unit of power injected into the network
// (scattered direct light, emission, sky) leaves it at the end of a line or is absorbed.
TEST(IlluminationNetwork, PowerBooksClose)
{
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(1024, 1.0, 0.1, 5.0, 1.0);
  vtkNew<vtkIlluminationNetwork> network;
  network->SetInputData(cloud);
  network->SetLightType(vtkIlluminationNetwork::POINT_LIGHT);
  network->SetLightPosition(0.05, -0.03, 0.02); // inside the cloud
  network->SetLightIntensity(1.0, 0.7, 0.4);
  network->SetTolerance(1e-6);
  network->SetMaximumIterations(4000);
  network->Update();
  EXPECT_TRUE(network->GetConverged());
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_EQ(network->GetAbsorbedPower()[c], 0.0); // albedo 1 absorbs nothing
  }
  ExpectBooksClose(network, 0.01, "albedo 1, point light inside");
  // The balance is exact up to the last iteration's change: far tighter than 1%.
  EXPECT_NEAR(network->GetEscapedPower()[0] / network->GetInjectedPower()[0], 1.0, 1e-3);

  // Absorbing particles with an anisotropic phase function, lit by the sky as well.
  vtkSmartPointer<vtkPolyData> absorbing = MakeCloud(1024, 1.0, 0.1, 5.0, 0.8);
  absorbing->GetPointData()->AddArray(MakeArray(Medium::AnisotropyName(), 1, 1024, 0.6));
  network->SetInputData(absorbing);
  network->SetSkyRadiance(0.1, 0.2, 0.3);
  network->Update();
  EXPECT_TRUE(network->GetConverged());
  ExpectBooksClose(network, 1e-3, "albedo 0.8, g 0.6, point light and sky");
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_GT(network->GetAbsorbedPower()[c], 0.0);
  }
}

// The paper's warm start: after a small light move the previous solution is a better start.
TEST(IlluminationNetwork, WarmStartConvergesFaster)
{
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(1024, 1.0, 0.1, 5.0, 0.9);
  vtkNew<vtkIlluminationNetwork> network;
  network->SetInputData(cloud);
  network->SetLightType(vtkIlluminationNetwork::POINT_LIGHT);
  network->SetLightPosition(1.5, 0.0, 0.0);
  network->SetTolerance(1e-4);
  network->SetCheckInterval(1);
  network->Update();
  ASSERT_TRUE(network->GetConverged());
  network->SetLightPosition(1.5, 0.1, 0.0); // a small move
  network->Update();
  ASSERT_TRUE(network->GetConverged());
  const int warm = network->GetIterations();
  vtkSmartPointer<vtkDataArray> warmFluence =
    network->GetOutput()->GetPointData()->GetArray(Medium::MultipleFluenceName());
  network->ResetState();
  network->Update();
  ASSERT_TRUE(network->GetConverged());
  const int cold = network->GetIterations();
  std::printf("after a light move of 0.1: warm start %d iterations, cold start %d\n", warm, cold);
  EXPECT_LT(warm, cold);
  // Both reach the same fixed point.
  vtkDataArray* coldFluence =
    network->GetOutput()->GetPointData()->GetArray(Medium::MultipleFluenceName());
  EXPECT_NEAR(Sum(warmFluence, 0) / Sum(coldFluence, 0), 1.0, 2e-3);
}

// The quadrature error of one direction set is noise over random rotations: averaging R sets
// brings two independent seeds' per-particle fluence closer than single sets do.
TEST(IlluminationNetwork, RotationsAverageTheQuadratureError)
{
  vtkSmartPointer<vtkPolyData> cloud = MakeCloud(512, 1.0, 0.12, 4.0, 0.9);
  auto spread = [&](int rotations)
  {
    vtkSmartPointer<vtkFloatArray> results[2];
    for (int s = 0; s < 2; ++s)
    {
      vtkNew<vtkIlluminationNetwork> network;
      network->SetInputData(cloud);
      network->SetNumberOfDirections(32);
      network->SetNumberOfRotations(rotations);
      network->SetSeed(11 + 97 * s);
      network->SetLightType(vtkIlluminationNetwork::DIRECTIONAL_LIGHT);
      network->SetLightDirection(0.3, -1.0, 0.2);
      network->SetTolerance(1e-4);
      network->Update();
      results[s] = vtkFloatArray::SafeDownCast(
        network->GetOutput()->GetPointData()->GetArray(Medium::MultipleFluenceName()));
    }
    double difference = 0, mean = 0;
    for (vtkIdType p = 0; p < results[0]->GetNumberOfTuples(); ++p)
    {
      const double a = results[0]->GetComponent(p, 0), b = results[1]->GetComponent(p, 0);
      difference += (a - b) * (a - b);
      mean += 0.5 * (a + b);
    }
    const vtkIdType n = results[0]->GetNumberOfTuples();
    return std::sqrt(difference / n) / (mean / n);
  };
  const double one = spread(1);
  const double eight = spread(8);
  std::printf(
    "relative rms difference between two seeds: 1 set %.4f, 8 rotated sets %.4f\n", one, eight);
  EXPECT_LT(eight, 0.6 * one); // 1/sqrt(8) = 0.35 for independent noise
}

// Bad input: a clear error naming the input and what is valid, and an empty output.
TEST(IlluminationNetwork, BadParticles)
{
  struct Case
  {
    const char* What;
    vtkSmartPointer<vtkPolyData> Cloud;
    const char* Expected;
  };
  std::vector<Case> cases;
  {
    auto cloud = MakeCloud(16, 1.0, 0.1, 1.0, 0.5);
    cloud->GetPointData()->GetArray(Medium::RadiusName())->SetComponent(3, 0, -0.1);
    cases.push_back({ "negative radius", cloud, "'Radius' of particle 3 is -0.1" });
  }
  {
    auto cloud = MakeCloud(16, 1.0, 0.1, 1.0, 0.5);
    cloud->GetPointData()->GetArray(Medium::ExtinctionName())->SetComponent(5, 1, std::nan(""));
    cases.push_back({ "NaN extinction", cloud, "'Extinction' of particle 5" });
  }
  {
    auto cloud = MakeCloud(16, 1.0, 0.1, 1.0, 0.5);
    cloud->GetPoints()->SetPoint(2, 0.0, std::nan(""), 0.0);
    cases.push_back({ "NaN position", cloud, "particle 2 has a non-finite position" });
  }
  {
    auto cloud = MakeCloud(16, 1.0, 0.1, 1.0, 0.5);
    cloud->GetPointData()->Initialize();
    cases.push_back({ "no arrays", cloud, "no point-data array 'Radius'" });
  }
  {
    auto cloud = MakeCloud(16, 1.0, 0.1, 1.0, 0.5);
    cloud->GetPointData()->GetArray(Medium::AlbedoName())->SetComponent(0, 0, 1.5);
    cases.push_back({ "albedo 1.5", cloud, "'Albedo' of particle 0 is 1.5; it must be in [0, 1]" });
  }
  {
    auto cloud = MakeCloud(16, 1.0, 0.1, 1.0, 0.5);
    cloud->GetPointData()->AddArray(MakeArray(Medium::AnisotropyName(), 3, 16, 0.0));
    cases.push_back({ "3-component anisotropy", cloud, "'Anisotropy' has 3 components" });
  }
  cases.push_back({ "empty", vtkSmartPointer<vtkPolyData>::New(), "the particle set is empty" });
  for (const Case& c : cases)
  {
    vtkNew<vtkIlluminationNetwork> network;
    vtkNew<vtkTest::ErrorObserver> errors;
    network->AddObserver(vtkCommand::ErrorEvent, errors);
    network->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
    network->SetInputData(c.Cloud);
    network->Update();
    EXPECT_TRUE(errors->GetError()) << c.What;
    EXPECT_NE(errors->GetErrorMessage().find("Input 0"), std::string::npos) << c.What;
    EXPECT_NE(errors->GetErrorMessage().find(c.Expected), std::string::npos)
      << c.What << ": " << errors->GetErrorMessage();
    EXPECT_EQ(network->GetOutput()->GetNumberOfPoints(), 0) << c.What;
  }
}

// A million particles with D = 128: the network (about 6.6 GB) is refused before any allocation
// where the device cannot hold it, with the sizes in the message; the time to say so is measured.
TEST(IlluminationNetwork, MillionParticles)
{
  const vtkIdType n = 1000000;
  auto cloud = MakeCloud(n, 10.0, 0.05, 1.0, 0.9);
  vtkOpenCLContext* context = vtkOpenCLContext::GetDefault();
  ASSERT_TRUE(context->Initialize());
  const double bytes = vtkIlluminationNetwork::NetworkBytes(n, 128);
  const bool fits = n * 128.0 * 12 <= context->GetMaximumAllocationBytes() &&
    bytes <= 0.8 * context->GetGlobalMemoryBytes() && bytes <= 0.5 * context->GetHostMemoryBytes();
  if (fits)
  {
    GTEST_SKIP() << "this device holds a " << bytes / 1048576.0
                 << " MiB network; the long benchmark measures it";
  }
  vtkNew<vtkIlluminationNetwork> network;
  vtkNew<vtkTest::ErrorObserver> errors;
  network->AddObserver(vtkCommand::ErrorEvent, errors);
  network->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  network->SetInputData(cloud);
  const auto start = std::chrono::steady_clock::now();
  network->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("a million particles, D = 128: refused after %.3f s: %s\n", seconds,
    errors->GetErrorMessage().c_str());
  EXPECT_TRUE(errors->GetError());
  EXPECT_NE(
    errors->GetErrorMessage().find("1000000 particles and 128 directions needs"), std::string::npos)
    << errors->GetErrorMessage();
  EXPECT_EQ(network->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_LT(seconds, 5.0);
}

// The deposit marks its medium as particles, and the effect plan says that refraction does not
// apply to them (issue 14); a grid medium carries no such mark.
TEST(ParticleMediumDeposit, ThePlanSaysRefractionDoesNotApplyToParticles)
{
  vtkNew<vtkParticleMediumDeposit> deposit;
  deposit->SetInputData(MakeCloud(64, 1.0, 0.2, 5.0, 0.9));
  deposit->SetSampleDimensions(16, 16, 16);
  deposit->Update();
  vtkNew<vtkLight> sun;
  sun->SetPositional(false);
  sun->SetPosition(0, 0, 10);
  vtkNew<vtkSceneAnalysis> analysis;
  analysis->SetMedium(deposit->GetMediumOutput());
  analysis->AddLight(sun);
  ASSERT_TRUE(analysis->Analyze());
  EXPECT_EQ(analysis->GetNumberOfDepositedParticles(), 64);
  vtkNew<vtkEffectPlan> plan;
  plan->Decide(analysis);
  EXPECT_FALSE(plan->IsEnabled(vtkEffectPlan::REFRACTION));
  const std::string reason = plan->GetReason(vtkEffectPlan::REFRACTION);
  EXPECT_NE(reason.find("refraction does not apply to particles (64 deposited)"), std::string::npos)
    << reason;
  EXPECT_TRUE(plan->IsEnabled(vtkEffectPlan::SINGLE_SCATTERING));
  EXPECT_NE(analysis->GetSummary().find("64 particles deposited"), std::string::npos);

  vtkNew<vtkImageData> grid;
  grid->DeepCopy(deposit->GetMediumOutput());
  grid->GetFieldData()->RemoveArray(Medium::DepositedParticlesName());
  analysis->SetMedium(grid);
  ASSERT_TRUE(analysis->Analyze());
  EXPECT_EQ(analysis->GetNumberOfDepositedParticles(), 0);
  plan->Decide(analysis);
  EXPECT_EQ(
    std::string(plan->GetReason(vtkEffectPlan::REFRACTION)).find("particles"), std::string::npos);
}
