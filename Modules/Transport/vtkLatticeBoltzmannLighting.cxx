#include "vtkLatticeBoltzmannLighting.h"

#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkLatticeBoltzmannSolver.h"
#include "vtkMediumValidator.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenCLContext.h"
#include "vtkPointData.h"
#include "vtkRefractaGridFrame.h"
#include "vtkRefractaLightingVolume.h"
#include "vtkRefractaMedium.h"
#include "vtkRefractaSettings.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkLatticeBoltzmannLighting);
vtkRefractaCxxSetClampMacro(vtkLatticeBoltzmannLighting, Tolerance, 0.0, 1.0);

namespace
{
// Why `array` is not `tuples` x 3 finite values >= 0 (power per unit volume), or "" if it is.
std::string CheckPowerArray(vtkDataArray* array, vtkIdType tuples)
{
  if (!array)
  {
    return "it has none";
  }
  if (array->GetNumberOfComponents() != 3 || array->GetNumberOfTuples() != tuples)
  {
    return "it has one with " + std::to_string(array->GetNumberOfComponents()) +
      " components and " + std::to_string(array->GetNumberOfTuples()) + " tuples";
  }
  for (vtkIdType t = 0; t < tuples; ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double value = array->GetComponent(t, c);
      if (!std::isfinite(value) || value < 0)
      {
        return "tuple " + std::to_string(t) + " component " + std::to_string(c) + " is " +
          std::to_string(value);
      }
    }
  }
  return "";
}

// Forwards the solver's progress to the filter (scaled into [First, Last]) and the filter's
// AbortExecute to the solver.
class ProgressForwarder : public vtkCommand
{
public:
  static ProgressForwarder* New() { return new ProgressForwarder; }
  void Execute(vtkObject* caller, unsigned long, void* data) override
  {
    const double p = *static_cast<double*>(data);
    this->Filter->UpdateProgress(this->First + (this->Last - this->First) * p);
    if (this->Filter->GetAbortExecute())
    {
      static_cast<vtkLatticeBoltzmannSolver*>(caller)->SetAbortSolve(true);
    }
  }
  vtkAlgorithm* Filter = nullptr;
  double First = 0.0;
  double Last = 1.0;
};
}

//------------------------------------------------------------------------------
vtkLatticeBoltzmannLighting::vtkLatticeBoltzmannLighting()
{
  this->SetNumberOfInputPorts(3);
}
vtkLatticeBoltzmannLighting::~vtkLatticeBoltzmannLighting() = default;

