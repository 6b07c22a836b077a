/**
 * @class   vtkRefractaErrorCapture
 * @brief   Holds the text of an inner algorithm's last error so that its owner can say it once,
 *          in its own words.
 *
 * A front end that runs a filter of its own (the mapper's transfer-function mapping,
 * refracta-render's voxelizer) wants the filter's message, not the two lines VTK prints for it:
 * the filter's own error and its executive's "returned failure for request" with a dump of the
 * request. Observe() adds ErrorEvent observers to the algorithm and to its executive: the
 * algorithm's text is kept (without VTK's "ERROR: In file, line N / class (address): " header),
 * the executive's is swallowed, and neither is printed. The owner reports GetText() where it
 * decides to (vtkErrorMacro, an exception, its own ErrorEvent).
 */
#ifndef vtkRefractaErrorCapture_h
#define vtkRefractaErrorCapture_h

#include "RefractaCoreModule.h" // for export macro
#include "vtkAlgorithm.h"       // for vtkWeakPointer<vtkAlgorithm>
#include "vtkObject.h"
#include "vtkWeakPointer.h" // for Observed

#include <string> // for std::string

class REFRACTACORE_EXPORT vtkRefractaErrorCapture : public vtkObject
{
public:
  static vtkRefractaErrorCapture* New();
  vtkTypeMacro(vtkRefractaErrorCapture, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Captures `algorithm`'s errors (and silences its executive's) from now on. An algorithm may
   * be observed by one capture at a time; observing another releases the previous one.
   */
  void Observe(vtkAlgorithm* algorithm);

  /**
   * The last captured error's text, empty when none since Clear().
   */
  const std::string& GetText() const { return this->Text; }
  bool HasError() const { return !this->Text.empty(); }

  /**
   * Forgets the captured text (before a new Update()).
   */
  void Clear() { this->Text.clear(); }

protected:
  vtkRefractaErrorCapture();
  ~vtkRefractaErrorCapture() override;

private:
  vtkRefractaErrorCapture(const vtkRefractaErrorCapture&) = delete;
  void operator=(const vtkRefractaErrorCapture&) = delete;

  static void Capture(vtkObject*, unsigned long, void* self, void* callData);
  static void Swallow(vtkObject*, unsigned long, void*, void*) {}
  void Release();

  std::string Text;
  vtkWeakPointer<vtkAlgorithm> Observed; // not owned: either may go first
  unsigned long AlgorithmTag = 0;
  unsigned long ExecutiveTag = 0;
};

#endif
