// Strict access to a refracta-render scene (JSON): every key must be known, every value checked;
// errors are SceneErrors that name the key path ("scene.image.width: ...").
#ifndef RefractaSceneJson_h
#define RefractaSceneJson_h

#include <nlohmann/json.hpp>

#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace RefractaRender
{
using json = nlohmann::ordered_json;

/// A scene that cannot be rendered as written; what() is "PATH: what is wrong".
struct SceneError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Whether `v` is an integer: written as one (96) or as a number with no fractional part (96.0).
bool IsInteger(const json& v);

/// Throws SceneError("PATH: WHAT").
[[noreturn]] void Fail(const std::string& path, const std::string& what);

/// Fails unless `object` is an object whose keys are all in `allowed`.
void CheckKeys(const json& object, const std::string& path, const std::set<std::string>& allowed);

/// object[key] as a number in [lo, hi], or `fallback` where the key is absent.
double Number(const json& object, const std::string& key, const std::string& path, double fallback,
  double lo, double hi);

/// object[key] as an integer in [lo, hi], or `fallback` where the key is absent.
int Integer(const json& object, const std::string& key, const std::string& path, int fallback,
  int lo, int hi);

/// object[key] as an array of `size` numbers in [lo, hi], or `fallback` where the key is absent.
std::vector<double> Vector(const json& object, const std::string& key, const std::string& path,
  std::vector<double> fallback, size_t size, double lo, double hi);

/// object[key] as an array of `size` integers in [lo, hi], or `fallback` where the key is absent
/// (a fractional entry is an error, not truncated).
std::vector<int> IntegerVector(const json& object, const std::string& key, const std::string& path,
  std::vector<int> fallback, size_t size, int lo, int hi);

/// object[key] as bounds (xmin, xmax, ymin, ymax, zmin, zmax), every min below its max; empty
/// where the key is absent.
std::vector<double> Bounds(const json& object, const std::string& key, const std::string& path);

/// object[key] as a string (one of `choices` unless that is empty), or `fallback`.
std::string String(const json& object, const std::string& key, const std::string& path,
  const std::string& fallback, const std::set<std::string>& choices = {});

/// object[key] as true or false, or `fallback` where the key is absent.
bool Boolean(const json& object, const std::string& key, const std::string& path, bool fallback);

/// A string option and the value it stands for (an enum of a VTK class).
template <typename T>
using ChoiceTable = std::vector<std::pair<std::string, T>>;

/// A string option read with String() against the names of `table`: the name and its value.
template <typename T>
std::pair<std::string, T> Choice(const json& object, const std::string& key,
  const std::string& path, const std::string& fallback, const ChoiceTable<T>& table)
{
  std::set<std::string> names;
  for (const auto& entry : table)
  {
    names.insert(entry.first);
  }
  const std::string name = String(object, key, path, fallback, names);
  for (const auto& entry : table)
  {
    if (entry.first == name)
    {
      return entry;
    }
  }
  throw std::logic_error(path + "." + key + ": the fallback '" + fallback + "' is not a choice");
}
}

#endif
