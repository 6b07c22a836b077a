// What Refracta's fuzz targets share: reading structured values from the fuzzer's bytes, a quiet
// VTK output window that counts the errors reported, and the check that turns a broken contract
// into a crash that libFuzzer (or the corpus replay) reports.
//
// Every target defines LLVMFuzzerTestOneInput(). Built with REFRACTA_FUZZ (clang, libFuzzer,
// ASan, UBSan) it is a fuzzer; otherwise FuzzReplayMain.cxx gives it a main() that replays the
// seed corpus, so the default suite runs every stored input on every build.
#ifndef FuzzSupport_h
#define FuzzSupport_h

#include <cstddef>
#include <cstdint>
#include <string>

class vtkImageData;

namespace refracta_fuzz
{
/**
 * The fuzzer's bytes read front to back as small structured values. Past the end every read
 * returns zero (or the lowest allowed value), so every input decodes to something.
 */
class FuzzBytes
{
public:
  FuzzBytes(const uint8_t* data, size_t size)
    : Data(data)
    , Size(size)
  {
  }

  /// The next byte (0 past the end).
  uint8_t Byte();

  /// An integer in [lo, hi] (lo past the end).
  int Int(int lo, int hi);

  /// True or false (false past the end).
  bool Bool() { return (this->Byte() & 1) != 0; }

  /**
   * A double that is mostly ordinary and often hostile: the first byte picks a small lattice
   * value ((b - 128) / 16), one of a table of edge values (+-0, denormals, 1e30, DBL_MAX, NaN,
   * +-Inf, FLT_MAX, ...), or the raw bits of a double or float.
   */
  double Double();

  /// A lattice value in [-8, 8] with step 1/16 (coincident and coplanar points are common).
  double Lattice() { return (static_cast<int>(this->Byte()) - 128) / 16.0; }

  size_t Remaining() const { return this->Pos < this->Size ? this->Size - this->Pos : 0; }

private:
  const uint8_t* Data;
  size_t Size;
  size_t Pos = 0;
};

/**
 * Silences VTK's output for a fuzz run and counts its error messages (warnings are dropped).
 * Set REFRACTA_FUZZ_VERBOSE=1 to print every message. Call once; idempotent.
 */
void InstallQuietOutput();

/// Prints `text` (and a new line) to stderr when REFRACTA_FUZZ_VERBOSE is set.
void Print(const std::string& text);

/// Error messages VTK reported since the last ResetErrorCount().
int GetErrorCount();
void ResetErrorCount();

/// The text of the last VTK error message (empty when none).
const std::string& GetLastError();

/**
 * Aborts (a crash libFuzzer records, with the input) when `condition` is false: the code under
 * test broke its contract, e.g. produced an invalid medium or failed without saying why.
 */
void Require(bool condition, const char* what);

/**
 * True when `image` passes vtkMediumValidator; otherwise prints the validator's message (so a
 * crash report says which array is wrong).
 */
bool IsValidMedium(vtkImageData* image);
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

#endif
