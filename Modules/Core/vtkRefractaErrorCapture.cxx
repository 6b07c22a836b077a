#include "vtkRefractaErrorCapture.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkRefractaErrorCapture);

//------------------------------------------------------------------------------
vtkRefractaErrorCapture::vtkRefractaErrorCapture() = default;

//------------------------------------------------------------------------------
vtkRefractaErrorCapture::~vtkRefractaErrorCapture()
{
  this->Release();
}

//------------------------------------------------------------------------------
void vtkRefractaErrorCapture::Observe(vtkAlgorithm* algorithm)
{
  this->Release();
  if (!algorithm)
  {
    return;
  }
  vtkNew<vtkCallbackCommand> capture;
  capture->SetCallback(&vtkRefractaErrorCapture::Capture);
  capture->SetClientData(this);
  this->AlgorithmTag = algorithm->AddObserver(vtkCommand::ErrorEvent, capture);
  vtkNew<vtkCallbackCommand> swallow;
  swallow->SetCallback(&vtkRefractaErrorCapture::Swallow);
  this->ExecutiveTag = algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, swallow);
  this->Observed = algorithm;
}

//------------------------------------------------------------------------------
void vtkRefractaErrorCapture::Release()
{
  if (this->Observed)
  {
    this->Observed->RemoveObserver(this->AlgorithmTag);
    this->Observed->GetExecutive()->RemoveObserver(this->ExecutiveTag);
    this->Observed = nullptr;
  }
}

//------------------------------------------------------------------------------
void vtkRefractaErrorCapture::Capture(vtkObject*, unsigned long, void* self, void* callData)
{
  // vtkErrorMacro's event text is "ERROR: In <file>, line <n>\n<class> (<address>): <message>":
  // keep the message.
  std::string text = callData ? static_cast<const char*>(callData) : "";
  const size_t header = text.find("): ");
  if (text.compare(0, 6, "ERROR:") == 0 && header != std::string::npos)
  {
    text = text.substr(header + 3);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
  {
    text.pop_back();
  }
  static_cast<vtkRefractaErrorCapture*>(self)->Text = text;
}

//------------------------------------------------------------------------------
void vtkRefractaErrorCapture::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Observed: " << this->Observed.GetPointer() << "\n";
  os << indent << "Text: " << this->Text << "\n";
}