//------------------------------------------------------------------------------
void vtkLatticeBoltzmannLighting::SetContext(vtkOpenCLContext* context)
{
  if (this->Context != context)
  {
    this->Context = context;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkLatticeBoltzmannLighting::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  if (port == 2)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkLatticeBoltzmannLighting::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The output lives on the medium's grid.
  vtkInformation* in = inputVector[0]->GetInformationObject(0);
  vtkInformation* out = outputVector->GetInformationObject(0);
  if (in && in->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    out->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(),
      in->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkLatticeBoltzmannLighting::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* medium = vtkImageData::GetData(inputVector[0]);
  vtkImageData* lighting = vtkImageData::GetData(inputVector[1]);
  vtkImageData* orders = inputVector[2]->GetNumberOfInformationObjects() > 0
    ? vtkImageData::GetData(inputVector[2])
    : nullptr;
  vtkImageData* output = vtkImageData::GetData(outputVector);
  output->Initialize();
  this->LastRunAborted = false;
  if (this->GetAbortExecute())
  {
    // Aborted before the solve began (e.g. while the pass upstream ran, which then left its
    // output empty): an abort, not bad input.
    this->LastRunAborted = true;
    return 1;
  }

  vtkNew<vtkMediumValidator> validator;
  if (!validator->Validate(medium))
  {
    vtkErrorMacro("Input 0 is not a valid medium: " << validator->GetErrorMessage());
    return 0;
  }
  if (!lighting)
  {
    vtkErrorMacro("Input 1 (the lighting volume with `Radiance`, from the photon pass) is "
                  "missing: connect it with SetLightingConnection().");
    return 0;
  }
  for (vtkImageData* image : { lighting, orders })
  {
    if (image && !vtkRefractaGridFrame::SameGrid(image, medium))
    {
      vtkErrorMacro("Input " << (image == lighting ? 1 : 2) << " ("
                             << (image == lighting ? "lighting volume" : "photon orders")
                             << ") has " << vtkRefractaGridFrame::DescribeGrid(image)
                             << "; it must be on the medium's grid ("
                             << vtkRefractaGridFrame::DescribeGrid(medium) << ").");
      return 0;
    }
  }
  const vtkIdType n = medium->GetNumberOfPoints();
  // The source: S1 (`Radiance`), or with the first-collision split the light the photons handed
  // on (`MultipleScatteringSource`, of the lighting volume or of the photon orders on port 2),
  // whose S_ms (orders up to k) the lattice's is added to. Photon orders without a source carried
  // every order: their S_ms is the whole of it and the lattice has nothing to do.
  // Photon orders with neither carried nothing (their medium did not scatter): ignored.
  if (orders &&
    !orders->GetPointData()->GetArray(vtkRefractaLightingVolume::MultipleScatteringName()))
  {
    orders = nullptr;
  }
  vtkImageData* photons = orders ? orders : lighting;
  const bool split = vtkRefractaLightingVolume::HasPhotonMultipleScattering(photons);
  const bool everyOrder = orders && !split;
  struct Required
  {
    vtkImageData* Image;
    const char* Name;
  };
  std::vector<Required> required = { { lighting, vtkRefractaLightingVolume::RadianceName() } };
  if (split)
  {
    required.push_back({ photons, vtkRefractaLightingVolume::MultipleScatteringSourceName() });
  }
  if (split || everyOrder)
  {
    required.push_back({ photons, vtkRefractaLightingVolume::MultipleScatteringName() });
  }
  for (const Required& r : required)
  {
    const std::string problem = CheckPowerArray(r.Image->GetPointData()->GetArray(r.Name), n);
    if (!problem.empty())
    {
      vtkErrorMacro(
        "Input " << (r.Image == lighting ? "1 (lighting volume)" : "2 (photon orders)")
                 << " needs a point array `" << r.Name << "` with 3 components and " << n
                 << " tuples of power per unit volume, finite and >= 0: " << problem << ".");
      return 0;
    }
  }
  vtkDataArray* direction =
    lighting->GetPointData()->GetArray(vtkRefractaLightingVolume::RadianceDirectionName());
  vtkDataArray* sourceDirection = photons->GetPointData()->GetArray(
    vtkRefractaLightingVolume::LatticeSourceDirectionName(photons));
  vtkDataArray* photonDirection =
    photons->GetPointData()->GetArray(vtkRefractaLightingVolume::MultipleScatteringDirectionName());
  for (vtkDataArray* d : { direction, sourceDirection, photonDirection })
  {
    if (d && (d->GetNumberOfComponents() != 3 || d->GetNumberOfTuples() != n))
    {
      vtkErrorMacro("Input " << (d == direction ? 1 : 2) << ": `" << d->GetName()
                             << "` must have 3 components and " << n << " tuples.");
      return 0;
    }
  }

  vtkNew<vtkFloatArray> ms;
  ms->SetName(vtkRefractaLightingVolume::MultipleScatteringName());
  ms->SetNumberOfComponents(3);
  ms->SetNumberOfTuples(n);
  vtkNew<vtkLatticeBoltzmannSolver> solver;
  if (everyOrder)
  {
    ms->FillValue(0.0f); // the photons carried every order: nothing is left for the lattice
  }
  else
  {
    const int solved = this->Solve(solver, medium, photons, ms,
      split ? photons->GetPointData()->GetArray(vtkRefractaLightingVolume::MultipleScatteringName())
            : nullptr);
    if (solved <= 0)
    {
      output->Initialize();
      this->LastRunAborted = solved == 0;
      return solved == 0 ? 1 : 0;
    }
  }
  // The direction of the light S_ms scatters: the photons' where they carried every order, else
  // the lattice's own flux (with the split merged with the photons' orders').
  vtkSmartPointer<vtkDataArray> msDirection;
  if (everyOrder)
  {
    vtkRefractaLightingVolume::AddPhotonMultipleScattering(photons, ms);
    msDirection = photonDirection;
  }
  else
  {
    vtkNew<vtkFloatArray> flux;
    flux->SetName(vtkRefractaLightingVolume::MultipleScatteringDirectionName());
    if (!solver->ComputeMultipleScatteringDirection(
          flux, split ? ms.GetPointer() : nullptr, split ? photons : nullptr))
    {
      output->Initialize();
      return 0;
    }
    msDirection = flux;
  }

  output->CopyStructure(medium);
  vtkRefractaLightingVolume::PassSingleScattering(lighting, output);
  output->GetPointData()->AddArray(ms);
  if (msDirection)
  {
    output->GetPointData()->AddArray(msDirection);
  }
  output->GetFieldData()->PassData(lighting->GetFieldData());
  vtkNew<vtkIntArray> iterations;
  iterations->SetName("LatticeBoltzmannIterations");
  iterations->InsertNextValue(everyOrder ? 0 : solver->GetIterations());
  vtkNew<vtkDoubleArray> residual;
  residual->SetName("LatticeBoltzmannResidual");
  residual->InsertNextValue(everyOrder ? 0.0 : solver->GetResidual());
  vtkNew<vtkIntArray> converged;
  converged->SetName("LatticeBoltzmannConverged");
  converged->InsertNextValue(everyOrder || solver->GetConverged() ? 1 : 0);
  output->GetFieldData()->AddArray(iterations);
  output->GetFieldData()->AddArray(residual);
  output->GetFieldData()->AddArray(converged);
  return 1;
}

//------------------------------------------------------------------------------
int vtkLatticeBoltzmannLighting::Solve(vtkLatticeBoltzmannSolver* solver, vtkImageData* medium,
  vtkImageData* sources, vtkFloatArray* ms, vtkDataArray* addend)
{
  if (this->Context)
  {
    solver->SetContext(this->Context);
  }
  solver->SetLattice(this->Lattice == 18 ? 18 : 6);
  solver->SetBlockSize(this->BlockSize);
  solver->SetStepsPerExchange(this->StepsPerExchange);
  solver->SetBoundary(this->Boundary);
  solver->SetSourceDistribution(this->SourceDistribution);
  solver->SetCollisionModel(this->CollisionModel);
  solver->SetTolerance(this->Tolerance);
  solver->SetCheckInterval(this->CheckInterval);
  solver->SetProbeSpacing(this->ProbeSpacing);
  solver->SetMaximumIterations(this->MaximumIterations);
  solver->SetKeepDeviceCopies(this->KeepDeviceCopies);
  vtkNew<ProgressForwarder> forwarder;
  forwarder->Filter = this;
  // The solve is nearly all the work; reading the arrays and the final pass share the rest.
  forwarder->First = 0.02;
  forwarder->Last = 0.98;
  solver->AddObserver(vtkCommand::ProgressEvent, forwarder);

  int dims[3];
  double spacing[3];
  medium->GetDimensions(dims);
  medium->GetSpacing(spacing);
  const std::vector<float> extinction =
    vtkRefractaMedium::ReadArray(medium, vtkRefractaMedium::ExtinctionName(), 3, 0.0f);
  const std::vector<float> albedo =
    vtkRefractaMedium::ReadArray(medium, vtkRefractaMedium::AlbedoName(), 3, 0.0f);
  const std::vector<float> anisotropy =
    vtkRefractaMedium::ReadArray(medium, vtkRefractaMedium::AnisotropyName(), 1, 0.0f);
  if (!solver->Initialize(dims, spacing, extinction.data(), albedo.data(), anisotropy.data()) ||
    !solver->SetSourceFromLighting(sources) || !solver->Solve())
  {
    vtkErrorMacro("The Lattice-Boltzmann solver failed (see the previous message).");
    return -1;
  }
  if (solver->GetAborted() || this->GetAbortExecute())
  {
    // An abort is not an error: empty output, the solver and its buffers go with `solver`.
    return 0;
  }
  return solver->ComputeMultipleScattering(ms, addend) ? 1 : -1;
}

//------------------------------------------------------------------------------
void vtkLatticeBoltzmannLighting::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Lattice: D3Q" << this->Lattice << "\n";
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "StepsPerExchange: " << this->StepsPerExchange << "\n";
  os << indent << "Boundary: " << this->Boundary << "\n";
  os << indent << "SourceDistribution: " << this->SourceDistribution << "\n";
  os << indent << "CollisionModel: " << this->CollisionModel << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
  os << indent << "KeepDeviceCopies: " << this->KeepDeviceCopies << "\n";
  os << indent << "CheckInterval: " << this->CheckInterval << "\n";
  os << indent << "ProbeSpacing: " << this->ProbeSpacing << "\n";
  os << indent << "MaximumIterations: " << this->MaximumIterations << "\n";
  os << indent << "LastRunAborted: " << this->LastRunAborted << "\n";
}
