// main() for a fuzz target built without libFuzzer: runs LLVMFuzzerTestOneInput on every file
// named on the command line and on every file in every folder named there (not recursive),
// printing each file's name first so that a crash names its input.
#include "FuzzSupport.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;

int main(int argc, char* argv[])
{
  std::vector<fs::path> files;
  for (int a = 1; a < argc; ++a)
  {
    const fs::path path = argv[a];
    if (fs::is_directory(path))
    {
      for (const auto& entry : fs::directory_iterator(path))
      {
        if (entry.is_regular_file())
        {
          files.push_back(entry.path());
        }
      }
    }
    else if (fs::is_regular_file(path))
    {
      files.push_back(path);
    }
    else
    {
      std::cerr << "fuzz replay: '" << path.string() << "' is neither a file nor a folder\n";
      return 2;
    }
  }
  if (files.empty())
  {
    std::cerr << "fuzz replay: no input files (give corpus files or folders)\n";
    return 2;
  }
  std::sort(files.begin(), files.end());
  for (const auto& file : files)
  {
    std::cout << "replaying " << file.filename().string() << std::endl;
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes(
      (std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  std::cout << "replayed " << files.size() << " inputs without a crash" << std::endl;
  return 0;
}
