/**
 * @class   vtkOpenCLBinaryCache
 * @brief   The on-disk cache of compiled OpenCL programs: checked entries, atomic writes.
 *
 * vtkOpenCLContext keeps one. An entry is one file, `<16 hex digits>.clbin` (the FNV-1a hash of
 * the key: source, options, Refracta version, platform, device and driver), holding
 * - a header: the magic "RFCLBIN1", the full key's hash and length, the payload's size and its
 *   FNV-1a checksum (64-bit, little-endian on the machine that wrote it);
 * - the payload: the device binary.
 * Load() accepts an entry only if every header field matches; a file too short (truncated), with
 * another magic or key (foreign: another program, another version, a hash collision) or a payload
 * whose size or checksum differs (corrupt) is rejected, counted and deleted, and the caller
 * rebuilds and stores the entry again.
 *
 * Store() writes `<entry>.tmp.<pid>.<n>` in the same folder and renames it over the entry:
 * rename is atomic within a file system, so concurrent processes writing the same entry never
 * leave a mixed file and a reader sees the old entry, the new one or none.
 *
 * A folder that cannot be created or written disables the disk cache (until another folder is
 * set); GetDisabledReason() then names the folder and the reason, for the owner's one warning.
 * Compiling from source goes on as without a cache.
 */
#ifndef vtkOpenCLBinaryCache_h
#define vtkOpenCLBinaryCache_h

#include "RefractaOpenCLModule.h" // for export macro
#include "vtkObject.h"

#include <cstdint> // for std::uint64_t
#include <string>  // for std::string
#include <vector>  // for std::vector

class REFRACTAOPENCL_EXPORT vtkOpenCLBinaryCache : public vtkObject
{
public:
  static vtkOpenCLBinaryCache* New();
  vtkTypeMacro(vtkOpenCLBinaryCache, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Folder of the entries; empty (default) disables the cache. Setting another folder enables
   * the cache again after a failed write.
   */
  void SetDirectory(const std::string& directory);
  const std::string& GetDirectory() const { return this->Directory; }
  ///@}

  /**
   * What Load() found.
   */
  enum LoadResult
  {
    MISSING = 0,  ///< no entry (or the cache is disabled)
    LOADED = 1,   ///< the payload was read and checked
    REJECTED = 2, ///< an entry existed but was truncated, corrupt or foreign; it was deleted
  };

  /**
   * Read the entry of `key` into `payload`. On REJECTED, `why` (if given) says what was wrong.
   */
  int Load(const std::string& key, std::vector<unsigned char>& payload, std::string* why = nullptr);

  /**
   * Write the entry of `key` atomically. Returns false when nothing was written; a failure to
   * create or write the folder disables the cache (GetDisabledReason()).
   */
  bool Store(const std::string& key, const std::vector<unsigned char>& payload);

  /**
   * Delete the entry of `key` (e.g. when the driver refuses a binary that passed the checks).
   */
  void Remove(const std::string& key);

  /**
   * Path of the entry of `key` (empty when the cache has no folder).
   */
  std::string GetEntryPath(const std::string& key) const;

  /**
   * True while the folder is set and no write has failed.
   */
  bool IsEnabled() const { return !this->Directory.empty() && this->DisabledReason.empty(); }

  /**
   * Why a failed write disabled the cache (folder and reason), or empty.
   */
  const std::string& GetDisabledReason() const { return this->DisabledReason; }

  ///@{
  /**
   * Counters since creation: entries loaded, rejected (and deleted), stored.
   */
  vtkGetMacro(NumberOfLoadedEntries, int);
  vtkGetMacro(NumberOfRejectedEntries, int);
  vtkGetMacro(NumberOfStoredEntries, int);
  ///@}

  /**
   * 64-bit FNV-1a of `size` bytes: stable across processes and platforms.
   */
  static std::uint64_t Checksum(const void* data, size_t size);

protected:
  vtkOpenCLBinaryCache() = default;
  ~vtkOpenCLBinaryCache() override = default;

  void Disable(const std::string& reason);

  std::string Directory;
  std::string DisabledReason;
  int NumberOfLoadedEntries = 0;
  int NumberOfRejectedEntries = 0;
  int NumberOfStoredEntries = 0;

private:
  vtkOpenCLBinaryCache(const vtkOpenCLBinaryCache&) = delete;
  void operator=(const vtkOpenCLBinaryCache&) = delete;
};

#endif
